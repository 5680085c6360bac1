// The AO error figures (metrics/AoMetrics.h) on synthetic images with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "base/Error.h"
#include "metrics/AoMetrics.h"

using namespace obscura;

namespace {

GreyImage constant(int width, int height, float value) {
  return GreyImage{width, height, std::vector<float>(static_cast<size_t>(width) * height, value)};
}

// A smooth pattern with structure at several scales.
GreyImage pattern(int width, int height) {
  GreyImage image = constant(width, height, 0.0f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.values[static_cast<size_t>(y) * width + x] =
          0.5f + 0.3f * std::sin(0.3f * float(x)) * std::cos(0.17f * float(y)) + 0.1f * std::sin(0.05f * float(x * y));
  return image;
}

}  // namespace

TEST(Metrics, IdenticalImagesHaveNoErrorAndSsimOne) {
  const GreyImage a = pattern(64, 48);
  const AoComparison c = compareAo(a, a, {});
  EXPECT_EQ(c.pixels, 64u * 48u);
  EXPECT_EQ(c.mae, 0.0);
  EXPECT_EQ(c.rmse, 0.0);
  EXPECT_EQ(c.bias, 0.0);
  EXPECT_NEAR(c.ssim, 1.0, 1e-6);
}

TEST(Metrics, KnownErrorsOverTheMask) {
  // B differs from A by +0.4 on a quarter of the pixels; the mask drops the left half, where B differs by -0.3.
  const int w = 40, h = 20;
  GreyImage a = constant(w, h, 0.5f), b = a;
  std::vector<std::uint8_t> mask(static_cast<size_t>(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      mask[i] = x >= w / 2;
      if (x < w / 2) b.values[i] = 0.2f;
      else if (y < h / 2) b.values[i] = 0.9f;
    }
  const AoComparison c = compareAo(a, b, mask);
  EXPECT_EQ(c.pixels, static_cast<size_t>(w * h / 2));
  EXPECT_NEAR(c.mae, 0.2, 1e-6);                    // half of the masked pixels off by 0.4
  EXPECT_NEAR(c.rmse, std::sqrt(0.5 * 0.16), 1e-6);
  EXPECT_NEAR(c.bias, 0.2, 1e-6);
  EXPECT_LT(c.ssim, 0.97);  // a quarter of the pixels at luminance term 2(0.5)(0.9) / (0.5^2 + 0.9^2) = 0.85
  EXPECT_EQ(c.haloPixels, 0u);  // no depth given
}

TEST(Metrics, PearsonCorrelationIgnoresScaleAndOffsetButNotShape) {
  const GreyImage a = pattern(64, 48);
  GreyImage weaker = a, inverted = a, other = pattern(64, 48);
  for (float& v : weaker.values) v = 1.0f - 0.25f * (1.0f - v);  // the same AO at a quarter of its strength
  for (float& v : inverted.values) v = 1.0f - v;
  for (int y = 0; y < 48; ++y)  // the pattern shifted by a quarter of its x period: partly related
    for (int x = 0; x < 64; ++x)
      other.values[static_cast<size_t>(y) * 64 + x] = a.at((x + 5) % 64, y);
  EXPECT_NEAR(compareAo(a, a, {}).pearson, 1.0, 1e-9);
  EXPECT_NEAR(compareAo(a, weaker, {}).pearson, 1.0, 1e-6);  // MAE is large, the correlation perfect
  EXPECT_GT(compareAo(a, weaker, {}).mae, 0.05);
  EXPECT_NEAR(compareAo(a, inverted, {}).pearson, -1.0, 1e-6);
  const double shifted = compareAo(a, other, {}).pearson;
  EXPECT_GT(shifted, -0.9);
  EXPECT_LT(shifted, 0.9);
  // Symmetric, and 0 against a constant image (nothing varies with the reference).
  EXPECT_NEAR(compareAo(other, a, {}).pearson, shifted, 1e-9);
  EXPECT_EQ(compareAo(a, constant(64, 48, 1.0f), {}).pearson, 0.0);
}

// Pearson over the mask only, on two regions whose values correlate with opposite signs.
TEST(Metrics, PearsonCorrelationCountsOnlyMaskedPixels) {
  const int w = 40, h = 20;
  GreyImage a = constant(w, h, 0.0f), b = a;
  std::vector<std::uint8_t> right(static_cast<size_t>(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      a.values[i] = static_cast<float>(y) / h;
      b.values[i] = x < w / 2 ? 1.0f - a.values[i] : 0.5f * a.values[i] + 0.2f;
      right[i] = x >= w / 2;
    }
  EXPECT_NEAR(compareAo(a, b, right).pearson, 1.0, 1e-6);
  EXPECT_LT(compareAo(a, b, {}).pearson, 0.0);  // the left half's inverted ramp outweighs the right's
}

TEST(Metrics, SsimFallsWithNoiseAndIsSymmetric) {
  const GreyImage a = pattern(64, 64);
  GreyImage slightly = a, very = a;
  for (size_t i = 0; i < a.values.size(); ++i) {
    const float noise = static_cast<float>((i * 2654435761u) % 1000) / 1000.0f - 0.5f;  // deterministic, zero-mean
    slightly.values[i] += 0.02f * noise;
    very.values[i] += 0.3f * noise;
  }
  const double small = compareAo(a, slightly, {}).ssim, large = compareAo(a, very, {}).ssim;
  EXPECT_GT(small, 0.9);
  EXPECT_LT(large, small - 0.2);
  EXPECT_NEAR(compareAo(very, a, {}).ssim, large, 1e-9);
}

TEST(Metrics, SsimOfConstantImagesFollowsTheLuminanceTerm) {
  // No variance: SSIM reduces to (2 mu_a mu_b + C1) / (mu_a^2 + mu_b^2 + C1), the luminance comparison.
  const double c1 = 1e-4;
  const AoComparison c = compareAo(constant(16, 16, 0.8f), constant(16, 16, 0.4f), {});
  EXPECT_NEAR(c.ssim, (2 * 0.8 * 0.4 + c1) / (0.64 + 0.16 + c1), 1e-5);
}

TEST(Metrics, DiscontinuityBandFollowsDepthStepsNotSlopes) {
  // Left half: a steep but continuous ramp (two grey levels per pixel); right half: a plane far behind.
  const int w = 60, h = 10;
  GreyImage depth = constant(w, h, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      depth.values[static_cast<size_t>(y) * w + x] = x < 30 ? 0.1f + 1.5f * static_cast<float>(x) / 255.0f : 0.8f;
  DiscontinuityOptions options;
  options.haloWidth = 3;
  const std::vector<std::uint8_t> band = discontinuityBand(depth, options);
  for (int x = 0; x < w; ++x) {
    // The step lies between columns 29 and 30; both are marked, then widened by 3 either side: columns 26 .. 33,
    // the near surface's (26 .. 29) and the far one's (30 .. 33).
    const std::uint8_t expected = x >= 26 && x <= 29 ? kNearSide : x >= 30 && x <= 33 ? kFarSide : 0;
    for (int y = 0; y < h; ++y) EXPECT_EQ(band[static_cast<size_t>(y) * w + x], expected) << x << "," << y;
  }
  // The halo figures count exactly those pixels.
  GreyImage a = constant(w, h, 0.5f), b = a;
  for (int y = 0; y < h; ++y) b.values[static_cast<size_t>(y) * w + 28] = 0.1f;  // an error inside the band
  const AoComparison c = compareAo(a, b, {}, band);
  EXPECT_EQ(c.haloPixels, static_cast<size_t>(8 * h));
  EXPECT_NEAR(c.haloMae, 0.4 / 8.0, 1e-6);
  EXPECT_NEAR(c.interiorMae, 0.0, 1e-9);
  EXPECT_EQ(c.farSidePixels, static_cast<size_t>(4 * h));
  EXPECT_NEAR(c.nearSideMae, 0.4 / 4.0, 1e-6);  // column 28 lies on the near side
  EXPECT_NEAR(c.farSideMae, 0.0, 1e-9);
}

TEST(Metrics, RefusesMismatchedSizesAndEmptyMasks) {
  const GreyImage a = constant(8, 8, 0.5f);
  EXPECT_THROW(compareAo(a, constant(8, 9, 0.5f), {}), InputError);
  EXPECT_THROW(compareAo(a, a, std::vector<std::uint8_t>(64, 0)), InputError);
  const std::vector<std::uint8_t> band = discontinuityBand(constant(9, 8, 0.5f), {});
  EXPECT_THROW(compareAo(a, a, {}, band), InputError);
}

TEST(Metrics, DifferenceImageColoursTheSignOfTheError) {
  const GreyImage a{3, 1, {0.5f, 0.5f, 0.5f}}, b{3, 1, {0.5f, 0.2f, 0.9f}};
  const Image diff = differenceImage(a, b, {1, 1, 1}, 0.25f);
  auto rgb = [&](int x) {
    return std::array<int, 3>{diff.rgba[4 * x], diff.rgba[4 * x + 1], diff.rgba[4 * x + 2]};
  };
  EXPECT_EQ(rgb(0), (std::array<int, 3>{255, 255, 255}));  // equal: white
  EXPECT_EQ(rgb(1), (std::array<int, 3>{255, 0, 0}));      // B darker by 0.3 >= 0.25: full red
  EXPECT_EQ(rgb(2), (std::array<int, 3>{0, 0, 255}));      // B lighter: blue
  const Image masked = differenceImage(a, b, {0, 1, 1});
  EXPECT_EQ(masked.rgba[0], 128);
}

TEST(Metrics, SideBySidePlacesPanelsWithGaps) {
  Image left{2, 2, std::vector<std::uint8_t>(16, 10)}, right{3, 2, std::vector<std::uint8_t>(24, 200)};
  const Image joined = sideBySide({left, right}, 1);
  ASSERT_EQ(joined.width, 6);
  ASSERT_EQ(joined.height, 2);
  EXPECT_EQ(joined.rgba[0], 10);
  EXPECT_EQ(joined.rgba[4 * 2], 0);      // the gap
  EXPECT_EQ(joined.rgba[4 * 3], 200);
  EXPECT_EQ(joined.rgba[4 * (6 + 5)], 200);
  Image taller{1, 3, std::vector<std::uint8_t>(12, 0)};
  EXPECT_THROW(sideBySide({left, taller}), InputError);
}
