// The lit image: base colour under one directional light and the image-based ambient light of lib/environment.glsl
// (spherical-harmonic irradiance and a prefiltered specular environment; the background shows the environment).
// AO multiplies the ambient term only (direct light is shadowed by shadow maps, not by AO). Today's materials are
// rough dielectrics: F0 0.04, roughness 1. Variants (src/core/LightingEffect.h):
//
//   DEFERRED 0        the scene drawn again with the G-buffer pass's vertex stage (geometry.vert), tested against
//                     its depth; the material's base colour from lib/material.glsl (a variant per MaterialKind:
//                     ALPHA_MASK 1 discards cut-outs, BASE_COLOR_TEXTURE 0 uses the factor alone).
//   DEFERRED 1        a full-screen pass (fullscreen.vert): the normal from the G-buffer, the base colour from the
//                     target the G-buffer pass wrote beside it (several render targets). Each pixel once.
//   TONEMAP_INLINE 0  linear HDR colour in the RGBA8 encoding of lib/hdr.glsl, for the passes after it;
//                  1  the tone mapping done here, where the tone-mapping pass would be this colour's only reader:
//                     exposure, curve (TONEMAP_OPERATOR), sRGB, and the luma FXAA reads in alpha.
//   BACKGROUND 1      (with DEFERRED 1, over fullscreen.vert at the far plane) the forward forms' background: the
//                     environment where the scene left the depth at 1.
//   COUNT_SHADING 1   the diagnostic: each fragment adds 1/255 (additive blending), counting the fragments shaded
//                     per pixel under the lit pass's depth test.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/srgb.glsl"
#include "lib/hdr.glsl"
#include "lib/material.glsl"

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
uniform vec3 u_lightDirection;   // view space, towards the light, unit
uniform vec3 u_lightColor;
uniform mat3 u_viewToWorld;      // the camera's rotation: view-space directions to world space

const vec3 DIELECTRIC_F0 = vec3(0.04);  // glTF's dielectric specular reflectance at normal incidence
const float MATERIAL_ROUGHNESS = 1.0;

// n: unit normal, toEye: unit direction to the eye, both view space.
vec3 shade(vec3 base, vec3 n, vec3 toEye, float ao) {
  vec3 ambient = ambientLight(u_viewToWorld * n, u_viewToWorld * toEye, base, DIELECTRIC_F0, MATERIAL_ROUGHNESS, ao);
  vec3 direct = base * u_lightColor * max(dot(n, u_lightDirection), 0.0);
  return ambient + direct;
}

// What the eye sees where no geometry is, towards the view-space direction `ray`: the environment itself.
vec3 background(vec3 ray) { return environmentSpecular(u_viewToWorld * ray, 0.0); }

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
  if (isBackgroundCode(unpackDepthCode(g.ba))) {
    gl_FragColor = encodeOutput(background(v_farRay));
    return;
  }
  vec3 base = srgbToLinear(texture2D(u_baseColor, v_uv).rgb);
  // The far-plane ray points from the eye through the pixel, as the surface's position does.
  vec3 toEye = -normalize(v_farRay);
  gl_FragColor = encodeOutput(shade(base, decodeNormal(g.rg), toEye, texture2D(u_ao, v_uv).r));
}
#else
void main() {
  vec4 base = baseColor(v_texcoord);
#if ALPHA_MASK
  if (base.a < u_alphaCutoff) discard;
#endif
  vec3 n = normalize(v_viewNormal);
  if (!gl_FrontFacing) n = -n;
  // This fragment's pixel centre in [0, 1]^2, from the interpolated clip position rather than gl_FragCoord, which is
  // only mediump in GLSL ES 1.00 and would address the wrong AO texel beyond 2048 pixels.
  vec2 screenUv = v_clipPosition.xy / v_clipPosition.w * 0.5 + 0.5;
  gl_FragColor = encodeOutput(shade(base.rgb, n, -normalize(v_viewPosition), texture2D(u_ao, screenUv).r));
}
#endif
#endif
