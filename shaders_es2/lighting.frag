// Forward lighting of the final image: base colour under one directional light and a sky/ground hemisphere
// ambient. AO multiplies the ambient term only (direct light is shadowed by shadow maps, not by AO).
#include "lib/precision.glsl"
#include "lib/material.glsl"

uniform sampler2D u_ao;          // blurred AO in R, same size as the viewport
uniform vec2 u_viewportSize;
uniform float u_aoSplitX;        // AO applies right of this pixel column (0: everywhere, the width: nowhere)
uniform vec3 u_lightDirection;   // view space, towards the light, unit
uniform vec3 u_lightColor;
uniform vec3 u_skyColor;
uniform vec3 u_groundColor;
uniform vec3 u_viewUp;           // world up in view space

varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
varying vec2 v_texcoord;
varying vec4 v_clipPosition;

void main() {
  vec4 base = baseColor(v_texcoord);
  if (u_alphaCutoff >= 0.0 && base.a < u_alphaCutoff) discard;
  vec3 n = normalize(v_viewNormal);
  if (!gl_FrontFacing) n = -n;

  // This fragment's pixel centre in [0, 1]^2, from the interpolated clip position rather than gl_FragCoord, which is
  // only mediump in GLSL ES 1.00 and would address the wrong AO texel beyond 2048 pixels.
  vec2 screenUv = v_clipPosition.xy / v_clipPosition.w * 0.5 + 0.5;
  float ao = texture2D(u_ao, screenUv).r;
  if (screenUv.x * u_viewportSize.x < u_aoSplitX) ao = 1.0;

  vec3 ambient = mix(u_groundColor, u_skyColor, dot(n, u_viewUp) * 0.5 + 0.5) * ao;
  vec3 direct = u_lightColor * max(dot(n, u_lightDirection), 0.0);
  vec3 color = base.rgb * (ambient + direct);
  // Display encoding: the 2.2 power that the texture decode inverts.
  gl_FragColor = vec4(pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
