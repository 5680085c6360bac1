// CPU tests of auto exposure's arithmetic (src/encoding/ExposureMetering.h): the encodings' round trips and steps,
// the metered value of black and of HDR whites, the reduction levels' counts, the weighted means a two-level
// reduction gives against the plain mean, the histogram's bins and trimmed means against sorted samples, and the
// adaptation's steps against e^(-speed t) integrated frame by frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "encoding/ExposureMetering.h"

using namespace obscura;
namespace em = ExposureMetering;

TEST(ExposureMetering, Log2CodesRoundTripWithinHalfAStep) {
  const float step = 32.0f / 65535.0f;
  for (float x = -16.0f; x <= 16.0f; x += 0.0137f)
    EXPECT_NEAR(em::log2FromCode(em::codeFromLog2(x)), x, 0.5f * step + 1e-6f) << x;
  EXPECT_EQ(em::codeFromLog2(-100.0f), 0);
  EXPECT_EQ(em::codeFromLog2(100.0f), 65535);
  EXPECT_FLOAT_EQ(em::log2FromCode(0), -16.0f);
  EXPECT_FLOAT_EQ(em::log2FromCode(65535), 16.0f);
  for (float w : {0.0f, 1e-4f, 0.25f, 0.999f, 1.0f})
    EXPECT_NEAR(em::weightFromCode(em::codeFromWeight(w)), w, 0.5f / 65535.0f + 1e-7f);
  const em::MeteredBlock block{-3.21f, 0.4375f};
  const auto bytes = em::bytesFromBlock(block);
  const em::MeteredBlock back = em::blockFromBytes(bytes.data());
  EXPECT_NEAR(back.meanLog2, block.meanLog2, step);
  EXPECT_NEAR(back.weight, block.weight, 1.0f / 65535.0f);
}

TEST(ExposureMetering, BlackIsNotMeteredAndLuminanceIsRec709) {
  EXPECT_FLOAT_EQ(em::meteredLog2(glm::vec3(0.0f)), -16.0f);
  EXPECT_FALSE(em::metered(glm::vec3(0.0f)));
  EXPECT_FALSE(em::metered(glm::vec3(1e-5f)));
  EXPECT_TRUE(em::metered(glm::vec3(1.6e-5f)));
  EXPECT_FLOAT_EQ(em::meteredLog2(glm::vec3(1.0f)), 0.0f);
  EXPECT_NEAR(em::meteredLog2(glm::vec3(0.18f)), em::kKeyLog2, 1e-6f);
  EXPECT_FLOAT_EQ(em::meteredLog2(glm::vec3(65408.0f)), std::log2(65408.0f));
  EXPECT_FLOAT_EQ(em::luminance({1.0f, 0.0f, 0.0f}), 0.2126f);
  EXPECT_FLOAT_EQ(em::luminance({0.0f, 1.0f, 0.0f}), 0.7152f);
  EXPECT_FLOAT_EQ(em::luminance({0.0f, 0.0f, 1.0f}), 0.0722f);
}

TEST(ExposureMetering, ReductionsFollowTheFrameSize) {
  EXPECT_EQ(em::meterGridSize({1280, 720}), glm::ivec2(160, 90));
  EXPECT_EQ(em::meterGridSize({333, 187}), glm::ivec2(42, 24));
  EXPECT_EQ(em::reductionCount({128, 128}), 0);
  EXPECT_EQ(em::reductionCount({129, 8}), 1);
  EXPECT_EQ(em::reductionCount({1280, 720}), 1);  // 160x90 -> 10x6
  EXPECT_EQ(em::reductionCount({2048, 2048}), 1);  // 256x256 -> 16x16
  EXPECT_EQ(em::reductionCount({2100, 40}), 2);   // 263x5 -> 17x1 -> 2x1
  EXPECT_EQ(em::reductionCount({16384, 16384}), 2);
}

TEST(ExposureMetering, WeightedBlockMeansReduceToTheFramesMean) {
  // A 37 x 21 frame of random log2 values in 8 x 8 blocks (partial at the right and top), then one 16 x 16
  // reduction, each level quantised as the targets store it: the mean of the whole frame within a few code steps.
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(-12.0f, 9.0f);
  const int w = 37 * 8 - 3, h = 21 * 8 - 5;
  std::vector<float> frame(static_cast<size_t>(w) * h);
  double sum = 0.0;
  for (float& v : frame) sum += (v = value(random));
  const glm::ivec2 grid = em::meterGridSize({w, h});
  std::vector<em::MeteredBlock> blocks;
  for (int by = 0; by < grid.y; ++by)
    for (int bx = 0; bx < grid.x; ++bx) {
      double s = 0.0, n = 0.0;
      for (int y = by * 8; y < std::min(by * 8 + 8, h); ++y)
        for (int x = bx * 8; x < std::min(bx * 8 + 8, w); ++x) {
          s += frame[static_cast<size_t>(y) * w + x];
          n += 1.0;
        }
      const auto bytes = em::bytesFromBlock({static_cast<float>(s / n), static_cast<float>(n / 64.0)});
      blocks.push_back(em::blockFromBytes(bytes.data()));
    }
  double s = 0.0, n = 0.0;
  for (const em::MeteredBlock& b : blocks) {
    s += b.weight * b.meanLog2;
    n += b.weight;
  }
  EXPECT_NEAR(s / n, sum / static_cast<double>(frame.size()), 3.0 * 32.0 / 65535.0);
}

TEST(ExposureMetering, CentreWeightingFallsWithTheDistanceFromTheMiddle) {
  const float aspect = 16.0f / 9.0f;
  EXPECT_FLOAT_EQ(em::meteringWeight(em::Metering::Centre, {0.5f, 0.5f}, aspect), 1.0f);
  EXPECT_NEAR(em::meteringWeight(em::Metering::Centre, {0.5f, 1.0f}, aspect), std::exp(-2.0f), 1e-6f);
  EXPECT_LT(em::meteringWeight(em::Metering::Centre, {1.0f, 1.0f}, aspect), 3e-4f);
  EXPECT_FLOAT_EQ(em::meteringWeight(em::Metering::Average, {1.0f, 1.0f}, aspect), 1.0f);
  EXPECT_FLOAT_EQ(em::meteringWeight(em::Metering::Percentile, {0.0f, 0.3f}, aspect), 1.0f);
}

TEST(ExposureMetering, PercentileMeansAreTheTrimmedMeansOfTheBinnedSamples) {
  EXPECT_EQ(em::histogramBin(-16.0f), 0);
  EXPECT_EQ(em::histogramBin(-100.0f), 0);
  EXPECT_EQ(em::histogramBin(15.99f), em::kHistogramBins - 1);
  EXPECT_EQ(em::histogramBin(16.0f), em::kHistogramBins - 1);
  EXPECT_EQ(em::histogramBin(0.0f), 64);
  EXPECT_FLOAT_EQ(em::histogramBinCentre(64), 0.125f);
  // 1000 samples at bin centres: the mean between the 10th and 90th percentiles of the sorted samples.
  std::mt19937 random(3);
  std::normal_distribution<float> value(-1.5f, 2.5f);
  std::vector<float> samples;
  std::vector<std::uint32_t> counts(em::kHistogramBins, 0);
  for (int i = 0; i < 1000; ++i) {
    const int bin = em::histogramBin(value(random));
    ++counts[static_cast<size_t>(bin)];
    samples.push_back(em::histogramBinCentre(bin));
  }
  std::sort(samples.begin(), samples.end());
  double trimmed = 0.0;
  for (int i = 100; i < 900; ++i) trimmed += samples[static_cast<size_t>(i)];
  EXPECT_NEAR(em::percentileMean(counts, 0.1f, 0.9f), trimmed / 800.0, 1e-5);
  double all = 0.0;
  for (float v : samples) all += v;
  EXPECT_NEAR(em::percentileMean(counts, 0.0f, 1.0f), all / 1000.0, 1e-5);
  EXPECT_EQ(em::percentileMean(std::vector<std::uint32_t>(em::kHistogramBins, 0), 0.1f, 0.9f), 0.0f);
  // The saturation limit: 256 slots of 255 counts.
  EXPECT_EQ(em::kHistogramMaxSamples, 65280);
}

TEST(ExposureMetering, AdaptationStepsAreExponentialAndFasterTowardsLight) {
  // Frame by frame at 1/60 s, the adapted value follows target + (start - target) e^(-speed t).
  for (float target : {4.0f, -4.0f}) {
    const float up = 3.0f, down = 1.0f, dt = 1.0f / 60.0f;
    float adapted = 0.0f;
    for (int frame = 1; frame <= 60; ++frame) {
      adapted = em::adapt(adapted, target, dt, up, down);
      const float speed = target > 0.0f ? up : down;
      EXPECT_NEAR(adapted, target * (1.0f - std::exp(-speed * dt * static_cast<float>(frame))), 1e-4f)
          << target << " " << frame;
    }
  }
  EXPECT_GT(em::adapt(0.0f, 1.0f, 0.1f, 3.0f, 1.0f), -em::adapt(0.0f, -1.0f, 0.1f, 3.0f, 1.0f));
  EXPECT_FLOAT_EQ(em::adapt(2.0f, 5.0f, 0.0f, 3.0f, 1.0f), 2.0f);
  // The exposure: the key over the adapted value, clamped, then compensated.
  EXPECT_NEAR(em::exposureEv(em::kKeyLog2, 0.0f, -10.0f, 10.0f), 0.0f, 1e-6f);
  EXPECT_NEAR(em::exposureEv(em::kKeyLog2 + 3.0f, 0.5f, -10.0f, 10.0f), -2.5f, 1e-6f);
  EXPECT_NEAR(em::exposureEv(-14.0f, 1.0f, -4.0f, 4.0f), 5.0f, 1e-6f);
}
