#include "encoding/HdrEncoding.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/matrix.hpp>

#include "encoding/ColorSpaces.h"

namespace obscura {
namespace {

// Every step below is written in the shader's order and in float, so the CPU rounds where the GPU does.

// Tracks how close the inexactly computed values came to a byte boundary (see encodeHdr's roundingMargin).
struct Rounding {
  float margin = std::numeric_limits<float>::infinity();

  float round(float x) {  // floor(x + 0.5): changes at k + 0.5
    margin = std::min(margin, std::abs(x - std::floor(x) - 0.5f));
    return std::floor(x + 0.5f);
  }
  float floor(float x) {  // changes at integers
    const float f = x - std::floor(x);
    margin = std::min(margin, std::min(f, 1.0f - f));
    return std::floor(x);
  }
  float ceil(float x) {
    const float f = x - std::floor(x);
    margin = std::min(margin, std::min(f, 1.0f - f));
    return std::ceil(x);
  }
};

// max(v, 0) that also sends NaN to 0.
float nonNegative(float v) { return v > 0.0f ? v : 0.0f; }
glm::vec3 nonNegative(const glm::vec3& v) { return {nonNegative(v.r), nonNegative(v.g), nonNegative(v.b)}; }
float max3(const glm::vec3& v) { return std::max(v.r, std::max(v.g, v.b)); }
std::uint8_t byte(float b) { return static_cast<std::uint8_t>(b); }

// GLSL's step(edge, x).
float step(float edge, float x) { return x < edge ? 0.0f : 1.0f; }

// lib/hdr.glsl's hdrExponentStep: binary search for floor(log2(x)) with exact products by powers of two.
// r = (n, 2^(lo + n), 2^-(lo + n)); takes bit k (up = 2^k, down = 2^-k) when x >= 2^(lo + n + k).
glm::vec3 exponentStep(const glm::vec3& r, float x, float k, float up, float down) {
  const float s = step(r.y * up, x);
  return {r.x + s * k, s > 0.0f ? r.y * up : r.y, s > 0.0f ? r.z * down : r.z};
}

// lib/hdr.glsl's HDR_MULTIPLIER_SLACK: RGBM's multiplier and RGBD's divisor are taken within it of a whole number (a
// decoded texel encoded again gives one exactly, which a GPU's inexact division puts a rounding off).
constexpr float kMultiplierSlack = 1e-3f;

// ---- RGBM ----
HdrTexel encodeRgbm(const glm::vec3& linear, float range, Rounding& r) {
  const glm::vec3 c = glm::min(nonNegative(linear), glm::vec3(range));
  const float m = std::max(r.ceil(max3(c) * (255.0f / range) - kMultiplierSlack), 1.0f);
  const float k = 65025.0f / range;
  HdrTexel t;
  for (int i = 0; i < 3; ++i) t[i] = byte(std::min(r.round(c[i] * k / m), 255.0f));
  t[3] = byte(m);
  return t;
}
glm::vec3 decodeRgbm(const HdrTexel& t, float range) {
  const float scale = static_cast<float>(t[3]) * (range / 65025.0f);
  return glm::vec3(t[0], t[1], t[2]) * scale;
}

// ---- RGBD ----
HdrTexel encodeRgbd(const glm::vec3& linear, float range, Rounding& r) {
  const glm::vec3 c = glm::min(nonNegative(linear), glm::vec3(range));
  // max(.., range / 512) keeps the division finite for black; D clamps to 255 there anyway.
  const float d = std::clamp(r.floor(range / std::max(max3(c), range / 512.0f) + kMultiplierSlack), 1.0f, 255.0f);
  const float k = 255.0f / range;
  HdrTexel t;
  for (int i = 0; i < 3; ++i) t[i] = byte(std::min(r.round(c[i] * d * k), 255.0f));
  t[3] = byte(d);
  return t;
}
glm::vec3 decodeRgbd(const HdrTexel& t, float range) {
  return glm::vec3(t[0], t[1], t[2]) * (range / 255.0f) / static_cast<float>(t[3]);
}

// ---- RGBE (Ward) ----
constexpr float kRgbeMax = 4294967296.0f * (255.0f / 256.0f);  // 2^32 * 255/256: e <= 32
constexpr float kRgbeMin = 2.3283064365386963e-10f;             // 2^-32: below it the texel is black

HdrTexel encodeRgbe(const glm::vec3& linear) {
  const glm::vec3 c = glm::min(nonNegative(linear), glm::vec3(kRgbeMax));
  const float maxc = max3(c);
  if (maxc < kRgbeMin) return {0, 0, 0, 0};
  // n = floor(log2(maxc)) + 32 in [0, 63]; maxc = m 2^e with m in [0.5, 1) for e = n - 31, E = e + 128 = n + 97.
  glm::vec3 r(0.0f, kRgbeMin, 4294967296.0f);
  r = exponentStep(r, maxc, 32.0f, 4294967296.0f, 2.3283064365386963e-10f);
  r = exponentStep(r, maxc, 16.0f, 65536.0f, 1.52587890625e-05f);
  r = exponentStep(r, maxc, 8.0f, 256.0f, 0.00390625f);
  r = exponentStep(r, maxc, 4.0f, 16.0f, 0.0625f);
  r = exponentStep(r, maxc, 2.0f, 4.0f, 0.25f);
  r = exponentStep(r, maxc, 1.0f, 2.0f, 0.5f);
  const float scale = 128.0f * r.z;  // 2^(8 - e)
  HdrTexel t;
  for (int i = 0; i < 3; ++i) t[i] = byte(std::floor(c[i] * scale));  // exact: a product by a power of two
  t[3] = byte(r.x + 97.0f);
  return t;
}
glm::vec3 decodeRgbe(const HdrTexel& t) {
  if (t[3] == 0) return glm::vec3(0.0f);
  return (glm::vec3(t[0], t[1], t[2]) + 0.5f) * std::exp2(static_cast<float>(t[3]) - 136.0f);
}

// ---- RGB9E5 (EXT_texture_shared_exponent) ----
constexpr float kRgb9e5Max = 65408.0f;  // (2^9 - 1) / 2^9 * 2^(31 - 15)

HdrTexel encodeRgb9e5(const glm::vec3& linear) {
  const glm::vec3 c = glm::min(nonNegative(linear), glm::vec3(kRgb9e5Max));
  const float maxc = max3(c);
  // exp_shared_p = max(-B - 1, floor(log2(maxc))) + 1 + B, B = 15; maxc below 2^-16 takes the denormal exponent 0.
  // exp_shared_p = max(-B - 1, floor(log2(maxc))) + 1 + B in [0, 31]; 1 / 2^(exp - B - N) = 2^8 * 2^-(exp - 16).
  glm::vec3 r(0.0f, 1.52587890625e-05f, 65536.0f);
  r = exponentStep(r, maxc, 16.0f, 65536.0f, 1.52587890625e-05f);
  r = exponentStep(r, maxc, 8.0f, 256.0f, 0.00390625f);
  r = exponentStep(r, maxc, 4.0f, 16.0f, 0.0625f);
  r = exponentStep(r, maxc, 2.0f, 4.0f, 0.25f);
  r = exponentStep(r, maxc, 1.0f, 2.0f, 0.5f);
  float e = r.x;
  float scale = 256.0f * r.z;
  // The spec rounds the largest mantissa and takes the next exponent if it rounds up to 2^9.
  const float up = step(511.5f, maxc * scale);
  e += up;
  scale *= 1.0f - 0.5f * up;
  HdrTexel t;
  float high = 0.0f;
  for (int i = 0; i < 3; ++i) {
    const float m = std::floor(c[i] * scale + 0.5f);  // exact: a product by a power of two, then + 0.5 below 2^23
    const float h = std::floor(m * (1.0f / 256.0f));
    t[i] = byte(m - h * 256.0f);
    high = high * 2.0f + h;  // red's ninth bit ends up worth 4, green's 2, blue's 1
  }
  t[3] = byte(e * 8.0f + high);
  return t;
}
glm::vec3 decodeRgb9e5(const HdrTexel& t) {
  const float a = static_cast<float>(t[3]);
  const float e = std::floor(a * (1.0f / 8.0f));
  float bits = a - e * 8.0f;
  const float rh = std::floor(bits * 0.25f);
  bits -= rh * 4.0f;
  const float gh = std::floor(bits * 0.5f);
  const float bh = bits - gh * 2.0f;
  const glm::vec3 m = glm::vec3(t[0], t[1], t[2]) + 256.0f * glm::vec3(rh, gh, bh);
  return m * std::exp2(e - 24.0f);
}

// ---- LogLuv ----
// 2^-17: black below it (log2 is undefined at 0); up to 2^(-16 + 1/4096) the code rounds to 0, black too.
constexpr float kLogLuvBlack = 7.62939453125e-06f;

HdrTexel encodeLogLuv(const glm::vec3& linear, Rounding& r) {
  const LogLuvConstants& k = logLuvConstants();
  const glm::vec3 w = k.encode * nonNegative(linear);  // (4X, Y, X + 15Y + 3Z)
  if (w.y < kLogLuvBlack) return {byte(kLogLuvWhiteU), byte(kLogLuvWhiteV), 0, 0};
  // Code 0 decodes as black: luminance below 2^(-16 + 1/4096) rounds to it.
  const float code = std::clamp(r.round((std::log2(w.y) + 16.0f) * 2048.0f), 0.0f, 65535.0f);
  const float high = std::floor(code * (1.0f / 256.0f));
  const float u = std::clamp(r.round((w.x / w.z - k.uOffset) * kLogLuvChromaScale), 0.0f, 255.0f);
  const float v = std::clamp(r.round((9.0f * w.y / w.z - k.vOffset) * kLogLuvChromaScale), 0.0f, 255.0f);
  return {byte(u), byte(v), byte(high), byte(code - high * 256.0f)};
}
glm::vec3 decodeLogLuv(const HdrTexel& t) {
  const LogLuvConstants& k = logLuvConstants();
  const float code = static_cast<float>(t[2]) * 256.0f + static_cast<float>(t[3]);
  if (code < 0.5f) return glm::vec3(0.0f);
  const float y = std::exp2(code * (1.0f / 2048.0f) - 16.0f);
  const float u = static_cast<float>(t[0]) * kLogLuvChromaStep + k.uOffset;
  const float v = static_cast<float>(t[1]) * kLogLuvChromaStep + k.vOffset;
  const float d = 9.0f * y / v;  // X + 15Y + 3Z
  return glm::max(k.decode * glm::vec3(u * d, y, d), glm::vec3(0.0f));
}

}  // namespace

std::string HdrEncoding::name() const {
  switch (kind) {
    case HdrEncodingKind::Rgbm: return "rgbm" + std::to_string(static_cast<int>(range));
    case HdrEncodingKind::Rgbd: return "rgbd" + std::to_string(static_cast<int>(range));
    case HdrEncodingKind::Rgbe: return "rgbe";
    case HdrEncodingKind::Rgb9e5: return "rgb9e5";
    case HdrEncodingKind::LogLuv: return "logluv";
  }
  return "?";
}

std::vector<HdrEncoding> hdrEncodingCandidates() {
  return {{HdrEncodingKind::Rgbm, 8.0f},   {HdrEncodingKind::Rgbm, 16.0f}, {HdrEncodingKind::Rgbm, 64.0f},
          {HdrEncodingKind::Rgbd, 16.0f},  {HdrEncodingKind::Rgbd, 256.0f}, {HdrEncodingKind::Rgbe, 0.0f},
          {HdrEncodingKind::Rgb9e5, 0.0f}, {HdrEncodingKind::LogLuv, 0.0f}};
}

HdrTexel encodeHdr(const glm::vec3& linear, const HdrEncoding& encoding, float* roundingMargin) {
  Rounding r;
  HdrTexel t{};
  switch (encoding.kind) {
    case HdrEncodingKind::Rgbm: t = encodeRgbm(linear, encoding.range, r); break;
    case HdrEncodingKind::Rgbd: t = encodeRgbd(linear, encoding.range, r); break;
    case HdrEncodingKind::Rgbe: t = encodeRgbe(linear); break;
    case HdrEncodingKind::Rgb9e5: t = encodeRgb9e5(linear); break;
    case HdrEncodingKind::LogLuv: t = encodeLogLuv(linear, r); break;
  }
  if (roundingMargin) *roundingMargin = r.margin;
  return t;
}

glm::vec3 decodeHdr(const HdrTexel& t, const HdrEncoding& encoding) {
  switch (encoding.kind) {
    case HdrEncodingKind::Rgbm: return decodeRgbm(t, encoding.range);
    case HdrEncodingKind::Rgbd: return decodeRgbd(t, encoding.range);
    case HdrEncodingKind::Rgbe: return decodeRgbe(t);
    case HdrEncodingKind::Rgb9e5: return decodeRgb9e5(t);
    case HdrEncodingKind::LogLuv: return decodeLogLuv(t);
  }
  return glm::vec3(0.0f);
}

float hdrLargestValue(const HdrEncoding& encoding) {
  switch (encoding.kind) {
    case HdrEncodingKind::Rgbm:
    case HdrEncodingKind::Rgbd: return encoding.range;
    case HdrEncodingKind::Rgbe: return kRgbeMax;
    case HdrEncodingKind::Rgb9e5: return kRgb9e5Max;
    case HdrEncodingKind::LogLuv: return std::exp2(65535.0f / 2048.0f - 16.0f);
  }
  return 0.0f;
}

std::vector<std::pair<std::string, std::string>> hdrShaderDefines(const HdrEncoding& encoding) {
  std::vector<std::pair<std::string, std::string>> defines = {
      {"HDR_ENCODING", std::to_string(static_cast<int>(encoding.kind))}};
  if (encoding.kind == HdrEncodingKind::Rgbm || encoding.kind == HdrEncodingKind::Rgbd)
    defines.emplace_back("HDR_RANGE", std::to_string(static_cast<int>(encoding.range)) + ".0");
  return defines;
}

const LogLuvConstants& logLuvConstants() {
  static const LogLuvConstants constants = [] {
    const glm::dmat3 toXyz = ColorSpaces::rgbToXyz(ColorSpaces::kBt709);
    // (X, Y, Z) -> (4X, Y, X + 15Y + 3Z): u' = 4X / (X + 15Y + 3Z), v' = 9Y / (X + 15Y + 3Z) (CIE 1976 UCS).
    const glm::dmat3 toW(4.0, 0.0, 1.0,    // X's column
                         0.0, 1.0, 15.0,   // Y's
                         0.0, 0.0, 3.0);   // Z's
    // (u' d, Y, d) -> (X, Y, Z): X = u' d / 4, Z = (d - X - 15Y) / 3 = d / 3 - u' d / 12 - 5Y.
    const glm::dmat3 fromW(0.25, 0.0, -1.0 / 12.0,  //
                           0.0, 1.0, -5.0,          //
                           0.0, 0.0, 1.0 / 3.0);
    LogLuvConstants c;
    c.encode = glm::mat3(toW * toXyz);
    c.decode = glm::mat3(glm::inverse(toXyz) * fromW);
    // D65 white's chromaticity, from the matrix itself (rgb = (1, 1, 1)), so that grey encodes on the white codes.
    const glm::dvec3 white = toW * toXyz * glm::dvec3(1.0);
    c.uOffset = static_cast<float>(white.x / white.z - kLogLuvWhiteU / 620.0);
    c.vOffset = static_cast<float>(9.0 * white.y / white.z - kLogLuvWhiteV / 620.0);
    return c;
  }();
  return constants;
}

std::vector<GlslConstant> hdrShaderConstants() {
  const LogLuvConstants& c = logLuvConstants();
  return {glslMat3("LOGLUV_ENCODE", c.encode), glslMat3("LOGLUV_DECODE", c.decode),
          glslFloat("LOGLUV_U_OFFSET", c.uOffset), glslFloat("LOGLUV_V_OFFSET", c.vOffset),
          glslFloat("LOGLUV_CHROMA_SCALE", kLogLuvChromaScale), glslFloat("LOGLUV_CHROMA_STEP", kLogLuvChromaStep),
          glslFloat("LOGLUV_WHITE_U", static_cast<float>(kLogLuvWhiteU)),
          glslFloat("LOGLUV_WHITE_V", static_cast<float>(kLogLuvWhiteV))};
}

}  // namespace obscura
