// The lit image: glTF 2.0 metallic-roughness materials (lib/material.glsl, lib/pbr.glsl: Cook-Torrance with GGX,
// Smith visibility and Schlick Fresnel) under the sun (one directional light), up to MAX_PUNCTUAL_LIGHTS
// KHR_lights_punctual point and spot lights, the image-based ambient light of lib/environment.glsl (spherical-harmonic
// irradiance and a prefiltered specular environment; the background shows the environment) and the material's
// emission. The AO darkens the ambient term only (diffuse directly, specular through Lagarde's specular occlusion),
// combined with the material's baked occlusion by their minimum (docs/pbr.md measured the rule); direct light is
// never darkened. Variants (src/effects/lighting/LightingEffect.h):
//
//   DEFERRED 0        the scene drawn again with the G-buffer pass's vertex stage (geometry.vert), tested against
//                     its depth; the material from lib/material.glsl (a variant per MaterialKind: ALPHA_MASK 1
//                     discards cut-outs, BASE_COLOR_TEXTURE 0 uses the factor alone, PBR_TEXTURES 1 samples the
//                     metallic-roughness, normal, occlusion and emissive textures).
//   DEFERRED 1        a full-screen pass (fullscreen.vert): the normal from the G-buffer, the base colour from the
//                     target the G-buffer pass wrote beside it (several render targets). Each pixel once. Only
//                     scenes whose materials are all rough dielectrics without emission and without punctual lights
//                     take it (scene/Scene.h: Material::needsForwardLighting): it shades metallic 0, roughness 1.
//   (the shading forms) the lit linear HDR colour goes through finishPixel (lib/stage.glsl), which the program
//                     defines before this file: the per-pixel stages fused into the pass (src/frame/Stage.h: fog, the
//                     tone curve, ...), then the encoding of the last colour (HDR, or display colour with its luma).
//   BACKGROUND 1      (with DEFERRED 1, over fullscreen.vert at the far plane) the forward forms' background: the
//                     environment where the scene left the depth at 1.
//   COUNT_SHADING 1   the diagnostic: each fragment adds 1/255 (additive blending), counting the fragments shaded
//                     per pixel under the lit pass's depth test.
//   UNLIT 1           KHR_materials_unlit: the base colour (times the vertex colour) is the colour; no light, no AO.
//   MATERIAL_LAYERS 1 KHR_materials_ior and _specular (the dielectric's F0 and F90) and _clearcoat (a second GGX
//                     lobe over the base, the Khronos sample viewer's layering).
//   BLENDED 1         the transparent layer's form (effects/transparency): the surface composited over what lies
//                     behind it (shaders_es2/transparency/composite.glsl), fogged by its own distance; TRANSMISSION 1
//                     adds KHR_materials_transmission's thin-walled refraction.
//   LIGHTING_QUALITY  the tier (LightingEffect.h, LightingQuality): 0 low, 1 medium, 2 high.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/srgb.glsl"
#include "lib/hdr.glsl"
#if !DEFERRED && !COUNT_SHADING
#define MATERIAL_SURFACE 1
#endif
#ifndef UNLIT
#define UNLIT 0
#endif
#ifndef BLENDED
#define BLENDED 0
#endif
#include "lib/material.glsl"
#include "lib/pbr.glsl"
#include "lib/reconstruct.glsl"  // the eye's rays, perspective or orthographic

#if DEFERRED
uniform sampler2D u_gbuffer;    // RG normal, BA depth code
varying vec2 v_uv;
#if !COUNT_SHADING
varying vec3 v_farRay;          // view space: the direction towards the pixel
varying vec3 v_environmentRay;  // the eye's ray in the environment's frame (fullscreen.vert, ENVIRONMENT_RAY)
#endif
#else
varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
varying vec2 v_texcoord;
varying vec4 v_clipPosition;
#endif

#if COUNT_SHADING
void main() {
#if DEFERRED
  if (isBackgroundCode(unpackDepthCode(texture2D(u_gbuffer, v_uv).ba))) discard;
#elif ALPHA_MASK
  if (alphaMasked(v_texcoord)) discard;
#endif
  gl_FragColor = vec4(1.0 / 255.0);
}
#else

#include "lib/environment.glsl"

uniform sampler2D u_ao;          // AO in R, the frame's size (1x1 white when the AO is off)
uniform vec3 u_lightDirection;   // view space, towards the sun, unit
uniform vec3 u_lightColor;       // the sun's illuminance: colour x intensity (lux)
// View-space directions to the environment's: the camera's rotation to world space, then the sky's turn about the
// vertical that puts its sun at lighting.sun-azimuth (LightingEffect::environmentRotation).
uniform mat3 u_viewToEnvironment;

#if MAX_PUNCTUAL_LIGHTS > 0
// KHR_lights_punctual, view space (effects/lighting/LightingEffect.h: PunctualLightUniforms). An unused slot has colour
// 0.
uniform vec4 u_lightPositionRange[MAX_PUNCTUAL_LIGHTS];  // xyz position, w 1 / range^4 (0: no range)
uniform vec4 u_lightColorSpot[MAX_PUNCTUAL_LIGHTS];      // rgb colour x intensity (candela), a the spot's scale
uniform vec4 u_lightSpot[MAX_PUNCTUAL_LIGHTS];           // xyz the spot's direction (towards where it shines),
                                                         // w its offset: cone = clamp(cos * scale + offset, 0, 1)^2
#endif

// The ambient light: the environment's radiance (lib/environment.glsl), diffuse and specular, darkened by `occlusion`
// (the screen-space AO and the material's baked occlusion, their minimum). n the shading normal, g the surface's own
// (interpolated) normal, v towards the eye (all unit, view space), diffuseColor, f0 and f90 the material's
// (lib/pbr.glsl), roughness perceptual; scaleBias the split sum's (A, B) at (roughness, n.v). The diffuse keeps the
// energy the specular does not take (so a white furnace gives 1).
#if LIGHTING_QUALITY == 0
// Low: no fetch. The specular environment is the irradiance towards the reflected direction (the spherical
// harmonics' cosine lobe stands for every roughness: right for the roughest, too blurred for a mirror), weighted by
// Karis's analytic (A, B); the occlusion darkens both terms alike.
vec3 ambientLight(vec3 n, vec3 g, vec3 v, vec3 diffuseColor, vec3 f0, vec3 f90, float roughness, float occlusion,
                  vec2 scaleBias) {
  vec3 specularAlbedo = f0 * scaleBias.x + f90 * scaleBias.y;
  vec3 diffuse = diffuseColor * (1.0 - specularAlbedo) * environmentIrradiance(u_viewToEnvironment * n);
  vec3 specular = specularAlbedo * environmentIrradiance(u_viewToEnvironment * reflect(-v, n));
  return (diffuse + specular) * occlusion;
}
#else
// Medium: the split sum (Karis 2013) with the prefiltered environment, the specular darkened by Lagarde's specular
// occlusion of the occlusion. High adds the light that scatters more than once between microfacets (Fdez-Aguera,
// "A Multiple-Scattering Microfacet Model for Real-Time Image-based Lighting", JCGT 8(1), 2019, eq. 13-16: the
// single-scattering energy Ess = A + B, a multiple-scattering lobe of Fms Ems carried by the irradiance, and the
// diffuse taking what both leave), and the horizon occlusion of a reflection a normal texture tilts below the surface
// (Russell, "Horizon Occlusion for Normal Mapped Reflections", 2015, as Filament: (1 + r.g)^2 clamped).
vec3 ambientLight(vec3 n, vec3 g, vec3 v, vec3 diffuseColor, vec3 f0, vec3 f90, float roughness, float occlusion,
                  vec2 scaleBias) {
  float nv = clamp(dot(n, v), 1e-4, 1.0);
  vec3 r = reflect(-v, n);
  vec3 irradiance = environmentIrradiance(u_viewToEnvironment * n);
  vec3 specularAlbedo = f0 * scaleBias.x + f90 * scaleBias.y;
#if DEFERRED
  // The deferred form shades roughness 1 alone (its main), where GGX's D is 1 / pi over the whole hemisphere: the
  // prefiltered radiance with n = v = r (environment/Environment.h) is then the integral of L (r.l)+ over that of
  // (r.l)+, E(r) / pi, which the nine terms give without the level's fetch, atan and acos: closer to the integral
  // than level 5 on the sky (Environment.AtRoughnessOneThePrefilteredRadianceIsTheIrradiance: worst 0.023 against
  // 0.035), and 121 -> 93 ms of the pass on SwiftShader at 1280x720 (docs/benchmarks.md, issue 26).
  vec3 specular = specularAlbedo * environmentIrradiance(u_viewToEnvironment * r);
#else
  vec3 specular = specularAlbedo * environmentSpecular(u_viewToEnvironment * r, roughness);
#endif
  float specularVisibility = specularOcclusion(nv, occlusion, roughness * roughness);
#if LIGHTING_QUALITY == 2
  float ess = scaleBias.x + scaleBias.y;
  float ems = 1.0 - ess;
  vec3 fAverage = f0 + (1.0 - f0) * (1.0 / 21.0);
  vec3 multiple = specularAlbedo * fAverage / (1.0 - ems * fAverage) * ems;
  vec3 diffuse = diffuseColor * (1.0 - specularAlbedo - multiple) * irradiance;
  specular += multiple * irradiance;
  float horizon = clamp(1.0 + dot(r, g), 0.0, 1.0);
  specularVisibility *= horizon * horizon;
#else
  vec3 diffuse = diffuseColor * (1.0 - specularAlbedo) * irradiance;
#endif
  return diffuse * occlusion + specular * specularVisibility;
}
#endif

// The split sum's (A, B): the table (medium, high) or Karis's analytic fit (low: "Physically Based Shading on
// Mobile", 2014; off by up to 0.18 in A at low roughness and grazing angles, docs/lighting.md).
vec2 splitSumScaleBias(float roughness, float nv) {
#if LIGHTING_QUALITY == 0
  vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
  vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
  vec4 r = roughness * c0 + c1;
  float a004 = min(r.x * r.x, exp2(-9.28 * nv)) * r.x + r.y;
  return vec2(-1.04, 1.04) * a004 + r.zw;
#else
  return environmentBrdf(roughness, nv);
#endif
}

#if MAX_PUNCTUAL_LIGHTS > 0
// A light's illuminance at p (view space) and the unit direction l towards it, from its three uniforms (the loops
// index the arrays: GLSL ES 1.00's Appendix A mandates only loop indices, not a function's parameter, as a fragment
// stage's uniform index). KHR_lights_punctual: inverse square, windowed to 0 at the range (the extension's
// recommended clamp(1 - (d / range)^4, 0, 1)^2), times the spot's smooth cone. A directional light (w -1: xyz the unit
// direction towards it) has neither: its colour is its illuminance.
vec3 punctualIlluminance(vec4 positionRange, vec4 colorSpot, vec4 spot, vec3 p, out vec3 l) {
  bool directional = positionRange.w < 0.0;
  vec3 toLight = directional ? positionRange.xyz : positionRange.xyz - p;
  float d2 = directional ? 1.0 : max(dot(toLight, toLight), 1e-8);
  l = toLight * inversesqrt(d2);
  float window = clamp(1.0 - d2 * d2 * positionRange.w, 0.0, 1.0);
  float cone = clamp(dot(spot.xyz, -l) * colorSpot.a + spot.w, 0.0, 1.0);
  return colorSpot.rgb * (window * window * cone * cone / d2);
}
#endif

#if MATERIAL_LAYERS
// KHR_materials_clearcoat over the lit base colour, as the Khronos sample viewer layers it: a dielectric coat (F0
// 0.04, ior 1.5) with a GGX lobe of its own roughness around the base's normal (the coat's normal texture is not
// read), lit by the sun, the punctual lights and the environment (darkened as the base's specular is; in the low
// tier, as its ambientLight, the irradiance towards the reflection and no fetch); the base below keeps what the coat
// does not reflect, 1 - clearcoat F(n.v).
vec3 coated(vec3 base, vec3 p, vec3 n, vec3 v, float occlusion) {
  if (u_clearcoat <= 0.0) return base;
  float roughness = clamp(u_clearcoatRoughness, PBR_MIN_ROUGHNESS, 1.0);
  float nv = clamp(dot(n, v), 1e-4, 1.0);
  vec2 scaleBias = splitSumScaleBias(roughness, nv);
#if LIGHTING_QUALITY == 0
  vec3 coat = vec3(0.04 * scaleBias.x + scaleBias.y) *
              environmentIrradiance(u_viewToEnvironment * reflect(-v, n)) * occlusion;
#else
  vec3 coat = vec3(0.04 * scaleBias.x + scaleBias.y) *
              environmentSpecular(u_viewToEnvironment * reflect(-v, n), roughness) *
              specularOcclusion(nv, occlusion, roughness * roughness);
#endif
  coat += brdfCosine(n, v, u_lightDirection, vec3(0.0), vec3(0.04), roughness) * u_lightColor;
#if MAX_PUNCTUAL_LIGHTS > 0
  for (int i = 0; i < MAX_PUNCTUAL_LIGHTS; i++) {
    vec3 l;
    vec3 illuminance = punctualIlluminance(u_lightPositionRange[i], u_lightColorSpot[i], u_lightSpot[i], p, l);
    coat += brdfCosine(n, v, l, vec3(0.0), vec3(0.04), roughness) * illuminance;
  }
#endif
  return base * (1.0 - u_clearcoat * fresnelSchlick(vec3(0.04), nv)) + u_clearcoat * coat;
}
#endif

// The material's Fresnel colours at normal (f0) and grazing (f90) incidence, metallic clamped to [0, 1]: with
// KHR_materials_specular and _ior the dielectric's from u_specular, else glTF's core 0.04 and 1; a metal's are its base
// colour and 1.
void fresnelColors(vec3 base, float metallic, out vec3 f0, out vec3 f90) {
#if MATERIAL_LAYERS
  f0 = mix(u_specular.rgb, base, metallic);
  f90 = vec3(mix(u_specular.a, 1.0, metallic));
#else
  f0 = mix(vec3(0.04), base, metallic);
  f90 = vec3(1.0);
#endif
}

// The lit colour of a surface point: p its view-space position, n its shading normal and g the surface's own normal
// (unit, facing the viewer).
vec3 shade(vec3 base, float metallic, float roughness, vec3 p, vec3 n, vec3 g, float occlusion, vec3 emissive) {
  vec3 v = -eyeRayDirection(p);
  roughness = clamp(roughness, PBR_MIN_ROUGHNESS, 1.0);
  metallic = clamp(metallic, 0.0, 1.0);
  vec3 diffuseColor = base * (1.0 - metallic);
  vec3 f0, f90;
  fresnelColors(base, metallic, f0, f90);
#if TRANSMISSION
  // Thin-walled transmission takes this share of the diffuse lobe (transparency/composite.glsl adds what it lets
  // through).
  diffuseColor *= 1.0 - u_transmission;
#endif
  vec2 scaleBias = splitSumScaleBias(roughness, clamp(dot(n, v), 1e-4, 1.0));
  vec3 color = ambientLight(n, g, v, diffuseColor, f0, f90, roughness, occlusion, scaleBias) + emissive;
#if LIGHTING_QUALITY == 2
  // Kulla & Conty, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH 2017, in Filament's form: the
  // specular lobe scaled by 1 + F0 (1 / Ess - 1), the energy single scattering loses at this roughness and angle.
  vec3 energy = 1.0 + f0 * (1.0 / max(scaleBias.x + scaleBias.y, 1e-3) - 1.0);
#else
  vec3 energy = vec3(1.0);
#endif
  color += brdfCosineCompensated(n, v, u_lightDirection, diffuseColor, f0, f90, roughness, energy) * u_lightColor;
#if MAX_PUNCTUAL_LIGHTS > 0
  for (int i = 0; i < MAX_PUNCTUAL_LIGHTS; i++) {
    vec3 l;
    vec3 illuminance = punctualIlluminance(u_lightPositionRange[i], u_lightColorSpot[i], u_lightSpot[i], p, l);
    color += brdfCosineCompensated(n, v, l, diffuseColor, f0, f90, roughness, energy) * illuminance;
  }
#endif
#if MATERIAL_LAYERS
  color = coated(color, p, n, v, occlusion);
#endif
  return color;
}

#if DEFERRED && !COUNT_SHADING
// What the eye sees where no geometry is: the environment itself along the eye's ray (one colour for an orthographic
// camera, whose rays are parallel), interpolated in the environment's frame by the vertex stage.
vec3 background() { return environmentSky(v_environmentRay); }
#endif

#if DEFERRED && BACKGROUND
void main() {
  StagePixel pixel = stagePixel(v_uv);
  pixel.viewPosition = v_farRay;
  pixel.background = true;
  gl_FragColor = finishPixel(background(), pixel);
}
#elif DEFERRED
uniform sampler2D u_baseColor;   // sRGB-encoded base colour

void main() {
  vec4 g = texture2D(u_gbuffer, v_uv);
  float code = unpackDepthCode(g.ba);
  StagePixel pixel = stagePixel(v_uv);
  pixel.background = isBackgroundCode(code);
  pixel.viewNormal = decodeNormal(g.rg);
  pixel.viewPosition = v_farRay;
#if STAGE_POSITION
  if (!pixel.background) pixel.viewPosition = viewPositionOnRay(v_farRay, code * (1.0 / 65535.0));
#endif
  vec3 base = srgbToLinear(texture2D(u_baseColor, v_uv).rgb);
  // Only the view direction matters to the shading here (no punctual lights take this form): the eye's ray through
  // the far plane's point is the surface's (shade takes it through eyeRayDirection). The G-buffer's normal is the
  // surface's own (no normal texture takes this form).
  vec3 color = shade(base, 0.0, 1.0, v_farRay, pixel.viewNormal, pixel.viewNormal, texture2D(u_ao, v_uv).r, vec3(0.0));
  // One colour through finishPixel: a CPU rasteriser runs both sides of the branch, and would run the stages twice.
  if (pixel.background) color = background();
  gl_FragColor = finishPixel(color, pixel);
}
#elif UNLIT && !BLENDED
// KHR_materials_unlit: the base colour (times the vertex colour) as it is; exposure and the tone curve still apply.
void main() {
  vec4 base = baseColor(v_texcoord);
#if ALPHA_MASK
  if (base.a < u_alphaCutoff) discard;
#endif
  StagePixel pixel = stagePixel(v_clipPosition.xy / v_clipPosition.w * 0.5 + 0.5);
  pixel.viewPosition = v_viewPosition;
  pixel.viewNormal = normalize(v_viewNormal);
  gl_FragColor = finishPixel(base.rgb, pixel);
}
#elif BLENDED
#include "transparency/composite.glsl"
#else
void main() {
  vec4 base = baseColor(v_texcoord);
#if ALPHA_MASK
  if (base.a < u_alphaCutoff) discard;
#endif
  Surface surface = surfaceAt(v_texcoord);
  vec3 g = normalize(v_viewNormal);
  if (!gl_FrontFacing) g = -g;
  vec3 n = perturbedNormal(g, gl_FrontFacing);
  // This fragment's pixel centre in [0, 1]^2, from the interpolated clip position rather than gl_FragCoord, which is
  // only mediump in GLSL ES 1.00 and would address the wrong AO texel beyond 2048 pixels.
  vec2 screenUv = v_clipPosition.xy / v_clipPosition.w * 0.5 + 0.5;
  // The baked occlusion and the screen-space AO: their minimum, not their product (measured against the ray-traced
  // reference: docs/pbr.md, tests/test_baked_occlusion.cpp); both see much of the same occlusion.
  float occlusion = min(texture2D(u_ao, screenUv).r, surface.occlusion);
  StagePixel pixel = stagePixel(screenUv);
  pixel.viewPosition = v_viewPosition;
  pixel.viewNormal = n;
  gl_FragColor = finishPixel(shade(base.rgb, surface.metallic, surface.roughness, v_viewPosition, n, g, occlusion,
                                   surface.emissive),
                             pixel);
}
#endif
#endif
