// Linear HDR colour in one RGBA8 texel: vec4 encodeHdr(vec3 linear), vec3 decodeHdr(vec4 texel).
// CPU mirror: src/encoding/HdrEncoding.h, which holds the candidates' sources, the measurements behind the choice
// (tools/hdr_encoding_study.cpp) and the tests' bounds. Needs lib/precision.glsl first: the arithmetic is exact in
// highp (binary32) and not in mediump.
//
// Filtering an encoded texture is not filtering the colour: fetch texels with NEAREST, decode, then filter. Never
// blend into an encoded target.
//
// HDR_ENCODING picks the encoding (HdrEncodingKind's values); HDR_RANGE (a float literal) is RGBM's and RGBD's largest
// value. Each byte b is written as (b + 0.25) / 255 (lib/packing.glsl's bytesToChannels), which rounding and truncating
// targets both store as b, so the texel holds exactly the bytes the CPU mirror computes.
#include "lib/packing.glsl"

#define HDR_ENCODING_RGBM 1
#define HDR_ENCODING_RGBD 2
#define HDR_ENCODING_RGBE 3
#define HDR_ENCODING_RGB9E5 4
#define HDR_ENCODING_LOGLUV 5

// The chosen encoding (HdrEncoding.h's kHdrColorEncoding), when the includer sets none.
#ifndef HDR_ENCODING
#define HDR_ENCODING HDR_ENCODING_RGB9E5
#endif

#if (HDR_ENCODING == HDR_ENCODING_RGBM || HDR_ENCODING == HDR_ENCODING_RGBD) && !defined(HDR_RANGE)
#error "RGBM and RGBD need HDR_RANGE (hdrShaderDefines() sets it)"
#endif

vec4 hdrBytesToTexel(vec4 bytes) { return vec4(bytesToChannels(bytes.rg), bytesToChannels(bytes.ba)); }
vec4 hdrTexelToBytes(vec4 texel) { return vec4(channelsToBytes(texel.rg), channelsToBytes(texel.ba)); }

float hdrMax3(vec3 v) { return max(v.r, max(v.g, v.b)); }

// The shared-exponent encodings find their exponent by binary search over its bits, with products by powers of two
// only, which are exact in binary32: no log2, which is an approximation (off by an ulp near powers of two) and, on
// llvmpipe, dearer than the whole search. r = (n, 2^(lo + n), 2^-(lo + n)) for a lower bound 2^lo; one step takes the
// bit k (up = 2^k, down = 2^-k) when x >= 2^(lo + n + k). A select, not mix(a, b, s): a driver may compute mix as
// a + s (b - a), which loses b where |a| is far larger (NVIDIA's 580 driver did: RGBE's 2^32 against 1 gave 0, so
// every RGBE mantissa came out 0; docs/robustness.md, "On an NVIDIA GPU").
vec3 hdrExponentStep(vec3 r, float x, float k, float up, float down) {
  return x >= r.y * up ? vec3(r.x + k, r.y * up, r.z * down) : r;
}

#if HDR_ENCODING == HDR_ENCODING_RGBM || HDR_ENCODING == HDR_ENCODING_RGBD
// RGBM's multiplier and RGBD's divisor are whole numbers in exact arithmetic when a decoded texel is encoded again; a
// GPU's inexact division (NVIDIA's driver: a reciprocal and a product) puts them a rounding above or below, where ceil
// and floor would take the next code (RGBD's round trip on an H200, 2026-11-29: 255 255 255 160 -> 253 253 253 159).
// They are taken within this slack of the whole number instead, as encoding/HdrEncoding.cpp does.
const float HDR_MULTIPLIER_SLACK = 1e-3;
#endif

#if HDR_ENCODING == HDR_ENCODING_RGBM
// Karis 2009 (three.js LinearToRGBM): multiplier quantised up, so every channel / (M R) <= 1.
vec4 encodeHdr(vec3 linear) {
  vec3 c = clamp(linear, 0.0, HDR_RANGE);
  float m = max(ceil(hdrMax3(c) * (255.0 / HDR_RANGE) - HDR_MULTIPLIER_SLACK), 1.0);
  vec3 rgb = min(floor(c * (65025.0 / HDR_RANGE) / m + 0.5), 255.0);
  return hdrBytesToTexel(vec4(rgb, m));
}

vec3 decodeHdr(vec4 texel) {
  vec4 b = hdrTexelToBytes(texel);
  return b.rgb * (b.a * (HDR_RANGE / 65025.0));
}

#elif HDR_ENCODING == HDR_ENCODING_RGBD
// three.js LinearToRGBD: D = clamp(floor(R / max), 1, 255); max(.., R / 512) keeps the division finite for black.
vec4 encodeHdr(vec3 linear) {
  vec3 c = clamp(linear, 0.0, HDR_RANGE);
  float d = clamp(floor(HDR_RANGE / max(hdrMax3(c), HDR_RANGE / 512.0) + HDR_MULTIPLIER_SLACK), 1.0, 255.0);
  vec3 rgb = min(floor(c * d * (255.0 / HDR_RANGE) + 0.5), 255.0);
  return hdrBytesToTexel(vec4(rgb, d));
}

vec3 decodeHdr(vec4 texel) {
  vec4 b = hdrTexelToBytes(texel);
  return b.rgb * (HDR_RANGE / 255.0) / b.a;
}

#elif HDR_ENCODING == HDR_ENCODING_RGBE
// Ward 1991: max = m 2^e, m in [0.5, 1); mantissas truncated, decoded at the step's centre; E = 0 is black. e is kept
// in [-31, 32] (every 2^k a normal float, inside GLSL ES's minimum highp range 2^62): 2^32 * 255/256 and 2^-32.
const float RGBE_MAX = 4278190080.0;
const float RGBE_MIN = 2.3283064365386963e-10;

vec4 encodeHdr(vec3 linear) {
  vec3 c = clamp(linear, 0.0, RGBE_MAX);
  float maxc = hdrMax3(c);
  if (maxc < RGBE_MIN) return hdrBytesToTexel(vec4(0.0));
  // n = floor(log2(maxc)) + 32 in [0, 63], so e = n - 31 and 2^(8 - e) = 2^7 * 2^-(n - 32).
  vec3 r = vec3(0.0, RGBE_MIN, 4294967296.0);
  r = hdrExponentStep(r, maxc, 32.0, 4294967296.0, 2.3283064365386963e-10);
  r = hdrExponentStep(r, maxc, 16.0, 65536.0, 1.52587890625e-05);
  r = hdrExponentStep(r, maxc, 8.0, 256.0, 0.00390625);
  r = hdrExponentStep(r, maxc, 4.0, 16.0, 0.0625);
  r = hdrExponentStep(r, maxc, 2.0, 4.0, 0.25);
  r = hdrExponentStep(r, maxc, 1.0, 2.0, 0.5);
  return hdrBytesToTexel(vec4(floor(c * (128.0 * r.z)), r.x + 97.0));
}

vec3 decodeHdr(vec4 texel) {
  vec4 b = hdrTexelToBytes(texel);
  if (b.a < 0.5) return vec3(0.0);
  return (b.rgb + 0.5) * exp2(b.a - 136.0);
}

#elif HDR_ENCODING == HDR_ENCODING_RGB9E5
// GL_RGB9_E5 (EXT_texture_shared_exponent): N = 9 mantissa bits, bias B = 15, largest (2^9 - 1) / 2^9 * 2^16. RGB hold
// the mantissas' low bytes, A = exponent * 8 + the ninth bits (red 4, green 2, blue 1). Every step of the encoder is
// exact in binary32 (products by powers of two, integers below 2^24), so any GPU writes the CPU's bytes.
const float RGB9E5_MAX = 65408.0;

vec4 encodeHdr(vec3 linear) {
  vec3 c = clamp(linear, 0.0, RGB9E5_MAX);
  float maxc = hdrMax3(c);
  // exp_shared_p = max(-B - 1, floor(log2(maxc))) + 1 + B in [0, 31] (0 below 2^-15, denormals included), and
  // 1 / 2^(exp - B - N) = 2^(24 - exp) = 2^8 * 2^-(exp - 16).
  vec3 r = vec3(0.0, 1.52587890625e-05, 65536.0);
  r = hdrExponentStep(r, maxc, 16.0, 65536.0, 1.52587890625e-05);
  r = hdrExponentStep(r, maxc, 8.0, 256.0, 0.00390625);
  r = hdrExponentStep(r, maxc, 4.0, 16.0, 0.0625);
  r = hdrExponentStep(r, maxc, 2.0, 4.0, 0.25);
  r = hdrExponentStep(r, maxc, 1.0, 2.0, 0.5);
  float e = r.x;
  float scale = 256.0 * r.z;
  // The largest mantissa rounding up to 2^9 takes the next exponent (the spec's exp_shared); halving scale is exact.
  float up = step(511.5, maxc * scale);
  e += up;
  scale *= 1.0 - 0.5 * up;
  vec3 m = floor(c * scale + 0.5);
  vec3 high = floor(m * (1.0 / 256.0));
  return hdrBytesToTexel(vec4(m - high * 256.0, e * 8.0 + dot(high, vec3(4.0, 2.0, 1.0))));
}

vec3 decodeHdr(vec4 texel) {
  vec4 b = hdrTexelToBytes(texel);
  float e = floor(b.a * (1.0 / 8.0));
  float bits = b.a - e * 8.0;
  float redHigh = floor(bits * 0.25);
  bits -= redHigh * 4.0;
  float greenHigh = floor(bits * 0.5);
  vec3 m = b.rgb + 256.0 * vec3(redHigh, greenHigh, bits - greenHigh * 2.0);
  return m * exp2(e - 24.0);  // exp2 of an integer: exact on llvmpipe (tested), at worst an ulp off elsewhere
}

#elif HDR_ENCODING == HDR_ENCODING_LOGLUV
// Ward 1998's LogLuv: Y as round((log2 Y + 16) * 2048) in B (high) and A (low), code 0 black; (u', v') in R and G,
// 620 codes per unit, offset so that D65 white is codes (46, 193). The matrices and offsets are derived from the
// BT.709 primaries by src/encoding/HdrEncoding.cpp (logLuvConstants) and printed by `obscura-hdr-study
// --glsl-constants`; tests/test_hdr_encoding.cpp holds these literals bit-identical to the CPU's floats.
// ---- begin constants generated by obscura-hdr-study --glsl-constants ----
const mat3 LOGLUV_ENCODE = mat3(
    1.6495632, 0.212639, 3.6599684,
    1.4303373, 0.71516865, 11.4426985,
    0.7219232, 0.07219232, 4.114962);
const mat3 LOGLUV_DECODE = mat3(
    0.8517934, -0.24577384, -0.07417344,
    0.9556706, 1.6681923, -5.4888344,
    -0.16620359, 0.013851685, 0.35232383);
const float LOGLUV_U_OFFSET = 0.12363646;
const float LOGLUV_V_OFFSET = 0.15702967;
const float LOGLUV_CHROMA_SCALE = 620.0;
const float LOGLUV_CHROMA_STEP = 0.0016129032;
const float LOGLUV_WHITE_U = 46.0;
const float LOGLUV_WHITE_V = 193.0;
// ---- end generated constants ----

vec4 encodeHdr(vec3 linear) {
  vec3 w = LOGLUV_ENCODE * max(linear, 0.0);  // (4X, Y, X + 15Y + 3Z)
  // Below 2^-17 black (log2 of 0 is undefined); up to 2^(-16 + 1/4096) the code rounds to 0, black too.
  if (w.y < 7.62939453125e-06) return hdrBytesToTexel(vec4(LOGLUV_WHITE_U, LOGLUV_WHITE_V, 0.0, 0.0));
  float code = clamp(floor((log2(w.y) + 16.0) * 2048.0 + 0.5), 0.0, 65535.0);
  float high = floor(code * (1.0 / 256.0));
  float u = clamp(floor((w.x / w.z - LOGLUV_U_OFFSET) * LOGLUV_CHROMA_SCALE + 0.5), 0.0, 255.0);
  float v = clamp(floor((9.0 * w.y / w.z - LOGLUV_V_OFFSET) * LOGLUV_CHROMA_SCALE + 0.5), 0.0, 255.0);
  return hdrBytesToTexel(vec4(u, v, high, code - high * 256.0));
}

vec3 decodeHdr(vec4 texel) {
  vec4 b = hdrTexelToBytes(texel);
  float code = b.b * 256.0 + b.a;
  if (code < 0.5) return vec3(0.0);
  float y = exp2(code * (1.0 / 2048.0) - 16.0);
  float u = b.r * LOGLUV_CHROMA_STEP + LOGLUV_U_OFFSET;
  float v = b.g * LOGLUV_CHROMA_STEP + LOGLUV_V_OFFSET;
  float d = 9.0 * y / v;  // X + 15Y + 3Z
  return max(LOGLUV_DECODE * vec3(u * d, y, d), 0.0);
}

#else
#error "unknown HDR_ENCODING"
#endif
