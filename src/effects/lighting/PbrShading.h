#pragma once
// The CPU mirror of the lighting pass's shading (shaders_es2/lib/pbr.glsl and lighting.frag's shade and
// ambientLight), in plain C++ and double precision: the glTF 2.0 metallic-roughness BRDF (Appendix B: GGX
// distribution, height-correlated Smith visibility, Schlick Fresnel, Lambertian diffuse weighted by 1 - F), the
// KHR_lights_punctual falloff and cone, and the ambient's environment BRDF and specular occlusion. tests/test_pbr.cpp
// holds the GPU to it at sample angles and checks it against the equations integrated numerically.
#include <glm/vec3.hpp>

namespace obscura::pbr {

constexpr double kPi = 3.14159265358979323846;

struct SurfaceParameters {
  glm::dvec3 base{1.0};
  double metallic = 0.0;
  double roughness = 1.0;  // perceptual; alpha = roughness^2 (clamped to kMinRoughness as the shader does)
  // KHR_materials_ior and _specular (glTF's defaults give the core material's 0.04 and 1).
  double ior = 1.5;
  double specular = 1.0;
  glm::dvec3 specularColor{1.0};
  // KHR_materials_clearcoat: the coat's strength and perceptual roughness (0: no coat).
  double clearcoat = 0.0;
  double clearcoatRoughness = 0.0;

  glm::dvec3 diffuseColor() const;  // base (1 - metallic)
  // The dielectric's F0, min(((ior - 1) / (ior + 1))^2 specularColor, 1) specular, and F90, specular; mixed towards
  // a metal's (base, 1) by metallic.
  glm::dvec3 f0() const;
  glm::dvec3 f90() const;
  double clampedRoughness() const;
};
constexpr double kMinRoughness = 0.089;  // PBR_MIN_ROUGHNESS

double distributionGgx(double nh, double alpha);
double visibilitySmithGgx(double nl, double nv, double alpha);  // G / (4 NL NV), height-correlated
glm::dvec3 fresnelSchlick(const glm::dvec3& f0, const glm::dvec3& f90, double vh);
// f(l, v) NL for unit n, v, l: what a light's illuminance multiplies.
glm::dvec3 brdfCosine(const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l, const SurfaceParameters& s);

// KHR_lights_punctual: the illuminance factor at distance d (inverse square times the range window; range 0: none)
// and the spot's cone attenuation at cos(angle from its axis).
double punctualFalloff(double distance, double range);
double spotCone(double cosAngle, double innerConeAngle, double outerConeAngle);

// Lagarde's specular occlusion.
double specularOcclusion(double nv, double ao, double alpha);

// lighting.frag's ambientLight under a uniform environment of this radiance (lighting.environment uniform, times its
// intensity), where the SH irradiance / pi and the prefiltered radiance are that radiance at every roughness: the
// split sum's scale and bias from the table the GPU reads (environment/Environment.h's environmentBrdf).
glm::dvec3 ambientLight(const glm::dvec3& radiance, const glm::dvec3& n, const glm::dvec3& v,
                        const SurfaceParameters& s, double occlusion);

// lighting.frag's coated: the lit colour `beneath` (ambientLight + the lights' brdfCosine) under the clear coat of
// s, lit by a uniform environment of this radiance and one light of illuminance E from l (the sun).
glm::dvec3 coated(const glm::dvec3& beneath, const glm::dvec3& radiance, const glm::dvec3& n, const glm::dvec3& v,
                  const glm::dvec3& l, const glm::dvec3& illuminance, const SurfaceParameters& s, double occlusion);

}  // namespace obscura::pbr
