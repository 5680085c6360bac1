// The lit image: base colour under one directional light and a sky/ground hemisphere ambient, written as linear HDR
// colour in the RGBA8 HDR encoding (lib/hdr.glsl). AO multiplies the ambient term only (direct light is shadowed by
// shadow maps, not by AO).
//
// COUNT_SHADING 1: the diagnostic variant. Each fragment adds 1/255 (additive blending), so the target counts the
// fragments shaded per pixel under the same depth test as the lit pass.
#include "lib/precision.glsl"
#include "lib/material.glsl"

varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
varying vec2 v_texcoord;
varying vec4 v_clipPosition;

#if COUNT_SHADING
void main() {
  if (alphaMasked(v_texcoord)) discard;
  gl_FragColor = vec4(1.0 / 255.0);
}
#else
#include "lib/hdr.glsl"

uniform sampler2D u_ao;          // AO in R, the frame's size (1x1 white when the AO is off)
uniform vec3 u_lightDirection;   // view space, towards the light, unit
uniform vec3 u_lightColor;
uniform vec3 u_skyColor;
uniform vec3 u_groundColor;
uniform vec3 u_viewUp;           // world up in view space

void main() {
  vec4 base = baseColor(v_texcoord);
  if (u_alphaCutoff >= 0.0 && base.a < u_alphaCutoff) discard;
  vec3 n = normalize(v_viewNormal);
  if (!gl_FrontFacing) n = -n;

  // This fragment's pixel centre in [0, 1]^2, from the interpolated clip position rather than gl_FragCoord, which is
  // only mediump in GLSL ES 1.00 and would address the wrong AO texel beyond 2048 pixels.
  vec2 screenUv = v_clipPosition.xy / v_clipPosition.w * 0.5 + 0.5;
  float ao = texture2D(u_ao, screenUv).r;

  vec3 ambient = mix(u_groundColor, u_skyColor, dot(n, u_viewUp) * 0.5 + 0.5) * ao;
  vec3 direct = u_lightColor * max(dot(n, u_lightDirection), 0.0);
  gl_FragColor = encodeHdr(base.rgb * (ambient + direct));
}
#endif
