// Bloom (src/core/BloomEffect.h: the method, its sources and the CPU mirror of these weights), one stage per program:
//   BLOOM_STAGE 0 prefilter: the soft threshold per texel of the scene colour, then the 13-tap downsample to 1/2
//               1 downsample: the 13-tap filter, level k-1 -> level k
//               2 upsample: up_k = mix(level_k, tent(up_k+1), radius)
//               3 composite: scene colour + intensity x tent(up_1)
// Every texture is RGB9E5 in RGBA8 (lib/hdr.glsl), fetched NEAREST at texel centres and decoded before filtering:
// the hardware's bilinear filter would average the encoded bytes.
#include "lib/precision.glsl"
#include "lib/hdr.glsl"

uniform sampler2D u_source;  // the level filtered: the scene colour (0), the finer level (1), the coarser up (2, 3)
uniform vec2 u_sourceSize;   // its size in texels
#if BLOOM_STAGE == 0
uniform vec3 u_threshold;    // (T, K, 1 / (4 K)) (0 for K = 0)
#endif
#if BLOOM_STAGE >= 2
uniform sampler2D u_level;   // at this pixel: level k (2), the scene colour (3); the same size as the output
#endif
#if BLOOM_STAGE == 2
uniform float u_radius;
#endif
#if BLOOM_STAGE == 3
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
// it covers: texel i0 - 1 + k weighs (1 - f) / 4, 1/2 - f/4, 1/4 + f/4, f/4 for k = 0 .. 3 in each axis.
vec4 tentWeights(float f) { return vec4(0.25 - 0.25 * f, 0.5 - 0.25 * f, 0.25 + 0.25 * f, 0.25 * f); }

vec3 tent() {
  vec2 p = v_uv * u_sourceSize - 0.5;
  vec2 i0 = floor(p);
  vec4 wx = tentWeights(p.x - i0.x);
  vec4 wy = tentWeights(p.y - i0.y);
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 4; j++) {
    float w = j == 0 ? wy.x : (j == 1 ? wy.y : (j == 2 ? wy.z : wy.w));
    vec2 base = i0 + vec2(-1.0, float(j) - 1.0);
    vec3 row = fetch(base) * wx.x + fetch(base + vec2(1.0, 0.0)) * wx.y + fetch(base + vec2(2.0, 0.0)) * wx.z +
               fetch(base + vec2(3.0, 0.0)) * wx.w;
    sum += row * w;
  }
  return sum;
}
#endif

void main() {
#if BLOOM_STAGE <= 1
  gl_FragColor = encodeHdr(downsample());
#elif BLOOM_STAGE == 2
  gl_FragColor = encodeHdr(mix(decodeHdr(texture2D(u_level, v_uv)), tent(), u_radius));
#else
  gl_FragColor = encodeHdr(decodeHdr(texture2D(u_level, v_uv)) + u_intensity * tent());
#endif
}
