// The AO's second depth layer (ao.layers 2; effects/ao/DepthPeelPass.h): depth peeling with a minimum separation
// (Mara et al., "Deep G-Buffers", HPG 2016, sec. 3). Drawn over geometry.vert, front and back faces alike, into a
// target with its own depth buffer: a fragment less than u_minSeparation (in linear depth) behind the G-buffer's
// depth at its pixel is discarded, so the depth test keeps the nearest surface behind the visible one.
// Output: BA = its 16-bit linear depth (the G-buffer's packing); the clear colour (code 65535) where none lies behind.
// ALPHA_MASK as in the G-buffer pass: cut-outs are no surface in either layer.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/material.glsl"

uniform sampler2D u_gbuffer;     // the first layer
uniform float u_near;
uniform float u_depthRange;      // far - near
uniform float u_minSeparation;   // in linear depth (units of far - near)

varying vec3 v_viewPosition;
varying vec2 v_texcoord;
varying vec4 v_clipPosition;

void main() {
#if ALPHA_MASK
  if (alphaMasked(v_texcoord)) discard;
#endif
  float linearDepth = (-v_viewPosition.z - u_near) / u_depthRange;
  // This fragment's pixel centre from the interpolated clip position (highp), as the lighting pass reads the AO.
  vec2 uv = v_clipPosition.xy / v_clipPosition.w * 0.5 + 0.5;
  float first = unpackLinearDepth(texture2D(u_gbuffer, uv).ba);
  if (linearDepth < first + u_minSeparation) discard;
  gl_FragColor = vec4(1.0, 1.0, packLinearDepth(linearDepth));
}
