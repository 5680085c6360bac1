// CPU tests of the tone-mapping mirror (src/encoding/ToneMapping.h): each curve against its published formula written
// out again here in double precision, known values, monotonic and bounded output, the sRGB transfer function's defining
// points, the colour-space matrices against their published roundings, and the literals lib/tonemap.glsl shares with
// the CPU (bit-identical).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "base/Error.h"
#include "encoding/ColorSpaces.h"
#include "encoding/ToneMapping.h"
#include "gl/ShaderLibrary.h"

using namespace obscura;

namespace {

const glm::vec3 kLuminance(0.2126f, 0.7152f, 0.0722f);

void expectNear(const glm::vec3& a, const glm::vec3& b, float tolerance, const std::string& what) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << what << " channel " << i;
}

// Stephen Hill's ACESFitted, from BakingLab/ACES.hlsl, in double: the rows as printed there, mul(M, v).
glm::dvec3 hillAces(const glm::dvec3& color) {
  const double in[3][3] = {{0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}};
  const double out[3][3] = {
      {1.60475, -0.53108, -0.07367}, {-0.10208, 1.10813, -0.00605}, {-0.00327, -0.07276, 1.07602}};
  glm::dvec3 v, r;
  for (int i = 0; i < 3; ++i) v[i] = in[i][0] * color.x + in[i][1] * color.y + in[i][2] * color.z;
  for (int i = 0; i < 3; ++i) {
    const double a = v[i] * (v[i] + 0.0245786) - 0.000090537;
    const double b = v[i] * (0.983729 * v[i] + 0.4329510) + 0.238081;
    v[i] = a / b;
  }
  for (int i = 0; i < 3; ++i)
    r[i] = std::clamp(out[i][0] * v.x + out[i][1] * v.y + out[i][2] * v.z, 0.0, 1.0);
  return r;
}

}  // namespace

TEST(ToneMapping, NamesRoundTripAndUnknownNamesAreRefused) {
  for (ToneMapOperator op : kToneMapOperators) EXPECT_EQ(parseToneMapOperator(toneMapOperatorName(op)), op);
  EXPECT_STREQ(toneMapOperatorName(ToneMapOperator::AcesFitted), "aces");
  EXPECT_STREQ(toneMapOperatorName(ToneMapOperator::Neutral), "neutral");
  EXPECT_THROW(parseToneMapOperator("filmic"), InputError);
  EXPECT_THROW(parseToneMapOperator(""), InputError);
  EXPECT_EQ(toneMapShaderDefine(ToneMapOperator::AgX),
            std::make_pair(std::string("TONEMAP_OPERATOR"), std::string("4")));
  EXPECT_EQ(toneMapShaderDefine(ToneMapOperator::Linear).second, "0");
}

TEST(ToneMapping, ExposureMultipliesByTwoToTheEv) {
  EXPECT_EQ(exposureScale(0.0f), 1.0f);
  EXPECT_EQ(exposureScale(1.0f), 2.0f);
  EXPECT_EQ(exposureScale(-2.0f), 0.25f);
  const glm::vec3 x(0.3f, 0.1f, 0.02f);
  for (ToneMapOperator op : kToneMapOperators)
    EXPECT_EQ(toneMap(op, x, 1.5f), toneMap(op, x * exposureScale(1.5f))) << toneMapOperatorName(op);
}

TEST(ToneMapping, LinearClampsAndReinhardOfOneIsOneHalf) {
  expectNear(toneMap(ToneMapOperator::Linear, glm::vec3(-1.0f, 0.25f, 7.0f)), glm::vec3(0.0f, 0.25f, 1.0f), 0.0f,
             "linear");
  EXPECT_EQ(toneMap(ToneMapOperator::Reinhard, glm::vec3(1.0f)), glm::vec3(0.5f));
  EXPECT_FLOAT_EQ(toneMap(ToneMapOperator::Reinhard, glm::vec3(3.0f)).r, 0.75f);
  EXPECT_EQ(toneMap(ToneMapOperator::Reinhard, glm::vec3(0.0f)), glm::vec3(0.0f));
}

TEST(ToneMapping, AcesIsHillsFitOfXOverPointSix) {
  const glm::vec3 points[] = {{0.0f, 0.0f, 0.0f},   {0.01f, 0.01f, 0.01f}, {0.18f, 0.18f, 0.18f}, {1, 1, 1},
                              {4.0f, 4.0f, 4.0f},   {16, 16, 16},          {0.8f, 0.2f, 0.05f},   {0.02f, 0.5f, 3.0f},
                              {100.0f, 1.0f, 0.0f}, {0.3f, 0.3f, 0.0f}};
  for (const glm::vec3& p : points) {
    const glm::dvec3 expected = hillAces(glm::dvec3(p));
    expectNear(acesFitted(p), glm::vec3(expected), 2e-6f, "acesFitted");
    expectNear(toneMap(ToneMapOperator::AcesFitted, p), glm::vec3(hillAces(glm::dvec3(p) / 0.6)), 2e-6f, "aces");
  }
  // Scene white: 0.619 with Hill's fit alone, 0.763 with three.js's 1/0.6; very bright input saturates to white.
  EXPECT_NEAR(acesFitted(glm::vec3(1.0f)).g, 0.6191, 1e-4);
  EXPECT_NEAR(toneMap(ToneMapOperator::AcesFitted, glm::vec3(1.0f)).g, 0.7633, 1e-4);
  EXPECT_GT(acesFitted(glm::vec3(1000.0f)).r, 0.99f);
}

TEST(ToneMapping, NeutralSubtractsF90BelowItsKneeAndCompressesAbove) {
  // Khronos PBR Neutral's spec: c_out = c_in - 0.04 when every channel is in [0.08, 0.8].
  for (float r = 0.08f; r <= 0.8f; r += 0.0311f)
    for (float g = 0.08f; g <= 0.8f; g += 0.0437f) {
      const glm::vec3 c(r, g, 0.5f);
      expectNear(pbrNeutral(c), c - 0.04f, 1e-6f, "neutral below the knee");
    }
  // The toe: x - 6.25 x^2 subtracted when the darkest channel x < 0.08; black stays black.
  EXPECT_EQ(pbrNeutral(glm::vec3(0.0f)), glm::vec3(0.0f));
  const float x = 0.05f;
  expectNear(pbrNeutral(glm::vec3(x, 0.3f, 0.6f)), glm::vec3(x, 0.3f, 0.6f) - (x - 6.25f * x * x), 1e-6f, "toe");
  // Above the knee the peak compresses towards 1 (never reaching it) and the colour desaturates towards white.
  const glm::vec3 hot = pbrNeutral(glm::vec3(50.0f, 5.0f, 0.5f));
  EXPECT_LT(std::max(hot.r, std::max(hot.g, hot.b)), 1.0f);
  EXPECT_GT(hot.r, 0.99f);
  EXPECT_GT(hot.b / hot.r, 0.5f / 50.0f);
  // Spec: p_n = 1 - (1 - Ks)^2 / (p + 1 - 2 Ks) on grey above the knee (g mixes grey with grey).
  const float ks = 0.76f, p = 2.0f - 0.04f;
  EXPECT_NEAR(pbrNeutral(glm::vec3(2.0f)).g, 1.0f - (1.0f - ks) * (1.0f - ks) / (p + 1.0f - 2.0f * ks), 1e-6f);
}

TEST(ToneMapping, AgxOfMidGreyIsItsSigmoidOfTheLogEncoding) {
  // Every AgX matrix maps grey to grey, so mid-grey reduces to the 1-D curve: x = (log2 0.18 - min) / (max - min),
  // the sigmoid, then pow 2.2 (three.js AgXToneMapping / Filament AgxToneMapper), in double here.
  const double x = (std::log2(0.18) - (-12.47393)) / (4.026069 - (-12.47393));
  const double p = 15.5 * std::pow(x, 6) - 40.14 * std::pow(x, 5) + 31.96 * std::pow(x, 4) - 6.868 * std::pow(x, 3) +
                   0.4298 * x * x + 0.1191 * x - 0.00232;
  const double expected = std::pow(p, 2.2);
  const glm::vec3 grey = agx(glm::vec3(0.18f));
  EXPECT_NEAR(grey.r, expected, 2e-5);
  EXPECT_NEAR(grey.g, expected, 2e-5);
  EXPECT_NEAR(grey.b, expected, 2e-5);
  EXPECT_NEAR(expected, 0.2148, 5e-4);
  EXPECT_NEAR(agxContrast(0.0f), -0.00232f, 1e-7f);
}

TEST(ToneMapping, MidGreyLandsWhereTheHeaderSays) {
  // ToneMapping.h: scene 0.18 at EV 0 displays at linear 0.18, reinhard 0.153, aces 0.213, neutral 0.14, agx 0.215.
  const float expected[] = {0.18f, 0.1525f, 0.2133f, 0.14f, 0.2148f};
  for (ToneMapOperator op : kToneMapOperators)
    EXPECT_NEAR(toneMap(op, glm::vec3(0.18f)).g, expected[static_cast<int>(op)], 1e-3f) << toneMapOperatorName(op);
  // Without three.js's 1/0.6, Hill's fit is a stop and a half darker.
  EXPECT_NEAR(acesFitted(glm::vec3(0.18f)).g, 0.1056f, 1e-3f);
}

TEST(ToneMapping, CurvesAreMonotonicAndStayInTheUnitCube) {
  const glm::vec3 bases[] = {{1, 1, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0.5f, 0.1f}, {0.2f, 0.4f, 1}, {1, 0, 1}};
  for (ToneMapOperator op : kToneMapOperators) {
    for (const glm::vec3& base : bases) {
      const bool grey = base == glm::vec3(1.0f);
      glm::vec3 previous(0.0f);
      float previousLuminance = 0.0f;
      for (int i = 0; i <= 9000; ++i) {
        const float scale = 1e-5f * std::pow(10.0f, static_cast<float>(i) / 1000.0f);  // 1e-5 .. 1e4
        const glm::vec3 out = toneMap(op, base * scale);
        for (int c = 0; c < 3; ++c) {
          ASSERT_GE(out[c], 0.0f) << toneMapOperatorName(op) << " at " << scale;
          ASSERT_LE(out[c], 1.0f) << toneMapOperatorName(op) << " at " << scale;
          // On grey every channel rises; on colours the curves that mix channels (aces, agx) or desaturate
          // (neutral) may lower the dimmer channels while the luminance rises.
          if (grey) {
            ASSERT_GE(out[c], previous[c]) << toneMapOperatorName(op) << " grey at " << scale;
          }
        }
        // AgX ends with a per-channel clamp (three.js: "Gamut mapping. Simple clamp for now."): on pure green near
        // white, red is clipped at 1 while the Rec. 2020 -> Rec. 709 matrix's negative terms still lower green, and
        // the luminance dips by 3.5e-5 (0.009 of an 8-bit level) around 43.
        const float slack = op == ToneMapOperator::AgX ? 1e-4f : 1e-6f;
        const float luminance = glm::dot(out, kLuminance);
        ASSERT_GE(luminance, previousLuminance - slack) << toneMapOperatorName(op) << " luminance at " << scale;
        previous = out;
        previousLuminance = luminance;
      }
    }
  }
}

TEST(Srgb, KnownPointsOfIec61966) {
  // The two pieces meet at linear 0.0031308 / encoded 0.04045 (IEC 61966-2-1).
  EXPECT_NEAR(linearToSrgb(0.0031308f), 0.04045f, 1e-6f);
  EXPECT_NEAR(srgbToLinear(0.04045f), 0.0031308f, 1e-7f);
  EXPECT_NEAR(12.92f * 0.0031308f, 1.055f * std::pow(0.0031308f, 1.0f / 2.4f) - 0.055f, 1e-6f);
  EXPECT_EQ(linearToSrgb(0.0f), 0.0f);
  EXPECT_NEAR(linearToSrgb(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(linearToSrgb(0.5f), 0.735357f, 1e-5f);
  EXPECT_NEAR(linearToSrgb(0.18f), 0.461356f, 1e-5f);
  EXPECT_NEAR(linearToSrgb(0.001f), 0.01292f, 1e-7f);
  EXPECT_NEAR(srgbToLinear(0.5f), 0.214041f, 1e-6f);
  EXPECT_EQ(linearToSrgb(-1.0f), 0.0f);
  EXPECT_NEAR(linearToSrgb(2.0f), 1.0f, 1e-6f);
}

TEST(Srgb, RoundTripsEveryByteAndTheUnitInterval) {
  for (int b = 0; b < 256; ++b) {
    const float encoded = static_cast<float>(b) / 255.0f;
    EXPECT_EQ(std::floor(linearToSrgb(srgbToLinear(encoded)) * 255.0f + 0.5f), static_cast<float>(b)) << b;
  }
  float previous = -1.0f;
  for (int i = 0; i <= 100000; ++i) {
    const float linear = static_cast<float>(i) / 100000.0f;
    const float encoded = linearToSrgb(linear);
    ASSERT_GT(encoded, previous);
    ASSERT_NEAR(srgbToLinear(encoded), linear, 2e-6f + linear * 2e-6f);
    previous = encoded;
  }
}

TEST(Srgb, FxaaLumaUsesBt601WeightsOnTheEncodedColour) {
  EXPECT_NEAR(fxaaLuma(glm::vec3(1.0f)), 1.0f, 1e-6f);
  EXPECT_FLOAT_EQ(fxaaLuma(glm::vec3(1, 0, 0)), 0.299f);
  EXPECT_FLOAT_EQ(fxaaLuma(glm::vec3(0, 1, 0)), 0.587f);
  EXPECT_FLOAT_EQ(fxaaLuma(glm::vec3(0, 0, 1)), 0.114f);
}

TEST(ColorSpaces, MatricesMatchTheirPublishedRoundings) {
  // IEC 61966-2-1 (sRGB), eq. 6: RGB -> XYZ to four decimals.
  const glm::dmat3 m = ColorSpaces::rgbToXyz(ColorSpaces::kBt709);
  const double srgb[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) EXPECT_NEAR(m[col][row], srgb[row][col], 1e-4) << row << "," << col;
  // ITU-R BT.2087-0, eq. (4): linear BT.709 -> BT.2020 to four decimals.
  const glm::dmat3 t = ColorSpaces::srgbToRec2020();
  const double bt2087[3][3] = {{0.6274, 0.3293, 0.0433}, {0.0691, 0.9195, 0.0114}, {0.0164, 0.0880, 0.8956}};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) EXPECT_NEAR(t[col][row], bt2087[row][col], 6e-5) << row << "," << col;
  // Both keep white white.
  const glm::dvec3 white = t * glm::dvec3(1.0);
  EXPECT_NEAR(white.x, 1.0, 1e-12);
  EXPECT_NEAR(white.y, 1.0, 1e-12);
  EXPECT_NEAR(white.z, 1.0, 1e-12);
}

TEST(ToneMapping, AgxMatricesAreDerivedFromFilamentsAndKeepGreyGrey) {
  const AgxMatrices& m = agxMatrices();
  // Filament's AgXOutsetMatrix is inverse(AgXOutsetMatrixInv); three.js prints it: 1.1271005818144368, ...
  EXPECT_NEAR(m.outset[0][0], 1.1271005818144368, 1e-6);
  EXPECT_NEAR(m.outset[0][1], -0.1413297634984383, 1e-6);
  EXPECT_NEAR(m.outset[2][2], 1.2519364065950405, 1e-6);
  // three.js's 4-decimal LINEAR_REC2020_TO_LINEAR_SRGB.
  EXPECT_NEAR(m.rec2020ToSrgb[0][0], 1.6605, 1e-4);
  EXPECT_NEAR(m.rec2020ToSrgb[1][0], -0.5876, 1e-4);
  EXPECT_NEAR(m.rec2020ToSrgb[2][2], 1.1187, 1e-4);
  for (const glm::mat3* matrix : {&m.input, &m.outset, &m.rec2020ToSrgb}) {
    const glm::vec3 grey = *matrix * glm::vec3(1.0f);
    expectNear(grey, glm::vec3(1.0f), 2e-6f, "grey through an AgX matrix");
  }
}

TEST(ToneMapping, ShaderLiteralsAreTheCpuFloatsBitForBit) {
  const std::string_view source = ShaderLibrary::file("lib/tonemap.glsl");
  for (const GlslConstant& constant : toneMapShaderConstants()) {
    const auto parsed = parseGlslConstant(source, constant.name);
    ASSERT_TRUE(parsed.has_value()) << constant.name << " is not declared in lib/tonemap.glsl";
    ASSERT_EQ(parsed->size(), constant.values.size()) << constant.name;
    for (size_t i = 0; i < parsed->size(); ++i)
      EXPECT_EQ((*parsed)[i], constant.values[i])
          << constant.name << "[" << i << "]: run `obscura-hdr-study --glsl-constants` and paste the block";
  }
}
