// The brute-force references of the temporal effects (renderer/AccumulationReference.h): the shutter's sample times,
// the box downsample, and the accumulation itself against renders made by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "TestSupport.h"
#include "base/Error.h"
#include "renderer/AccumulationReference.h"
#include "scene/BuiltinScene.h"

namespace obscura {
namespace {

TEST(AccumulationReference, ShutterTimesAreTheStrataMidpointsCentredOnTheFrameTime) {
  // F = 10, s = 0.5: the shutter is open 0.05 s, from T - 0.025 to T + 0.025; 4 strata of 0.0125 s.
  const std::vector<double> times = shutterSampleTimes(1.0, 10.0, 0.5, 4);
  ASSERT_EQ(times.size(), 4u);
  const double expected[] = {0.98125, 0.99375, 1.00625, 1.01875};
  for (size_t i = 0; i < 4; ++i) EXPECT_NEAR(times[i], expected[i], 1e-12);
  // One sample is the frame's time; a zero shutter is one instant.
  EXPECT_EQ(shutterSampleTimes(2.0, 60.0, 1.0, 1), std::vector<double>{2.0});
  for (double t : shutterSampleTimes(2.0, 60.0, 0.0, 3)) EXPECT_EQ(t, 2.0);
  EXPECT_THROW(shutterSampleTimes(0.0, 60.0, 0.5, 0), InputError);
  EXPECT_THROW(shutterSampleTimes(0.0, 0.0, 0.5, 4), InputError);
  EXPECT_THROW(shutterSampleTimes(0.0, 60.0, 1.5, 4), InputError);
}

TEST(AccumulationReference, BoxDownsampleAveragesEachBlock) {
  // A 4x2 image, factor 2: two output pixels, each the mean of a 2x2 block (rows top to bottom).
  std::vector<std::uint8_t> rgba(4 * 2 * 4, 0);
  const std::uint8_t left[4] = {0, 255, 255, 0}, right[4] = {10, 20, 30, 40};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 4; ++c)
        rgba[(y * 4 + x) * 4 + c] = x < 2 ? (c == 0 ? left[y * 2 + x] : 255) : static_cast<std::uint8_t>(right[c]);
  const LinearImage out = downsampleBox(rgba, 4, 2, 2);
  ASSERT_EQ(out.width, 2);
  ASSERT_EQ(out.height, 1);
  EXPECT_NEAR(out.at(0, 0, 0), 0.5f, 1e-6f);
  EXPECT_NEAR(out.at(0, 0, 1), 1.0f, 1e-6f);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(out.at(1, 0, c), right[c] / 255.0f, 1e-6f);
  EXPECT_EQ(out.toImage().rgba[0], 128);  // 127.5 rounds up
  EXPECT_THROW(downsampleBox(rgba, 4, 2, 3), InputError);
}

// Accumulating renders of the moving built-in scene is the mean of those renders, made one by one, and a still
// scene accumulates to itself.
TEST(AccumulationReference, IsTheMeanOfTheSubFramesRenders) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(160, 90);
  RenderSettings settings;
  AccumulationOptions options;
  options.time = 1.0;
  options.fps = 10.0;  // a long exposure, so that the two sub-frames differ
  options.shutter = 1.0;
  options.samples = 2;
  const LinearImage accumulated = accumulateShutter(renderer, [&](double) { return camera; }, settings, options);

  LinearImage expected;
  int moving = 0;
  std::vector<std::uint8_t> first;
  for (double t : shutterSampleTimes(1.0, 10.0, 1.0, 2)) {
    FrameOptions frame;
    frame.time = t;
    const test::RenderedImage image = test::render(renderer, camera, settings, View::Final, frame);
    const LinearImage linear = LinearImage::from(image.rgba, image.width, image.height);
    if (expected.rgba.empty()) {
      expected = linear;
      first = image.rgba;
    } else {
      for (size_t i = 0; i < expected.rgba.size(); ++i) expected.rgba[i] = 0.5f * (expected.rgba[i] + linear.rgba[i]);
      for (size_t i = 0; i < first.size(); ++i) moving += first[i] != image.rgba[i];
    }
  }
  EXPECT_GT(moving, 100) << "the sub-frames should differ where the pendulum and the limb move";
  ASSERT_EQ(accumulated.rgba.size(), expected.rgba.size());
  for (size_t i = 0; i < expected.rgba.size(); ++i) ASSERT_NEAR(accumulated.rgba[i], expected.rgba[i], 1e-5f) << i;

  // The still room, over the same shutter, is one render.
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const LinearImage still = accumulateShutter(renderer, [&](double) { return camera; }, settings, options);
  const test::RenderedImage once = test::render(renderer, camera, settings, View::Final);
  for (size_t i = 0; i < once.rgba.size(); ++i) ASSERT_NEAR(still.rgba[i], once.rgba[i] / 255.0f, 1e-5f) << i;
}

// Supersampling renders each sub-frame at k times the size and box-downsamples it.
TEST(AccumulationReference, SupersamplingIsTheDownsampledLargeRender) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  RenderSettings settings;
  settings.set("fxaa", "off");
  AccumulationOptions options;
  options.samples = 1;
  options.supersample = 2;
  const LinearImage reference =
      accumulateShutter(renderer, [&](double) { return builtinSceneCamera(80, 45); }, settings, options);
  const test::RenderedImage large = test::render(renderer, builtinSceneCamera(160, 90), settings, View::Final);
  const LinearImage expected = downsampleBox(large.rgba, 160, 90, 2);
  ASSERT_EQ(reference.width, 80);
  for (size_t i = 0; i < expected.rgba.size(); ++i) ASSERT_NEAR(reference.rgba[i], expected.rgba[i], 1e-6f) << i;
}

}  // namespace
}  // namespace obscura
