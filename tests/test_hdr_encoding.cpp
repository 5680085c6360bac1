// CPU tests of the HDR-in-RGBA8 mirrors (src/encoding/HdrEncoding.h): the round-trip error bounds measured by
// obscura-hdr-study, monotonic luminance, black and the range ends, clamping, RGB9E5 against the extension's own
// pseudo-code, LogLuv's grey and gamut, and the literals lib/hdr.glsl shares with the CPU (bit-identical).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <glm/geometric.hpp>

#include "encoding/ColorSpaces.h"
#include "encoding/HdrEncoding.h"
#include "gl/ShaderLibrary.h"

using namespace obscura;

namespace {

const glm::vec3 kLuminance(0.2126f, 0.7152f, 0.0722f);

glm::vec3 roundTrip(const glm::vec3& c, const HdrEncoding& e) { return decodeHdr(encodeHdr(c, e), e); }
float max3(const glm::vec3& v) { return std::max(v.r, std::max(v.g, v.b)); }

// Colours of 64 hues x 5 saturations whose brightest channel runs log-spaced from `lowest` to `highest`.
template <typename F>
void forEachColour(float lowest, float highest, int steps, F&& f) {
  for (int h = 0; h < 64; ++h)
    for (float s : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
      if (s == 0.0f && h > 0) continue;
      const glm::vec3 base = ColorSpaces::hsvColor(static_cast<float>(h) / 64.0f, s);
      for (int i = 0; i <= steps; ++i)
        f(base * (lowest * std::pow(highest / lowest, static_cast<float>(i) / static_cast<float>(steps))), i == 0);
    }
}

struct Bound {
  const char* name;
  float lowest;              // the brightest channel's smallest value the bound covers
  double maxError, meanError;  // |decoded - c| per channel over c's brightest channel
};

// Measured on this test's colours (64 hues x 5 saturations, brightest channel log-spaced in 4000 steps; the figures
// in brackets), with a little headroom. RGBM and RGBD are linear: their precision is relative to the range, so they
// hold a bound only above range / 16 (below, see obscura-hdr-study's "smallest (1 %)").
const Bound kBounds[] = {
    {"rgbm8", 0.5f, 0.0021, 0.0015},       // [0.208 %, 0.146 %]
    {"rgbm16", 1.0f, 0.0021, 0.0015},      // [0.208 %, 0.146 %]
    {"rgbm64", 4.0f, 0.0021, 0.0015},      // [0.208 %, 0.146 %]
    {"rgbd16", 1.0f, 0.0039, 0.0018},      // [0.389 %, 0.171 %]
    {"rgbd256", 16.0f, 0.0039, 0.0018},    // [0.389 %, 0.171 %]
    {"rgbe", 1e-4f, 0.003907, 0.0023},     // [0.391 %, 0.227 %]: 0.5 / 128, Ward's centred decoding
    {"rgb9e5", 1e-4f, 0.001953, 0.00105},  // [0.195 %, 0.102 %]: 0.5 / 256, a 9-bit mantissa rounded to nearest
    {"logluv", 1e-2f, 0.0130, 0.0060},     // [1.26 %, 0.581 %]: chroma, 620 steps per unit of u' and v'
};

const Bound& boundFor(const HdrEncoding& e) {
  for (const Bound& b : kBounds)
    if (e.name() == b.name) return b;
  throw std::logic_error("no bound for " + e.name());
}

}  // namespace

TEST(HdrEncoding, TheChosenEncodingIsRgb9e5AndTheShaderDefaultsToIt) {
  EXPECT_EQ(kHdrColorEncoding.kind, HdrEncodingKind::Rgb9e5);
  const std::string source(ShaderLibrary::file("lib/hdr.glsl"));
  EXPECT_NE(source.find("#define HDR_ENCODING HDR_ENCODING_RGB9E5\n"), std::string::npos);
  const std::pair<const char*, HdrEncodingKind> names[] = {
      {"RGBM", HdrEncodingKind::Rgbm},     {"RGBD", HdrEncodingKind::Rgbd},     {"RGBE", HdrEncodingKind::Rgbe},
      {"RGB9E5", HdrEncodingKind::Rgb9e5}, {"LOGLUV", HdrEncodingKind::LogLuv}};
  for (const auto& [name, kind] : names) {
    const std::string line = std::string("#define HDR_ENCODING_") + name + " " + std::to_string(static_cast<int>(kind));
    EXPECT_NE(source.find(line + "\n"), std::string::npos) << line;
  }
  EXPECT_EQ(hdrShaderDefines(kHdrColorEncoding),
            (std::vector<std::pair<std::string, std::string>>{{"HDR_ENCODING", "4"}}));
  EXPECT_EQ(hdrShaderDefines({HdrEncodingKind::Rgbm, 16.0f}),
            (std::vector<std::pair<std::string, std::string>>{{"HDR_ENCODING", "1"}, {"HDR_RANGE", "16.0"}}));
}

TEST(HdrEncoding, RoundTripErrorStaysWithinTheMeasuredBounds) {
  for (const HdrEncoding& e : hdrEncodingCandidates()) {
    const Bound& bound = boundFor(e);
    double worst = 0.0, sum = 0.0;
    long count = 0;
    forEachColour(bound.lowest, std::min(hdrLargestValue(e), 65408.0f), 4000, [&](const glm::vec3& c, bool) {
      if (e.kind == HdrEncodingKind::LogLuv && glm::dot(c, kLuminance) > hdrLargestValue(e)) return;
      const glm::vec3 d = glm::abs(roundTrip(c, e) - c);
      const double error = max3(d) / max3(c);
      worst = std::max(worst, error);
      sum += error;
      ++count;
    });
    EXPECT_LE(worst, bound.maxError) << e.name();
    EXPECT_LE(sum / static_cast<double>(count), bound.meanError) << e.name();
    RecordProperty(e.name() + "_max_percent", std::to_string(worst * 100.0));
  }
}

TEST(HdrEncoding, DecodedLuminanceNeverDecreasesAlongARamp) {
  // Greys for every encoding but RGBM and RGBD, and every hue and saturation for the chosen one and LogLuv. RGBM's
  // and RGBD's multiplier steps make the decoded value step back (measured: up to 1.4 %), bounded below.
  for (const HdrEncoding& e : hdrEncodingCandidates()) {
    const bool linear = e.kind == HdrEncodingKind::Rgbm || e.kind == HdrEncodingKind::Rgbd;
    const bool everyHue = e.kind == HdrEncodingKind::Rgb9e5 || e.kind == HdrEncodingKind::LogLuv;
    float previous = 0.0f;
    forEachColour(1e-4f, std::min(hdrLargestValue(e), 65408.0f), 20000, [&](const glm::vec3& c, bool first) {
      if (first) previous = 0.0f;
      if (!everyHue && !(c.r == c.g && c.g == c.b)) return;
      if (e.kind == HdrEncodingKind::LogLuv && glm::dot(c, kLuminance) > hdrLargestValue(e)) return;
      const float luminance = glm::dot(roundTrip(c, e), kLuminance);
      if (linear) ASSERT_GE(luminance, previous * (1.0f - 0.015f)) << e.name() << " at " << c.r;
      else ASSERT_GE(luminance, previous) << e.name() << " at (" << c.r << ", " << c.g << ", " << c.b << ")";
      previous = luminance;
    });
  }
}

TEST(HdrEncoding, BlackAndTheRangeEnds) {
  for (const HdrEncoding& e : hdrEncodingCandidates()) {
    EXPECT_EQ(roundTrip(glm::vec3(0.0f), e), glm::vec3(0.0f)) << e.name();
    const float top = hdrLargestValue(e);
    const glm::vec3 largest = roundTrip(glm::vec3(top), e);
    const float tolerance = e.kind == HdrEncodingKind::Rgbe ? 0.5f / 255.0f : 1e-5f;  // Ward decodes at step centres
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(largest[c], top, top * tolerance) << e.name();
  }
  // RGB9E5, bytes written out: 1 = 256 x 2^(16 - 24) with the ninth bits set; the largest value is every bit set;
  // the smallest denormal 2^-24 survives, half of it rounds up to it, a quarter rounds to 0.
  const HdrEncoding rgb9e5{HdrEncodingKind::Rgb9e5, 0.0f};
  EXPECT_EQ(encodeHdr(glm::vec3(1.0f), rgb9e5), (HdrTexel{0, 0, 0, 16 * 8 + 7}));
  EXPECT_EQ(encodeHdr(glm::vec3(1.0f, 0.0f, 0.0f), rgb9e5), (HdrTexel{0, 0, 0, 16 * 8 + 4}));
  EXPECT_EQ(encodeHdr(glm::vec3(65408.0f), rgb9e5), (HdrTexel{255, 255, 255, 255}));
  EXPECT_EQ(roundTrip(glm::vec3(std::ldexp(1.0f, -24)), rgb9e5), glm::vec3(std::ldexp(1.0f, -24)));
  EXPECT_EQ(roundTrip(glm::vec3(std::ldexp(1.0f, -25)), rgb9e5), glm::vec3(std::ldexp(1.0f, -24)));
  EXPECT_EQ(roundTrip(glm::vec3(std::ldexp(1.0f, -26)), rgb9e5), glm::vec3(0.0f));
  EXPECT_EQ(roundTrip(glm::vec3(0.75f, 0.0f, 1e-9f), rgb9e5), glm::vec3(0.75f, 0.0f, 0.0f));  // zeros stay zero
}

TEST(HdrEncoding, OutOfRangeValuesClamp) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (const HdrEncoding& e : hdrEncodingCandidates()) {
    const float top = hdrLargestValue(e);
    EXPECT_EQ(encodeHdr(glm::vec3(-1.0f, -1e-6f, nan), e), encodeHdr(glm::vec3(0.0f), e)) << e.name();
    if (e.kind == HdrEncodingKind::LogLuv) {
      // In luminance, keeping the chromaticity: a bright grey stays grey, a bright red stays red.
      EXPECT_EQ(encodeHdr(glm::vec3(top * 16.0f), e), encodeHdr(glm::vec3(top), e));
      const glm::vec3 red = roundTrip(glm::vec3(1e9f, 0.0f, 0.0f), e);
      EXPECT_NEAR(glm::dot(red, kLuminance), top, top * 1e-3f);
      EXPECT_LT(red.g, red.r * 0.01f);
    } else {
      // Per channel: over-range channels become the largest value, the others are unchanged.
      EXPECT_EQ(encodeHdr(glm::vec3(top * 4.0f, inf, top), e), encodeHdr(glm::vec3(top), e)) << e.name();
      EXPECT_EQ(encodeHdr(glm::vec3(top * 4.0f, top * 0.5f, 0.0f), e), encodeHdr(glm::vec3(top, top * 0.5f, 0.0f), e))
          << e.name();
    }
  }
}

// The encoder of EXT_texture_shared_exponent ("Encoding of special internal formats", the OpenGL 3.0 spec sec. 3.8.1),
// written out again from the spec in double precision.
TEST(HdrEncoding, Rgb9e5FollowsTheExtensionsPseudoCode) {
  const HdrEncoding rgb9e5{HdrEncodingKind::Rgb9e5, 0.0f};
  const int N = 9, B = 15, Emax = 31;
  const double sharedexpMax = (std::pow(2.0, N) - 1.0) / std::pow(2.0, N) * std::pow(2.0, Emax - B);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> exponent(-30.0f, 17.0f), ratio(0.0f, 1.0f);
  for (int i = 0; i < 1000000; ++i) {
    const float peak = std::exp2(exponent(rng));
    glm::vec3 c(peak * ratio(rng), peak * ratio(rng), peak * ratio(rng));
    c[i % 3] = peak;
    if (i % 7 == 0) c[(i + 1) % 3] = 0.0f;
    double rc[3];
    for (int k = 0; k < 3; ++k) rc[k] = std::max(0.0, std::min(sharedexpMax, static_cast<double>(c[k])));
    const double maxc = std::max(rc[0], std::max(rc[1], rc[2]));
    const int expSharedP = std::max(-B - 1, static_cast<int>(std::floor(std::log2(maxc)))) + 1 + B;
    const double maxs = std::floor(maxc / std::pow(2.0, expSharedP - B - N) + 0.5);
    const int expShared = maxs == std::pow(2.0, N) ? expSharedP + 1 : expSharedP;
    int mantissa[3];
    for (int k = 0; k < 3; ++k)
      mantissa[k] = static_cast<int>(std::floor(rc[k] / std::pow(2.0, expShared - B - N) + 0.5));
    float margin = 0.0f;
    const HdrTexel t = encodeHdr(c, rgb9e5, &margin);
    ASSERT_EQ(margin, std::numeric_limits<float>::infinity()) << "every step is exact";
    ASSERT_EQ(t[3] >> 3, expShared) << c.r << "," << c.g << "," << c.b;
    for (int k = 0; k < 3; ++k) ASSERT_EQ(t[k] + 256 * ((t[3] >> (2 - k)) & 1), mantissa[k]) << k;
    // Decoding: rs * 2^(exp_shared - B - N).
    const glm::vec3 d = decodeHdr(t, rgb9e5);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(d[k], static_cast<float>(mantissa[k] * std::pow(2.0, expShared - B - N)));
    // And a decoded texel encodes to itself, so textures written by the CPU round-trip through the shader.
    ASSERT_EQ(encodeHdr(d, rgb9e5), t);
  }
}

TEST(HdrEncoding, LogLuvKeepsGreyGreyAndCoversTheSrgbGamut) {
  const HdrEncoding logLuv{HdrEncodingKind::LogLuv, 0.0f};
  for (float g : {1e-4f, 0.18f, 1.0f, 3.7f, 1000.0f}) {
    const HdrTexel t = encodeHdr(glm::vec3(g), logLuv);
    EXPECT_EQ(t[0], kLogLuvWhiteU);
    EXPECT_EQ(t[1], kLogLuvWhiteV);
    const glm::vec3 d = decodeHdr(t, logLuv);
    EXPECT_NEAR(d.r, d.g, g * 1e-5f);
    EXPECT_NEAR(d.b, d.g, g * 1e-5f);
    EXPECT_NEAR(d.g, g, g * 2e-4f);  // 2048 codes per octave: within half a code, 0.017 %
  }
  // The sRGB primaries and secondaries land inside the chroma codes, not on the clamp.
  const LogLuvConstants& k = logLuvConstants();
  for (const glm::vec3 c : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(1, 1, 0),
                            glm::vec3(0, 1, 1), glm::vec3(1, 0, 1)}) {
    const glm::vec3 w = k.encode * c;
    const float u = (w.x / w.z - k.uOffset) * kLogLuvChromaScale;
    const float v = (9.0f * w.y / w.z - k.vOffset) * kLogLuvChromaScale;
    EXPECT_GT(u, 0.0f);
    EXPECT_LT(u, 255.0f);
    EXPECT_GT(v, 0.0f);
    EXPECT_LT(v, 255.0f);
  }
  // Y is CIE luminance: row 2 of the encoding matrix is BT.709's weights.
  EXPECT_NEAR(k.encode[0][1], 0.2126f, 1e-4f);
  EXPECT_NEAR(k.encode[1][1], 0.7152f, 1e-4f);
  EXPECT_NEAR(k.encode[2][1], 0.0722f, 1e-4f);
}

TEST(HdrEncoding, ABilinearFetchOfEncodedTexelsIsNotTheFilteredColour) {
  // Halfway between 1 (exponent 16) and 1.5 (exponent 16) the mantissas average; between 1.9 and 2.1 (exponents 16 and
  // 17) the bytes average into a colour near neither. Readers must fetch with NEAREST and decode before filtering.
  auto midpoint = [](const glm::vec3& a, const glm::vec3& b) {
    const HdrTexel ta = encodeHdr(a), tb = encodeHdr(b);
    HdrTexel mid;
    for (int i = 0; i < 4; ++i) mid[i] = static_cast<std::uint8_t>((ta[i] + tb[i] + 1) / 2);
    return decodeHdr(mid);
  };
  EXPECT_GT(std::abs(midpoint(glm::vec3(1.9f), glm::vec3(2.1f)).g - 2.0f), 0.5f);
}

TEST(HdrEncoding, ShaderLiteralsAreTheCpuFloatsBitForBit) {
  const std::string_view source = ShaderLibrary::file("lib/hdr.glsl");
  for (const GlslConstant& constant : hdrShaderConstants()) {
    const auto parsed = parseGlslConstant(source, constant.name);
    ASSERT_TRUE(parsed.has_value()) << constant.name << " is not declared in lib/hdr.glsl";
    ASSERT_EQ(parsed->size(), constant.values.size()) << constant.name;
    for (size_t i = 0; i < parsed->size(); ++i)
      EXPECT_EQ((*parsed)[i], constant.values[i])
          << constant.name << "[" << i << "]: run `obscura-hdr-study --glsl-constants` and paste the block";
  }
}

TEST(GlslConstants, FormatsShortestExactLiteralsAndParsesThemBack) {
  const std::vector<GlslConstant> constants = {glslFloat("A", 0.59719f), glslFloat("B", 620.0f),
                                               glslFloat("C", 1.0f / 3.0f), glslFloat("D", -2.5e-7f),
                                               glslMat3("M", glm::mat3(1, 2, 3, 4, 5, 6, 7, 8, 0.1f))};
  const std::string text = formatGlslConstants(constants);
  EXPECT_NE(text.find("const float A = 0.59719;"), std::string::npos) << text;
  EXPECT_NE(text.find("const float B = 620.0;"), std::string::npos) << text;
  for (const GlslConstant& c : constants) EXPECT_EQ(parseGlslConstant(text, c.name), c.values) << c.name;
  EXPECT_FALSE(parseGlslConstant(text, "N").has_value());
  EXPECT_FALSE(parseGlslConstant("float A = 1.0;", "A").has_value());  // not a const declaration
}
