// The bilateral blur on synthetic inputs: no AO crosses a 1 m depth step, and noise on a flat plane drops.
#include <gtest/gtest.h>

#include <random>

#include "TestSupport.h"
#include "effects/ao/BilateralBlurPass.h"
#include "encoding/LinearDepthPacking.h"
#include "encoding/NormalEncoding.h"

using namespace obscura;
namespace ldp = obscura::LinearDepthPacking;

namespace {

constexpr int kWidth = 96, kHeight = 64;

struct SyntheticFrame {
  std::vector<std::uint8_t> ao, gbuffer;  // bottom-up rows, as textures are uploaded
  Camera camera = test::makeCamera({0, 0, 0}, {0, 0, -1}, kWidth, kHeight, 0.1f, 50.0f);

  SyntheticFrame() : ao(kWidth * kHeight * 4), gbuffer(kWidth * kHeight * 4) {}
  // A surface facing the camera at distance `distance` with AO value `value` at pixel (x, y).
  void set(int x, int y, float distance, float value) {
    const auto code = ldp::codeFromDepth((distance - camera.near) / (camera.far - camera.near));
    const auto depth = ldp::bytesFromCode(code);
    const auto normal = encodeNormal(glm::vec3(0, 0, 1));
    std::uint8_t* a = &ao[(static_cast<size_t>(y) * kWidth + x) * 4];
    std::uint8_t* g = &gbuffer[(static_cast<size_t>(y) * kWidth + x) * 4];
    a[0] = static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f));
    a[1] = g[2] = depth[0];
    a[2] = g[3] = depth[1];
    a[3] = 255;
    g[0] = normal[0];
    g[1] = normal[1];
  }
};

// Runs both blur directions and returns the output's AO channel, bottom-up.
std::vector<float> blur(const SyntheticFrame& frame, const AoSettings& settings) {
  BilateralBlurPass pass(test::effectResources());
  const gl::Texture2D ao(kWidth, kHeight, GL_NEAREST, frame.ao.data());
  const gl::Texture2D gbuffer(kWidth, kHeight, GL_NEAREST, frame.gbuffer.data());
  const FrameCamera camera = FrameCamera::from(frame.camera, kWidth, kHeight);
  const gl::RenderTarget horizontal("blur h", kWidth, kHeight, GL_NEAREST, gl::RenderTarget::Depth::None, false);
  const gl::RenderTarget vertical("blur v", kWidth, kHeight, GL_NEAREST, gl::RenderTarget::Depth::None, false);
  horizontal.bindForDrawing();
  pass.render(BilateralBlurPass::Direction::Horizontal, ao, gbuffer, camera, settings, 1);
  vertical.bindForDrawing();
  pass.render(BilateralBlurPass::Direction::Vertical, horizontal.color(), gbuffer, camera, settings, 1);
  const std::vector<std::uint8_t> topDown = vertical.readRgba();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  std::vector<float> out(kWidth * kHeight);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      out[static_cast<size_t>(y) * kWidth + x] = topDown[(static_cast<size_t>(kHeight - 1 - y) * kWidth + x) * 4] / 255.0f;
  return out;
}

}  // namespace

TEST(BilateralBlur, NoAoBleedsAcrossAOneMetreDepthStep) {
  SyntheticFrame frame;
  // Left half: a dark surface 5 m away. Right half: an unoccluded surface 1 m behind it.
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) frame.set(x, y, x < kWidth / 2 ? 5.0f : 6.0f, x < kWidth / 2 ? 0.0f : 1.0f);
  for (bool normals : {true, false}) {
    AoSettings settings;
    settings.blurRadius = 8;
    settings.blurStride = 2;
    settings.blurNormalAware = normals;
    const std::vector<float> out = blur(frame, settings);
    float worstFar = 1.0f, worstNear = 0.0f;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        const float v = out[static_cast<size_t>(y) * kWidth + x];
        if (x < kWidth / 2) worstNear = std::max(worstNear, v);
        else worstFar = std::min(worstFar, v);
      }
    }
    EXPECT_GE(worstFar, 254.0f / 255.0f) << "normal-aware " << normals;
    EXPECT_LE(worstNear, 1.0f / 255.0f) << "normal-aware " << normals;
  }
}

TEST(BilateralBlur, BackgroundNeitherChangesNorContributes) {
  SyntheticFrame frame;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) frame.set(x, y, x < kWidth / 2 ? 5.0f : frame.camera.far, 0.0f);
  const std::vector<float> out = blur(frame, AoSettings{});
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const float v = out[static_cast<size_t>(y) * kWidth + x];
      if (x < kWidth / 2) EXPECT_EQ(v, 0.0f) << x << "," << y;
      else EXPECT_EQ(v, 1.0f) << x << "," << y;  // background is written as AO 1
    }
  }
}

TEST(BilateralBlur, NoiseVarianceOnAFlatPlaneDropsFourfold) {
  SyntheticFrame frame;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> noise(-0.3f, 0.3f);
  std::vector<float> input(kWidth * kHeight);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const float v = 0.5f + noise(rng);
      frame.set(x, y, 4.0f, v);
      input[static_cast<size_t>(y) * kWidth + x] = std::round(v * 255.0f) / 255.0f;
    }
  auto variance = [](const std::vector<float>& values) {
    double sum = 0.0, sumSq = 0.0;
    int n = 0;
    for (int y = 10; y < kHeight - 10; ++y)
      for (int x = 10; x < kWidth - 10; ++x) {
        const double v = values[static_cast<size_t>(y) * kWidth + x];
        sum += v;
        sumSq += v * v;
        ++n;
      }
    const double mean = sum / n;
    return sumSq / n - mean * mean;
  };
  for (bool normals : {true, false}) {
    AoSettings settings;
    settings.blurNormalAware = normals;
    const double before = variance(input);
    const double after = variance(blur(frame, settings));
    EXPECT_LE(after * 4.0, before) << "normal-aware " << normals << ": " << before << " -> " << after;
  }
}

// The blur's width follows the AO radius projected at the pixel (at most a quarter of it, blur.frag): a one-pixel
// dark line (a contact the reference draws that thin) stays dark where the radius covers a pixel or two, and spreads
// over the preset's width where it covers many.
TEST(BilateralBlur, AThinLineStaysSharpWhereTheRadiusProjectsToAFewPixels) {
  SyntheticFrame frame;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) frame.set(x, y, 4.0f, x == kWidth / 2 ? 0.2f : 1.0f);
  const FrameCamera camera = FrameCamera::from(frame.camera, kWidth, kHeight);
  for (bool normals : {true, false}) {
    AoSettings settings;
    settings.blurNormalAware = normals;
    auto lineValue = [&](float radius) {
      settings.radius = radius;
      return blur(frame, settings)[static_cast<size_t>(kHeight / 2) * kWidth + kWidth / 2];
    };
    const glm::vec2 projScale = camera.projScale(kHeight);
    const float pixelsPerMetre = projScale.x / 4.0f + projScale.y;
    // r = 0.1 m projects to about 1.4 px: s = half a tap, the line keeps (0.2 + 2 e^-2) / (1 + 2 e^-2) = 0.37.
    EXPECT_LT(0.1f * pixelsPerMetre, 2.0f);
    EXPECT_LT(lineValue(0.1f), 0.42f) << "normal-aware " << normals;
    // r = 2 m projects to about 28 px: the preset's s = 2.5 taps spreads it to about 0.86.
    EXPECT_GT(lineValue(2.0f), 0.8f) << "normal-aware " << normals;
  }
}
