// Film grain (src/effects/grain/Grain.h: the method and the CPU mirror): value noise of cells `size` pixels wide,
// new each frame, added to the display colour (sRGB-encoded), weighted by 1 - sqrt(luma) so the shadows and
// mid-tones take more of it than the highlights (Unity's post-processing stack's luminance response). A per-pixel
// stage on display colour (its pixel: gl_FragCoord, the frame's pixel in every head). Needs lib/precision.glsl and
// lib/stage.glsl first.
#include "lib/hash.glsl"
uniform vec4 u_grain;  // (intensity, 1 / size in pixels, the frame's seed x, y)

// Smooth value noise in [-1, 1]: the four cells' hashes, blended with smoothstep weights.
float grainNoise(vec2 p) {
  vec2 cell = floor(p);
  vec2 f = p - cell;
  f = f * f * (3.0 - 2.0 * f);
  float a = hash12(cell), b = hash12(cell + vec2(1.0, 0.0));
  float c = hash12(cell + vec2(0.0, 1.0)), d = hash12(cell + vec2(1.0, 1.0));
  return 2.0 * mix(mix(a, b, f.x), mix(c, d, f.x), f.y) - 1.0;
}

vec3 grain(vec3 srgb, vec2 pixel) {
  float n = grainNoise(pixel * u_grain.y + u_grain.zw);
  float response = 1.0 - sqrt(clamp(fxaaLuma(srgb), 0.0, 1.0));
  return srgb + vec3(u_grain.x * response * n);
}

vec3 grainStage(vec3 srgb, StagePixel pixel) { return grain(srgb, gl_FragCoord.xy); }
