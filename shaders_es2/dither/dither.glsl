// Dithering before 8-bit quantisation (src/effects/dither/Dither.h: why triangular noise of one step, and the CPU
// mirror): two hashes of the pixel and the frame, r1 + r2 - 1 in [-1, 1] with a triangular distribution, times one
// step of the 8-bit target, added to the display colour before it is written. Needs lib/precision.glsl and
// lib/hash.glsl first.
uniform vec2 u_ditherSeed;  // the frame's: a new pattern each frame

vec3 dither(vec3 srgb, vec2 pixel) {
  float r1 = hash12(pixel + u_ditherSeed);
  float r2 = hash12(pixel + u_ditherSeed + vec2(57.31, 113.7));
  return srgb + vec3((r1 + r2 - 1.0) * (1.0 / 255.0));
}
