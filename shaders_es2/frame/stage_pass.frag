// A stand-alone pass of per-pixel stages (src/frame/Stage.h: stagePass): the colour of the first stage's input at
// this pixel, decoded (STAGE_INPUT_DISPLAY 0: the HDR encoding; 1: display colour as it is), through the chain
// (finishPixel, generated before this file), encoded. Where a stage needs the pixel's position or normal, they come
// from the G-buffer (the position along the far-plane ray at the 16-bit linear depth, as fog.frag took it before).
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/hdr.glsl"

uniform sampler2D u_color;  // the first stage's input, NEAREST
varying vec2 v_uv;

#if STAGE_POSITION || STAGE_NORMAL
#include "lib/reconstruct.glsl"
uniform sampler2D u_gbuffer;  // RG normal, BA depth code
varying vec3 v_farRay;
#endif

void main() {
  StagePixel pixel = stagePixel(v_uv);
#if STAGE_POSITION || STAGE_NORMAL
  vec4 g = texture2D(u_gbuffer, v_uv);
  float code = unpackDepthCode(g.ba);
  pixel.background = isBackgroundCode(code);
  // The background's ray is the far-plane ray itself: only its direction counts.
  pixel.viewPosition = pixel.background ? v_farRay : viewPositionOnRay(v_farRay, code * (1.0 / 65535.0));
  pixel.viewNormal = decodeNormal(g.rg);
#endif
  vec4 texel = texture2D(u_color, v_uv);
#if STAGE_INPUT_DISPLAY
  vec3 color = texel.rgb;
#else
  vec3 color = decodeHdr(texel);
#endif
  gl_FragColor = finishPixel(color, pixel);
}
