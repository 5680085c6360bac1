// The environment's filterable encodings (encoding/EnvironmentEncoding.h): their CPU round trip, and the choice of
// the filtered texture (environment/Environment.h) by the error its levels have under the hardware's filter. The
// round trip through the GPU, filter included, is Environment.TheShaderMatchesItsMirrorInBothLayouts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "encoding/EnvironmentEncoding.h"
#include "environment/Environment.h"

using namespace obscura;

namespace {

float brightest(const glm::vec3& c) { return std::max(c.r, std::max(c.g, c.b)); }

}  // namespace

// Each encoding decodes its own bytes to within half a step: linear scale / 510 of every channel; sqrt half a step
// of the square root; RGBM half a step of the brightest channel relative to the multiplier (the colour's 8 bits),
// from the scale down to scale / 255. The scale and zero are exact; values beyond the scale clamp to it.
TEST(EnvironmentEncoding, EveryEncodingRoundTripsWithinHalfAStep) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float scale = 6.5f;
  for (EnvironmentEncodingKind kind : allEnvironmentEncodings()) {
    float worst = 0.0f;
    for (int i = 0; i < 20000; ++i) {
      // Brightest channel from scale / 255 to the scale (log-uniform), the others below it.
      const float top = scale * std::pow(255.0f, -unit(random));
      const glm::vec3 c = glm::vec3(top, top * unit(random), top * unit(random));
      const glm::vec3 got = decodeEnvironment(kind, encodeEnvironment(kind, c, scale), scale);
      float error = 0.0f;
      for (int k = 0; k < 3; ++k) error = std::max(error, std::abs(got[k] - c[k]));
      // The step each encoding promises at this colour.
      float allowed = 0.0f;
      switch (kind) {
        case EnvironmentEncodingKind::Linear: allowed = 0.5f * scale / 255.0f; break;
        case EnvironmentEncodingKind::Sqrt:
          allowed = (std::sqrt(top / scale) / 255.0f + 0.25f / (255.0f * 255.0f)) * scale;
          break;
        case EnvironmentEncodingKind::Rgbm:
          allowed = 0.5f * (std::ceil(top / scale * 255.0f) / 255.0f) * scale / 255.0f;
          break;
      }
      EXPECT_LE(error, allowed * 1.0001f) << environmentEncodingName(kind) << " at " << c.r << ", " << c.g << ", "
                                          << c.b;
      worst = std::max(worst, error / brightest(c));
    }
    std::printf("%s: worst round-trip error %.4f of the brightest channel, from scale / 255 to the scale\n",
                environmentEncodingName(kind), worst);
    EXPECT_EQ(decodeEnvironment(kind, encodeEnvironment(kind, glm::vec3(scale), scale), scale), glm::vec3(scale));
    EXPECT_EQ(decodeEnvironment(kind, encodeEnvironment(kind, glm::vec3(0.0f), scale), scale), glm::vec3(0.0f));
    EXPECT_EQ(decodeEnvironment(kind, encodeEnvironment(kind, glm::vec3(2.0f * scale), scale), scale),
              glm::vec3(scale));
  }
}

// RGBM under the filter: exact where neighbours share their multiplier, off where it changes (the product of the two
// blends): at the midpoint of white (multiplier 1) and a dim red (0.25, 0, 0; multiplier 64/255), green reads
// 0.5 x 0.625 = 0.31 for 0.5.
TEST(EnvironmentEncoding, RgbmUnderTheFilterIsExactOnlyWhereTheMultiplierStays) {
  const float scale = 1.0f;
  auto channels = [&](const glm::vec3& c) {
    const EnvironmentTexel t = encodeEnvironment(EnvironmentEncodingKind::Rgbm, c, scale);
    return glm::vec4(t[0], t[1], t[2], t[3]) / 255.0f;
  };
  const glm::vec4 a = channels(glm::vec3(0.5f, 0.25f, 0.1f)), b = channels(glm::vec3(0.4f, 0.5f, 0.2f));
  ASSERT_EQ(a.a, b.a);
  const glm::vec3 shared = decodeEnvironmentChannels(EnvironmentEncodingKind::Rgbm, 0.5f * (a + b), scale);
  EXPECT_NEAR(shared.r, 0.45f, 0.004f);
  EXPECT_NEAR(shared.g, 0.375f, 0.004f);
  const glm::vec4 bright = channels(glm::vec3(1.0f)), dim = channels(glm::vec3(0.25f, 0.0f, 0.0f));
  const glm::vec3 changed = decodeEnvironmentChannels(EnvironmentEncodingKind::Rgbm, 0.5f * (bright + dim), scale);
  EXPECT_NEAR(changed.g, 0.5f * (255.0f + 64.0f) / 510.0f, 0.002f);
  EXPECT_LT(changed.g, 0.35f) << "for 0.5";
}

// The filtered texture is used where it keeps its bound: the built-in sky's levels 2 .. 5 under an 8-bit filter stay
// within 2 % (99th percentile) and 5 % (worst) of the linear texels; the same sky with its sun 100 times as bright
// (a range RGBM's 8 bits cannot hold at those levels) keeps every level by hand.
TEST(EnvironmentEncoding, TheFilteredLevelsAreUsedWhereTheyKeepTheBound) {
  const EnvironmentImage sky = ProceduralSky{}.image(kEnvironmentWidth / 2, kEnvironmentHeight / 2);
  const PrefilteredEnvironment normal = PrefilteredEnvironment::of(sky, 64);
  std::printf("sky: filtered levels' error (8-bit filter) mean %.4f, p99 %.4f, worst %.4f; filtered from level %d\n",
              normal.filterError().mean, normal.filterError().p99, normal.filterError().worst,
              normal.filteredFrom());
  EXPECT_EQ(normal.filteredFrom(), kEnvironmentFilteredLevel);
  EXPECT_LE(normal.filterError().p99, kEnvironmentFilterBound.p99);
  ProceduralSky bright;
  bright.sun *= 100.0f;
  const PrefilteredEnvironment high = PrefilteredEnvironment::of(bright.image(kEnvironmentWidth / 2,
                                                                             kEnvironmentHeight / 2), 64);
  std::printf("sky, sun x 100: p99 %.4f, worst %.4f; filtered from level %d\n", high.filterError().p99,
              high.filterError().worst, high.filteredFrom());
  EXPECT_EQ(high.filteredFrom(), kEnvironmentLevels);
  // Forced either way, the choice holds.
  EXPECT_EQ(PrefilteredEnvironment::of(sky, 64, EnvironmentFiltering::ByHand).filteredFrom(), kEnvironmentLevels);
  EXPECT_EQ(PrefilteredEnvironment::of(sky, 64, EnvironmentFiltering::Hardware).filteredFrom(),
            kEnvironmentFilteredLevel);
}
