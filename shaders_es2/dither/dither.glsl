// Dithering before 8-bit quantisation (src/effects/dither/Dither.h: why triangular noise of one step, why the same
// pattern every frame, and the CPU mirror): two hashes of the pixel, r1 + r2 - 1 in [-1, 1] with a triangular
// distribution, times one step of the 8-bit target (less within a step of black and white, none at them), added to the
// display colour before it is written. The last
// per-pixel stage (its pixel: gl_FragCoord). Needs lib/precision.glsl and lib/stage.glsl first.
#include "lib/hash.glsl"

vec3 dither(vec3 srgb, vec2 pixel) {
  float r1 = hash12(pixel);
  float r2 = hash12(pixel + vec2(57.31, 113.7));
  // Less noise within a step of black and white, none at them: the target would clamp it there, moving the mean.
  vec3 amplitude = clamp(min(srgb, 1.0 - srgb) * 255.0, 0.0, 1.0);
  return srgb + amplitude * ((r1 + r2 - 1.0) * (1.0 / 255.0));
}

vec3 ditherStage(vec3 srgb, StagePixel pixel) { return dither(srgb, gl_FragCoord.xy); }
