// Bloom (src/effects/bloom/BloomEffect.h: the method, its sources and the CPU mirror of these weights), one stage per
// program:
//   BLOOM_STAGE 0 prefilter, first half: the soft threshold per texel of the scene colour, and the mean of each 2 x 2
//                 block of it, on the even grid (texels 2k, 2k + 1) and on the odd one (2k - 1, 2k) side by side
//               1 prefilter, second half: the 13-tap downsample to 1/2 from those blocks (9 even, 4 odd)
//               2 downsample: the 13-tap filter, level k-1 -> level k
//               3 horizontal tent: up_k+1 filtered along x to level k's width (its own height)
//               4 upsample: up_k = mix(level_k, tent(up_k+1), radius), the tent finished along y from stage 3
//               5 composite: scene colour + intensity x tent(up_1), the tent finished along y from stage 3; a stage
//                 head (its colour goes to finishPixel: the stages fused after it)
// The tent is separable (its weights are w(i) w(j)), so a 4 x 4 tent takes 4 + 4 fetches in two passes.
// Every texture is RGB9E5 in RGBA8 (lib/hdr.glsl), fetched NEAREST at texel centres and decoded before filtering:
// the hardware's bilinear filter would average the encoded bytes.
#include "lib/precision.glsl"
#include "lib/hdr.glsl"

// The scene colour (0), stage 0's blocks (1), the finer level (2), the coarser up (3), stage 3's result (4, 5).
uniform sampler2D u_source;
uniform vec2 u_sourceSize;   // its size in texels
#if BLOOM_STAGE <= 1
uniform float u_evenColumns; // the even grid's columns in stage 0's target: the odd grid's begin there
#endif
#if BLOOM_STAGE == 0
uniform vec3 u_threshold;    // (T, K, 1 / (4 K)) (0 for K = 0)
#endif
#if BLOOM_STAGE >= 4
uniform sampler2D u_level;   // at this pixel: level k (4), the scene colour (5); the same size as the output
#endif
#if BLOOM_STAGE == 4
uniform float u_radius;
#endif
#if BLOOM_STAGE == 5
uniform float u_intensity;
#endif

varying vec2 v_uv;

vec3 fetch(vec2 texel) { return decodeHdr(texture2D(u_source, (texel + 0.5) / u_sourceSize)); }

#if BLOOM_STAGE == 0
// c(m) / m for the largest channel m: c = 0 up to T, (m - T)^2 / (4K) up to T + 2K, m - T - K above.
vec3 thresholded(vec3 c) {
  float m = max(c.r, max(c.g, c.b));
  float x = max(m - u_threshold.x, 0.0);
  float kept = x < 2.0 * u_threshold.y ? x * x * u_threshold.z : x - u_threshold.y;
  return m > 0.0 ? c * (kept / m) : vec3(0.0);
}

// The 13-tap filter's weights (below) are a_i a_j / 2 + b_i b_j / 2 over six texels per axis, and both parts are
// made of 2 x 2 blocks: a = (1, 1, 2, 2, 1, 1) / 8 is (1, 2, 1) / 4 over the three blocks on the even grid, b =
// (0, 1, 1, 1, 1, 0) / 4 the mean of the two on the odd grid. So this pass thresholds each texel of the frame twice
// (once per grid) and averages the blocks, and stage 1 filters 9 + 4 of them: 2 + 3.25 decoded texels per frame pixel
// instead of the 9 (and 9 thresholds) of the 13 taps read texel by texel. Column c < u_evenColumns holds the even
// block k = c - 1 (texels 2k, 2k + 1 in each axis; row r: k = r - 1); column u_evenColumns + c and row r the odd block
// c (texels 2c - 1, 2c; row r: 2r - 1, 2r). Texels beyond the frame clamp to its edge, as the 13 taps' do.
vec3 block() {
  vec2 cell = floor(gl_FragCoord.xy);
  float odd = cell.x >= u_evenColumns ? 1.0 : 0.0;
  vec2 first = 2.0 * vec2(cell.x - odd * u_evenColumns, cell.y) - 2.0 + odd;
  return 0.25 * (thresholded(fetch(first)) + thresholded(fetch(first + vec2(1.0, 0.0))) +
                 thresholded(fetch(first + vec2(0.0, 1.0))) + thresholded(fetch(first + vec2(1.0, 1.0))));
}
#elif BLOOM_STAGE == 1
// Level 1 at pixel (o, p): a_i a_j / 2 over texels 2o - 2 .. 2o + 3 is (1, 2, 1) / 4 over even blocks o - 1 .. o + 1
// (columns o .. o + 2), b_i b_j / 2 the mean of odd blocks o, o + 1 (columns u_evenColumns + o, + o + 1).
vec3 fromBlocks() {
  vec2 cell = floor(gl_FragCoord.xy);
  vec3 even = vec3(0.0);
  for (int j = 0; j < 3; j++) {
    float wj = j == 1 ? 0.5 : 0.25;
    for (int i = 0; i < 3; i++) even += fetch(cell + vec2(float(i), float(j))) * (wj * (i == 1 ? 0.5 : 0.25));
  }
  vec2 odd = cell + vec2(u_evenColumns, 0.0);
  return 0.5 * even + 0.125 * (fetch(odd) + fetch(odd + vec2(1.0, 0.0)) + fetch(odd + vec2(0.0, 1.0)) +
                               fetch(odd + vec2(1.0, 1.0)));
}
#elif BLOOM_STAGE == 2
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
      sum += fetch(corner + vec2(oi, oj) - 0.5) * (0.5 * (ai * aj + bi * bj));
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
#if BLOOM_STAGE == 0
  gl_FragColor = encodeHdr(block());
#elif BLOOM_STAGE == 1
  gl_FragColor = encodeHdr(fromBlocks());
#elif BLOOM_STAGE == 2
  gl_FragColor = encodeHdr(downsample());
#elif BLOOM_STAGE == 3
  gl_FragColor = encodeHdr(tentAlong(vec2(1.0, 0.0)));
#elif BLOOM_STAGE == 4
  gl_FragColor = encodeHdr(mix(decodeHdr(texture2D(u_level, v_uv)), tentAlong(vec2(0.0, 1.0)), u_radius));
#else
  // The stages fused after the composite (the tone curve, ...: frame/Stage.h), or the HDR encoding alone.
  gl_FragColor = finishPixel(decodeHdr(texture2D(u_level, v_uv)) + u_intensity * tentAlong(vec2(0.0, 1.0)),
                             stagePixel(v_uv));
#endif
}
