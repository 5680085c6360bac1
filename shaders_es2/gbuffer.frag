// G-buffer pass: one RGBA8 target. RG = octahedral view-space normal, BA = 16-bit linear depth.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/material.glsl"

uniform float u_near;
uniform float u_depthRange;  // far - near

varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
varying vec2 v_texcoord;

void main() {
  if (alphaMasked(v_texcoord)) discard;
  vec3 n = normalize(v_viewNormal);
  // Double-sided materials show their back faces: turn the normal towards the viewer.
  if (!gl_FrontFacing) n = -n;
  float linearDepth = (-v_viewPosition.z - u_near) / u_depthRange;
  gl_FragColor = vec4(encodeNormal(n), packLinearDepth(linearDepth));
}
