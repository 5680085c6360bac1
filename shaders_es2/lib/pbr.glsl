// glTF 2.0 metallic-roughness shading (glTF 2.0 spec, Appendix B "BRDF Implementation"): a Cook-Torrance specular
// lobe with the GGX / Trowbridge-Reitz distribution D, the height-correlated Smith visibility V (G / (4 NL NV)) and
// Schlick's Fresnel F, over a Lambertian diffuse lobe weighted by (1 - F):
//   f = (1 - F) c_diff / pi + F D V,   c_diff = mix(base, 0, metallic),   F0 = mix(0.04, base, metallic),
//   alpha = roughness^2.
// A light of illuminance E (perpendicular to it) adds f E NL. CPU mirror: effects/lighting/PbrShading.h
// (tests/test_pbr.cpp compares the two at sample angles).
#ifndef PBR_GLSL
#define PBR_GLSL

const float PBR_PI = 3.14159265;
// alpha below which mediump would flush alpha^2 to zero (Filament's MIN_PERCEPTUAL_ROUGHNESS for mediump).
const float PBR_MIN_ROUGHNESS = 0.089;

float distributionGgx(float nh, float alpha) {
  float a2 = alpha * alpha;
  float d = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (PBR_PI * d * d);
}

// Height-correlated Smith for GGX (Heitz 2014, eq. 99), already divided by 4 NL NV.
float visibilitySmithGgx(float nl, float nv, float alpha) {
  float a2 = alpha * alpha;
  float v = nl * sqrt(nv * nv * (1.0 - a2) + a2);
  float l = nv * sqrt(nl * nl * (1.0 - a2) + a2);
  float sum = v + l;
  return sum > 0.0 ? 0.5 / sum : 0.0;
}

vec3 fresnelSchlick(vec3 f0, float vh) {
  float x = 1.0 - vh;
  float x2 = x * x;
  return f0 + (vec3(1.0) - f0) * (x2 * x2 * x);
}

// The BRDF times NL for unit n (shading normal), v (to the eye), l (to the light): what illuminance E multiplies;
// the specular lobe scaled by `energy` (the lighting's high tier: multiple scattering's energy compensation).
vec3 brdfCosineCompensated(vec3 n, vec3 v, vec3 l, vec3 diffuseColor, vec3 f0, float roughness, vec3 energy) {
  float nl = dot(n, l);
  if (nl <= 0.0) return vec3(0.0);
  float nv = max(dot(n, v), 1e-4);
  vec3 h = normalize(l + v);
  float nh = max(dot(n, h), 0.0);
  float vh = max(dot(v, h), 0.0);
  float alpha = roughness * roughness;
  vec3 f = fresnelSchlick(f0, vh);
  vec3 specular = f * (distributionGgx(nh, alpha) * visibilitySmithGgx(nl, nv, alpha));
  vec3 diffuse = (vec3(1.0) - f) * diffuseColor / PBR_PI;
  return (diffuse + specular * energy) * nl;
}

vec3 brdfCosine(vec3 n, vec3 v, vec3 l, vec3 diffuseColor, vec3 f0, float roughness) {
  return brdfCosineCompensated(n, v, l, diffuseColor, f0, roughness, vec3(1.0));
}

// Specular occlusion from the ambient occlusion (Lagarde and de Rousiers 2014, "Moving Frostbite to PBR", sec. 4.10.2,
// listing 26): how much of the specular ambient a visibility `ao` lets through at this view angle and roughness.
float specularOcclusion(float nv, float ao, float alpha) {
  return clamp(pow(nv + ao, exp2(-16.0 * alpha - 1.0)) - 1.0 + ao, 0.0, 1.0);
}

#endif
