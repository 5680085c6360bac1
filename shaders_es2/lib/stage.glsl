// Per-pixel stages (src/frame/Stage.h): what a stage's function sees of its pixel, and how a program that runs a chain
// of stages encodes its last colour. A fused program defines, before its head's file,
//   vec4 finishPixel(vec3 color, StagePixel pixel)
// (the chain's functions in turn, then stageOutput), and the head's main calls it with the colour it computed.
//   STAGE_POSITION 1 / STAGE_NORMAL 1   a stage reads the pixel's position / normal: the head fills them in
//   STAGE_OUTPUT_DISPLAY 1              the chain ends in display colour (after the tone curve), else in HDR
// Needs lib/precision.glsl first.
#include "lib/hdr.glsl"
#include "lib/srgb.glsl"

struct StagePixel {
  vec2 uv;            // the pixel's centre, [0, 1]^2
  vec3 viewPosition;  // STAGE_POSITION: the surface's view-space position; the background: a ray through the pixel
  vec3 viewNormal;    // STAGE_NORMAL: the surface's view-space normal, unit
  bool background;    // nothing was drawn at the pixel (STAGE_POSITION or STAGE_NORMAL)
};

StagePixel stagePixel(vec2 uv) {
  StagePixel pixel;
  pixel.uv = uv;
  pixel.viewPosition = vec3(0.0, 0.0, -1.0);
  pixel.viewNormal = vec3(0.0, 0.0, 1.0);
  pixel.background = false;
  return pixel;
}

#if STAGE_OUTPUT_DISPLAY
uniform float u_lumaInAlpha;  // 1: the display luma in alpha (FXAA's input); 0: alpha 1 (the output framebuffer)
vec4 stageOutput(vec3 display) { return vec4(display, mix(1.0, fxaaLuma(display), u_lumaInAlpha)); }
#else
vec4 stageOutput(vec3 linear) { return encodeHdr(linear); }
#endif
