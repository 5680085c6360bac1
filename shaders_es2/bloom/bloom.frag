// Bloom (src/effects/bloom/BloomEffect.h: the method, its sources and the CPU mirror of these weights), one stage per
// program:
//   BLOOM_STAGE 0 prefilter: the soft threshold per texel of the scene colour, then the 13-tap downsample to 1/2
//               1 downsample: the 13-tap filter, level k-1 -> level k
//               2 horizontal tent: up_k+1 filtered along x to level k's width (its own height)
//               3 upsample: up_k = mix(level_k, tent(up_k+1), radius), the tent finished along y from stage 2
//               4 composite: scene colour + intensity x tent(up_1), the tent finished along y from stage 2; a stage
//                 head (its colour goes to finishPixel: the stages fused after it)
// The tent is separable (its weights are w(i) w(j)), so a 4 x 4 tent takes 4 + 4 fetches in two passes.
// Every texture is RGB9E5 in RGBA8 (lib/hdr.glsl), fetched NEAREST at texel centres and decoded before filtering:
// the hardware's bilinear filter would average the encoded bytes.
#include "lib/precision.glsl"
#include "lib/hdr.glsl"

uniform sampler2D u_source;  // the scene colour (0), the finer level (1), the coarser up (2), stage 2's result (3, 4)
uniform vec2 u_sourceSize;   // its size in texels
#if BLOOM_STAGE == 0
uniform vec3 u_threshold;    // (T, K, 1 / (4 K)) (0 for K = 0)
#endif
#if BLOOM_STAGE >= 3
uniform sampler2D u_level;   // at this pixel: level k (3), the scene colour (4); the same size as the output
#endif
#if BLOOM_STAGE == 3
uniform float u_radius;
#endif
#if BLOOM_STAGE == 4
uniform float u_intensity;
#endif

varying vec2 v_uv;

vec3 fetch(vec2 texel) { return decodeHdr(texture2D(u_source, (texel + 0.5) / u_sourceSize)); }

#if BLOOM_STAGE <= 1
#if BLOOM_STAGE == 0
// c(m) / m for the largest channel m: c = 0 up to T, (m - T)^2 / (4K) up to T + 2K, m - T - K above.
vec3 thresholded(vec3 c) {
  float m = max(c.r, max(c.g, c.b));
  float x = max(m - u_threshold.x, 0.0);
  float kept = x < 2.0 * u_threshold.y ? x * x * u_threshold.z : x - u_threshold.y;
  return m > 0.0 ? c * (kept / m) : vec3(0.0);
}
#endif

// Jimenez 2014's 13 bilinear taps, as weights over the 6 x 6 texels they cover: a_i a_j / 2 + b_i b_j / 2 with
// a = (1, 1, 2, 2, 1, 1) / 8 and b = (0, 1, 1, 1, 1, 0) / 4 over texel offsets -3 .. 2 from the corner nearest to
// the pixel's centre.
vec3 downsample() {
  vec2 corner = floor(v_uv * u_sourceSize + 0.5);
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 6; j++) {
    float oj = float(j) - 2.5;
    float aj = abs(oj) < 1.0 ? 0.25 : 0.125;
    float bj = abs(oj) < 2.0 ? 0.25 : 0.0;
    for (int i = 0; i < 6; i++) {
      float oi = float(i) - 2.5;
      float ai = abs(oi) < 1.0 ? 0.25 : 0.125;
      float bi = abs(oi) < 2.0 ? 0.25 : 0.0;
      vec3 c = fetch(corner + vec2(oi, oj) - 0.5);
#if BLOOM_STAGE == 0
      c = thresholded(c);
#endif
      sum += c * (0.5 * (ai * aj + bi * bj));
    }
  }
  return sum;
}
#else
// The 3 x 3 tent (1, 2, 1) x (1, 2, 1) / 16 of bilinear taps one source texel apart, by hand over the 4 x 4 texels
// it covers: texel i0 - 1 + k weighs (1 - f) / 4, 1/2 - f/4, 1/4 + f/4, f/4 for k = 0 .. 3 in each axis, one axis
// per pass. The other axis is the output's own: its texel centre, fetched as it is.
vec4 tentWeights(float f) { return vec4(0.25 - 0.25 * f, 0.5 - 0.25 * f, 0.25 + 0.25 * f, 0.25 * f); }

vec3 tentAlong(vec2 axis) {
  vec2 p = v_uv * u_sourceSize - 0.5;
  float along = dot(p, axis);
  float i0 = floor(along);
  vec4 w = tentWeights(along - i0);
  // The texel of this row (or column) across the axis, and i0 - 1 along it.
  vec2 base = floor(p + 0.5) * (1.0 - axis) + (i0 - 1.0) * axis;
  return fetch(base) * w.x + fetch(base + axis) * w.y + fetch(base + 2.0 * axis) * w.z + fetch(base + 3.0 * axis) * w.w;
}
#endif

void main() {
#if BLOOM_STAGE <= 1
  gl_FragColor = encodeHdr(downsample());
#elif BLOOM_STAGE == 2
  gl_FragColor = encodeHdr(tentAlong(vec2(1.0, 0.0)));
#elif BLOOM_STAGE == 3
  gl_FragColor = encodeHdr(mix(decodeHdr(texture2D(u_level, v_uv)), tentAlong(vec2(0.0, 1.0)), u_radius));
#else
  // The stages fused after the composite (the tone curve, ...: frame/Stage.h), or the HDR encoding alone.
  gl_FragColor = finishPixel(decodeHdr(texture2D(u_level, v_uv)) + u_intensity * tentAlong(vec2(0.0, 1.0)),
                             stagePixel(v_uv));
#endif
}
