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
//   TONEMAP_INLINE 0  linear HDR colour in the RGBA8 encoding of lib/hdr.glsl, for the passes after it;
//                  1  the tone mapping done here, where the tone-mapping pass would be this colour's only reader:
//                     exposure, curve (TONEMAP_OPERATOR), sRGB, and the luma FXAA reads in alpha.
//   BACKGROUND 1      (with DEFERRED 1, over fullscreen.vert at the far plane) the forward forms' background: the
//                     environment where the scene left the depth at 1.
//   OVER_DEPTH 1      (with DEFERRED 1, at the far plane) the deferred shading alone, drawn over the G-buffer's depth
//                     where something was drawn; the background form draws the rest.
//   LIGHTING_QUALITY  the tier (LightingEffect.h, LightingQuality): 0 low, 1 medium, 2 high.
//   COUNT_SHADING 1   the diagnostic: each fragment adds 1/255 (additive blending), counting the fragments shaded
//                     per pixel under the lit pass's depth test.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/srgb.glsl"
#include "lib/hdr.glsl"
#if !DEFERRED && !COUNT_SHADING
#define MATERIAL_SURFACE 1
#endif
#include "lib/material.glsl"
#include "lib/pbr.glsl"
#include "lib/reconstruct.glsl"  // the eye's rays, perspective or orthographic

#if DEFERRED
uniform sampler2D u_gbuffer;    // RG normal, BA depth code
varying vec2 v_uv;
#if !COUNT_SHADING
varying vec3 v_farRay;          // view space: the direction towards the pixel
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
// (interpolated) normal, v towards the eye (all unit, view space), diffuseColor and f0 the material's (lib/pbr.glsl),
// roughness perceptual; scaleBias the split sum's (A, B) at (roughness, n.v). The diffuse keeps the energy the
// specular does not take (so a white furnace gives 1).
#if LIGHTING_QUALITY == 0
// Low: no fetch. The specular environment is the irradiance towards the reflected direction (the spherical
// harmonics' cosine lobe stands for every roughness: right for the roughest, too blurred for a mirror), weighted by
// Karis's analytic (A, B); the occlusion darkens both terms alike.
vec3 ambientLight(vec3 n, vec3 g, vec3 v, vec3 diffuseColor, vec3 f0, float roughness, float occlusion,
                  vec2 scaleBias) {
  vec3 specularAlbedo = f0 * scaleBias.x + scaleBias.y;
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
vec3 ambientLight(vec3 n, vec3 g, vec3 v, vec3 diffuseColor, vec3 f0, float roughness, float occlusion,
                  vec2 scaleBias) {
  float nv = clamp(dot(n, v), 1e-4, 1.0);
  vec3 r = reflect(-v, n);
  vec3 irradiance = environmentIrradiance(u_viewToEnvironment * n);
  vec3 specularAlbedo = f0 * scaleBias.x + scaleBias.y;
  vec3 specular = specularAlbedo * environmentSpecular(u_viewToEnvironment * r, roughness);
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

// The lit colour of a surface point: p its view-space position, n its shading normal and g the surface's own normal
// (unit, facing the viewer).
vec3 shade(vec3 base, float metallic, float roughness, vec3 p, vec3 n, vec3 g, float occlusion, vec3 emissive) {
  vec3 v = -eyeRayDirection(p);
  roughness = clamp(roughness, PBR_MIN_ROUGHNESS, 1.0);
  metallic = clamp(metallic, 0.0, 1.0);
  vec3 diffuseColor = base * (1.0 - metallic);
  vec3 f0 = mix(vec3(0.04), base, metallic);
  vec2 scaleBias = splitSumScaleBias(roughness, clamp(dot(n, v), 1e-4, 1.0));
  vec3 color = ambientLight(n, g, v, diffuseColor, f0, roughness, occlusion, scaleBias) + emissive;
#if LIGHTING_QUALITY == 2
  // Kulla & Conty, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH 2017, in Filament's form: the
  // specular lobe scaled by 1 + F0 (1 / Ess - 1), the energy single scattering loses at this roughness and angle.
  vec3 energy = 1.0 + f0 * (1.0 / max(scaleBias.x + scaleBias.y, 1e-3) - 1.0);
#define DIRECT_LIGHT(l, illuminance) brdfCosineCompensated(n, v, l, diffuseColor, f0, roughness, energy) * (illuminance)
#else
#define DIRECT_LIGHT(l, illuminance) brdfCosine(n, v, l, diffuseColor, f0, roughness) * (illuminance)
#endif
  color += DIRECT_LIGHT(u_lightDirection, u_lightColor);
#if MAX_PUNCTUAL_LIGHTS > 0
  for (int i = 0; i < MAX_PUNCTUAL_LIGHTS; i++) {
    vec3 toLight = u_lightPositionRange[i].xyz - p;
    float d2 = max(dot(toLight, toLight), 1e-8);
    vec3 l = toLight * inversesqrt(d2);
    // KHR_lights_punctual: inverse square, windowed to 0 at the range (the extension's recommended
    // clamp(1 - (d / range)^4, 0, 1)^2), times the spot's smooth cone.
    float window = clamp(1.0 - d2 * d2 * u_lightPositionRange[i].w, 0.0, 1.0);
    float cone = clamp(dot(u_lightSpot[i].xyz, -l) * u_lightColorSpot[i].a + u_lightSpot[i].w, 0.0, 1.0);
    vec3 illuminance = u_lightColorSpot[i].rgb * (window * window * cone * cone / d2);
    color += DIRECT_LIGHT(l, illuminance);
  }
#endif
  return color;
}

// What the eye sees where no geometry is, along the eye's ray through far-plane point `farRay`: the environment
// itself (one colour for an orthographic camera, whose rays are parallel).
vec3 background(vec3 farRay) { return environmentSpecular(u_viewToEnvironment * eyeRay(farRay), 0.0); }

#if TONEMAP_INLINE
#include "lib/tonemap.glsl"
uniform float u_lumaInAlpha;     // 1: luma in alpha, for FXAA; 0: alpha 1, for the output framebuffer
vec4 encodeOutput(vec3 linear) {
  vec3 display = linearToSrgb(toneMap(linear));
  return vec4(display, mix(1.0, fxaaLuma(display), u_lumaInAlpha));
}
#else
vec4 encodeOutput(vec3 linear) { return encodeHdr(linear); }
#endif

#if DEFERRED && BACKGROUND
void main() { gl_FragColor = encodeOutput(background(v_farRay)); }
#elif DEFERRED
uniform sampler2D u_baseColor;   // sRGB-encoded base colour

void main() {
  vec4 g = texture2D(u_gbuffer, v_uv);
#if !OVER_DEPTH
  if (isBackgroundCode(unpackDepthCode(g.ba))) {
    gl_FragColor = encodeOutput(background(v_farRay));
    return;
  }
#endif
  vec3 base = srgbToLinear(texture2D(u_baseColor, v_uv).rgb);
  // Only the view direction matters to the shading here (no punctual lights take this form): the eye's ray through
  // the far plane's point is the surface's (shade takes it through eyeRayDirection). The G-buffer's normal is the
  // surface's own (no normal texture takes this form).
  vec3 n = decodeNormal(g.rg);
  gl_FragColor = encodeOutput(shade(base, 0.0, 1.0, v_farRay, n, n, texture2D(u_ao, v_uv).r, vec3(0.0)));
}
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
  gl_FragColor = encodeOutput(shade(base.rgb, surface.metallic, surface.roughness, v_viewPosition, n, g, occlusion,
                                    surface.emissive));
}
#endif
#endif
