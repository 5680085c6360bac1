#include "effects/lighting/PbrShading.h"

#include "environment/Environment.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace obscura::pbr {

glm::dvec3 SurfaceParameters::diffuseColor() const { return base * (1.0 - std::clamp(metallic, 0.0, 1.0)); }
glm::dvec3 SurfaceParameters::f0() const {
  const double m = std::clamp(metallic, 0.0, 1.0);
  const double r = (ior - 1.0) / (ior + 1.0);
  const glm::dvec3 dielectric = glm::min(glm::dvec3(r * r) * specularColor, glm::dvec3(1.0)) * specular;
  return dielectric * (1.0 - m) + base * m;
}
glm::dvec3 SurfaceParameters::f90() const {
  const double m = std::clamp(metallic, 0.0, 1.0);
  return glm::dvec3(specular * (1.0 - m) + m);
}
double SurfaceParameters::clampedRoughness() const { return std::clamp(roughness, kMinRoughness, 1.0); }

double distributionGgx(double nh, double alpha) {
  const double a2 = alpha * alpha;
  const double d = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d);
}

double visibilitySmithGgx(double nl, double nv, double alpha) {
  const double a2 = alpha * alpha;
  const double v = nl * std::sqrt(nv * nv * (1.0 - a2) + a2);
  const double l = nv * std::sqrt(nl * nl * (1.0 - a2) + a2);
  return v + l > 0.0 ? 0.5 / (v + l) : 0.0;
}

glm::dvec3 fresnelSchlick(const glm::dvec3& f0, const glm::dvec3& f90, double vh) {
  return f0 + (f90 - f0) * std::pow(1.0 - vh, 5.0);
}

glm::dvec3 brdfCosine(const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l, const SurfaceParameters& s) {
  const double nl = glm::dot(n, l);
  if (nl <= 0.0) return glm::dvec3(0.0);
  const double nv = std::max(glm::dot(n, v), 1e-4);
  const glm::dvec3 h = glm::normalize(l + v);
  const double nh = std::max(glm::dot(n, h), 0.0), vh = std::max(glm::dot(v, h), 0.0);
  const double roughness = s.clampedRoughness();
  const double alpha = roughness * roughness;
  const glm::dvec3 f = fresnelSchlick(s.f0(), s.f90(), vh);
  const glm::dvec3 specular = f * (distributionGgx(nh, alpha) * visibilitySmithGgx(nl, nv, alpha));
  const glm::dvec3 diffuse = (glm::dvec3(1.0) - f) * s.diffuseColor() / kPi;
  return (diffuse + specular) * nl;
}

double punctualFalloff(double distance, double range) {
  const double d2 = std::max(distance * distance, 1e-8);
  if (range <= 0.0) return 1.0 / d2;
  const double window = std::clamp(1.0 - std::pow(distance / range, 4.0), 0.0, 1.0);
  return window * window / d2;
}

double spotCone(double cosAngle, double innerConeAngle, double outerConeAngle) {
  const double cosOuter = std::cos(outerConeAngle), cosInner = std::cos(innerConeAngle);
  const double scale = 1.0 / std::max(cosInner - cosOuter, 0.001);
  const double t = std::clamp(cosAngle * scale - cosOuter * scale, 0.0, 1.0);
  return t * t;
}

double specularOcclusion(double nv, double ao, double alpha) {
  return std::clamp(std::pow(nv + ao, std::exp2(-16.0 * alpha - 1.0)) - 1.0 + ao, 0.0, 1.0);
}

glm::dvec3 ambientLight(const glm::dvec3& radiance, const glm::dvec3& n, const glm::dvec3& v,
                        const SurfaceParameters& s, double occlusion) {
  const double nv = std::clamp(glm::dot(n, v), 1e-4, 1.0);
  const double roughness = s.clampedRoughness(), alpha = roughness * roughness;
  const glm::vec2 scaleBias = environmentBrdf(static_cast<float>(roughness), static_cast<float>(nv));
  const glm::dvec3 specularAlbedo = s.f0() * double(scaleBias.x) + s.f90() * double(scaleBias.y);
  const glm::dvec3 diffuse = s.diffuseColor() * (1.0 - specularAlbedo) * radiance;
  const glm::dvec3 specular = specularAlbedo * radiance;
  return diffuse * occlusion + specular * specularOcclusion(nv, occlusion, alpha);
}

glm::dvec3 coated(const glm::dvec3& beneath, const glm::dvec3& radiance, const glm::dvec3& n, const glm::dvec3& v,
                  const glm::dvec3& l, const glm::dvec3& illuminance, const SurfaceParameters& s, double occlusion) {
  if (s.clearcoat <= 0.0) return beneath;
  // The coat: a dielectric of ior 1.5 (F0 0.04), no diffuse, its own roughness (Khronos sample viewer).
  SurfaceParameters coat;
  coat.base = glm::dvec3(0.0);
  coat.metallic = 0.0;
  coat.roughness = s.clearcoatRoughness;
  const double nv = std::clamp(glm::dot(n, v), 1e-4, 1.0);
  const double roughness = coat.clampedRoughness();
  const glm::vec2 scaleBias = environmentBrdf(static_cast<float>(roughness), static_cast<float>(nv));
  const glm::dvec3 layer = glm::dvec3(0.04 * double(scaleBias.x) + double(scaleBias.y)) * radiance *
                               specularOcclusion(nv, occlusion, roughness * roughness) +
                           brdfCosine(n, v, l, coat) * illuminance;
  const glm::dvec3 fresnel = fresnelSchlick(glm::dvec3(0.04), glm::dvec3(1.0), nv);
  return beneath * (1.0 - s.clearcoat * fresnel) + s.clearcoat * layer;
}

}  // namespace obscura::pbr
