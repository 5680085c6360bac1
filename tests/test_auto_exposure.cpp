// Auto exposure (effects/auto_exposure/AutoExposureEffect.h) through the GPU: the adapted log-average against the
// same HDR target metered on the CPU (every reduction depth, each metering), the scattered histogram against the CPU's
// histogram of the same meter grid, the exposure that brings a 16x brighter sun back to the display luminance it had,
// the adaptation's step per frame at a given frame interval in both directions, and the history dropped on a scene
// change and a resize.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "TestSupport.h"
#include "effects/auto_exposure/AutoExposureEffect.h"
#include "effects/lighting/LightingEffect.h"
#include "effects/tonemap/TonemapEffect.h"
#include "encoding/ExposureMetering.h"
#include "encoding/HdrEncoding.h"
#include "encoding/ToneMapping.h"
#include "scene/BuiltinScene.h"

using namespace obscura;
namespace em = ExposureMetering;

namespace {

RenderSettings autoExposure(em::Metering metering = em::Metering::Average) {
  RenderSettings settings;
  settings.set("fxaa", "off");
  settings.set("ao", "off");
  settings.set("auto-exposure", "on");
  settings.of<AutoExposureSettings>().metering = metering;
  return settings;
}

// The exposure target's two values: the adapted log2 luminance and the EV the tone mapping applies.
struct Exposure {
  float adapted = 0.0f, ev = 0.0f;
};
Exposure readExposure(Renderer& renderer) {
  const std::vector<std::uint8_t> bytes = renderer.retained("exposure").readRgba();
  const em::MeteredBlock adapted = em::blockFromBytes(bytes.data());  // RG: the log2 value (BA read as a weight)
  return {adapted.meanLog2, em::log2FromCode(static_cast<std::uint16_t>(bytes[2] * 256 + bytes[3]))};
}

// One frame of `settings`, keeping the HDR colour the meter read and the exposure; rendered after `frameInterval`.
Exposure renderFrame(Renderer& renderer, const Camera& camera, const RenderSettings& settings,
                     double frameInterval = 1.0 / 60.0, std::vector<std::string> retain = {"exposure"}) {
  FrameOptions options = test::retaining(std::move(retain));
  options.frameInterval = frameInterval;
  test::render(renderer, camera, settings, View::Final, options);
  return readExposure(renderer);
}

// The CPU's metering of a retained HDR target: the weighted mean of l over every pixel.
float meteredOnTheCpu(const std::vector<std::uint8_t>& hdr, int width, int height, em::Metering metering) {
  double sum = 0.0, weights = 0.0;
  for (int row = 0; row < height; ++row)
    for (int x = 0; x < width; ++x) {
      const size_t i = (static_cast<size_t>(row) * width + x) * 4;
      const glm::vec3 c = decodeHdr(HdrTexel{hdr[i], hdr[i + 1], hdr[i + 2], hdr[i + 3]});
      const int y = height - 1 - row;  // readRgba's rows run top to bottom
      const glm::vec2 uv((static_cast<float>(x) + 0.5f) / static_cast<float>(width),
                         (static_cast<float>(y) + 0.5f) / static_cast<float>(height));
      const double w = em::metered(c) ? em::meteringWeight(metering, uv,
                                                           static_cast<float>(width) / static_cast<float>(height))
                                       : 0.0;
      sum += w * em::meteredLog2(c);
      weights += w;
    }
  return static_cast<float>(sum / weights);
}

// The mean display luminance of a frame (sRGB bytes decoded to linear).
double meanDisplayLuminance(const test::RenderedImage& image) {
  double sum = 0.0;
  for (size_t i = 0; i < image.rgba.size(); i += 4)
    sum += em::luminance({srgbToLinear(image.rgba[i] / 255.0f), srgbToLinear(image.rgba[i + 1] / 255.0f),
                          srgbToLinear(image.rgba[i + 2] / 255.0f)});
  return sum / static_cast<double>(image.rgba.size() / 4);
}

}  // namespace

// Sizes with no reduction (the grid fits in 16 x 16), one (partial blocks at both edges) and two; average and centre
// metering. The CPU computes the same weighted mean of log2 luminance from the HDR target the meter read.
TEST(AutoExposure, TheAdaptedLogAverageIsTheCpusWithinAHundredthOfAnEv) {
  for (const glm::ivec2 size : {glm::ivec2(100, 60), glm::ivec2(333, 187), glm::ivec2(2100, 40)}) {
    for (em::Metering metering : {em::Metering::Average, em::Metering::Centre}) {
      // A fresh renderer: no history, so the adapted value is the metered one.
      Renderer renderer = test::makeRenderer();
      renderer.setScene(makeBuiltinScene());
      const Camera camera = builtinSceneCamera(size.x, size.y);
      const RenderSettings settings = autoExposure(metering);
      const Exposure gpu = renderFrame(renderer, camera, settings, 1.0 / 60.0, {"exposure", "scene-color"});
      const float cpu = meteredOnTheCpu(renderer.retained("scene-color").readRgba(), size.x, size.y, metering);
      std::printf("%dx%d, %d reduction(s), metering %d: GPU %.4f, CPU %.4f log2 luminance\n", size.x, size.y,
                  em::reductionCount(size), static_cast<int>(metering), gpu.adapted, cpu);
      EXPECT_NEAR(gpu.adapted, cpu, 0.01f) << size.x << "x" << size.y;
      EXPECT_NEAR(gpu.ev, em::exposureEv(gpu.adapted, 0.0f, -10.0f, 10.0f), 2e-3f);
    }
  }
}

// A frame bright in its middle only: centre weighting meters it brighter than the average does.
TEST(AutoExposure, CentreWeightingFavoursTheMiddle) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(160, 90);
  const float average = renderFrame(renderer, camera, autoExposure(em::Metering::Average)).adapted;
  Renderer other = test::makeRenderer();
  other.setScene(makeBuiltinScene());
  const float centre = renderFrame(other, camera, autoExposure(em::Metering::Centre)).adapted;
  std::printf("built-in scene: average %.3f, centre-weighted %.3f log2 luminance\n", average, centre);
  // The built-in scene's sky fills the top of the frame and the lit floor its middle: the two differ.
  EXPECT_GT(std::abs(centre - average), 0.05f);
}

// The histogram scattered on the GPU against the CPU's from the same meter grid: the trimmed mean within a hundredth
// of an EV (both place samples at their bins' centres).
TEST(AutoExposure, PercentileMeteringIsTheTrimmedMeanOfTheMeterGridsHistogram) {
  if (!AutoExposureEffect::histogramAvailable(test::context().caps())) GTEST_SKIP() << "no vertex texture unit";
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  for (const glm::ivec2 size : {glm::ivec2(160, 90), glm::ivec2(1280, 720)}) {
    const Camera camera = builtinSceneCamera(size.x, size.y);
    RenderSettings settings = autoExposure(em::Metering::Percentile);
    settings.set("auto-exposure.percentile-low", "20");
    settings.set("auto-exposure.percentile-high", "95");
    const Exposure gpu = renderFrame(renderer, camera, settings, 1.0 / 60.0, {"exposure", "exposure-meter"});
    const std::vector<std::uint8_t> grid = renderer.retained("exposure-meter").readRgba();
    std::vector<std::uint32_t> counts(em::kHistogramBins, 0);
    for (size_t i = 0; i < grid.size(); i += 4) ++counts[static_cast<size_t>(em::histogramBin(
                                                    em::blockFromBytes(&grid[i]).meanLog2))];
    const float cpu = em::percentileMean(counts, 0.2f, 0.95f);
    double plain = 0.0;
    for (size_t i = 0; i < grid.size(); i += 4) plain += em::blockFromBytes(&grid[i]).meanLog2;
    std::printf("%dx%d: %zu samples, GPU %.4f, CPU %.4f (the plain mean of the grid: %.4f)\n", size.x, size.y,
                grid.size() / 4, gpu.adapted, cpu, plain / static_cast<double>(grid.size() / 4));
    EXPECT_NEAR(gpu.adapted, cpu, 0.01f);
  }
}

// Without a vertex texture unit (GLES 2's minimum), percentile metering falls back to the average.
TEST(AutoExposure, WithoutVertexTexturesPercentileMeteringIsTheAverage) {
  RendererOptions options;
  options.simulateVertexLimits = VertexLimits::gles2Minimum();
  Renderer renderer = test::makeRenderer(options);
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(160, 90);
  const float percentile = renderFrame(renderer, camera, autoExposure(em::Metering::Percentile)).adapted;
  Renderer full = test::makeRenderer();
  full.setScene(makeBuiltinScene());
  const float average = renderFrame(full, camera, autoExposure(em::Metering::Average)).adapted;
  EXPECT_NEAR(percentile, average, 1e-3f);
}

// The sun 16x brighter: once adapted, the mean display luminance is back within 10 % of where it was. The scene is lit
// by the sun alone (no environment light: a black background, black shadows), so every lit pixel scales with it and
// the black ones are not metered.
TEST(AutoExposure, ASixteenTimesBrighterSunEndsAtTheSameDisplayLuminance) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(160, 90);
  RenderSettings settings = autoExposure();
  settings.set("lighting.environment", "uniform");
  settings.set("lighting.environment-intensity", "0");
  FrameOptions options;
  options.frameInterval = 0.25;  // 53 % of the way towards light, 22 % towards dark, each frame
  auto settle = [&](const RenderSettings& s) {
    test::RenderedImage image;
    for (int frame = 0; frame < 40; ++frame) image = test::render(renderer, camera, s, View::Final, options);
    return meanDisplayLuminance(image);
  };
  const double before = settle(settings);
  RenderSettings brighter = settings;
  const float sun = settings.of<LightingSettings>().sunIntensity;
  brighter.of<LightingSettings>().sunIntensity = 16.0f * sun;
  const test::RenderedImage firstBright = test::render(renderer, camera, brighter, View::Final, options);
  const double after = settle(brighter);
  RenderSettings manual = brighter;
  manual.set("auto-exposure", "off");
  const double unadapted = meanDisplayLuminance(test::render(renderer, camera, manual, View::Final));
  std::printf("mean display luminance: %.4f before, %.4f on the first brighter frame, %.4f adapted (%.4f without "
              "auto exposure)\n",
              before, meanDisplayLuminance(firstBright), after, unadapted);
  EXPECT_NEAR(after / before, 1.0, 0.10);
  EXPECT_GT(unadapted / before, 1.5) << "the step must be visible without auto exposure";
}

// One frame after a step in brightness, at 1/60 s, the adapted value has moved 1 - e^(-speed / 60) of the way: the
// speed up towards light, the speed down towards dark.
TEST(AutoExposure, AdaptationFollowsTheStatedSpeedsPerFrame) {
  const Camera camera = builtinSceneCamera(160, 90);
  RenderSettings dim = autoExposure();
  dim.set("auto-exposure.speed-up", "4");
  dim.set("auto-exposure.speed-down", "0.5");
  RenderSettings bright = dim;
  bright.of<LightingSettings>().sunIntensity *= 16.0f;
  bright.of<LightingSettings>().environmentIntensity *= 16.0f;
  auto metered = [&](const RenderSettings& s) {
    Renderer fresh = test::makeRenderer();
    fresh.setScene(makeBuiltinScene());
    return renderFrame(fresh, camera, s).adapted;  // no history: the metered value itself
  };
  const float dimLog = metered(dim), brightLog = metered(bright);
  ASSERT_GT(brightLog - dimLog, 2.0f);
  for (bool towardsLight : {true, false}) {
    Renderer renderer = test::makeRenderer();
    renderer.setScene(makeBuiltinScene());
    const RenderSettings& from = towardsLight ? dim : bright;
    const RenderSettings& to = towardsLight ? bright : dim;
    const float start = renderFrame(renderer, camera, from).adapted;
    const float dt = 1.0f / 60.0f;
    const float step = renderFrame(renderer, camera, to, dt).adapted;
    const float speed = towardsLight ? 4.0f : 0.5f;
    const float target = towardsLight ? brightLog : dimLog;
    const float expected = start + (target - start) * (1.0f - std::exp(-speed * dt));
    std::printf("%s: from %.4f towards %.4f, one frame: %.4f (expected %.4f)\n", towardsLight ? "up" : "down", start,
                target, step, expected);
    EXPECT_NEAR(step, expected, 2e-3f);
    // A second frame at a longer interval moves by that interval's fraction.
    const float second = renderFrame(renderer, camera, to, 0.5).adapted;
    EXPECT_NEAR(second, step + (target - step) * (1.0f - std::exp(-speed * 0.5f)), 2e-3f);
  }
}

// A scene change and a resize drop the history: the next frame takes the metered value at once. So does a new
// Renderer (what a lost context makes).
TEST(AutoExposure, HistoryIsDroppedOnSceneChangeAndResize) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(160, 90);
  RenderSettings dim = autoExposure();
  RenderSettings bright = dim;
  bright.of<LightingSettings>().sunIntensity *= 16.0f;
  bright.of<LightingSettings>().environmentIntensity *= 16.0f;
  const float dimLog = renderFrame(renderer, camera, dim).adapted;
  const float brightLog = [&] {
    Renderer fresh = test::makeRenderer();
    fresh.setScene(makeBuiltinScene());
    return renderFrame(fresh, camera, bright).adapted;
  }();
  // Kept: one frame later the value has only moved a little towards the bright one.
  const float kept = renderFrame(renderer, camera, bright).adapted;
  EXPECT_LT(kept, brightLog - 1.0f);
  EXPECT_GT(kept, dimLog);
  // A scene change: the metered value at once.
  renderFrame(renderer, camera, dim);
  renderer.setScene(makeBuiltinScene());
  EXPECT_NEAR(renderFrame(renderer, camera, bright).adapted, brightLog, 2e-3f);
  // A resize: the metered value of the new size at once.
  renderFrame(renderer, camera, dim);
  const Camera resized = builtinSceneCamera(162, 90);
  const float resizedBright = [&] {
    Renderer fresh = test::makeRenderer();
    fresh.setScene(makeBuiltinScene());
    return renderFrame(fresh, resized, bright).adapted;
  }();
  EXPECT_NEAR(renderFrame(renderer, resized, bright).adapted, resizedBright, 2e-3f);
}

// The tone mapping applies the exposure target's EV in place of tonemap.exposure: the display colour of a pixel is the
// tone curve of its HDR colour times 2^EV.
TEST(AutoExposure, TheToneMappingAppliesTheMeteredExposure) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(96, 54);
  RenderSettings settings = autoExposure();
  settings.set("tonemap.exposure", "3");  // ignored while auto exposure is on
  settings.set("auto-exposure.compensation", "0.5");
  FrameOptions options = test::retaining({"exposure", "scene-color"});
  const test::RenderedImage image = test::render(renderer, camera, settings, View::Final, options);
  const Exposure exposure = readExposure(renderer);
  EXPECT_NEAR(exposure.ev, em::exposureEv(exposure.adapted, 0.5f, -10.0f, 10.0f), 2e-3f);
  const std::vector<std::uint8_t> hdr = renderer.retained("scene-color").readRgba();
  const ToneMapOperator op = settings.of<TonemapSettings>().op;
  int worst = 0;
  for (size_t i = 0; i < hdr.size(); i += 4) {
    const glm::vec3 c = decodeHdr(HdrTexel{hdr[i], hdr[i + 1], hdr[i + 2], hdr[i + 3]});
    const glm::vec3 display = linearToSrgb(toneMap(op, c, exposure.ev));
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs(static_cast<int>(std::lround(display[k] * 255.0f)) - image.rgba[i + k]));
  }
  EXPECT_LE(worst, 1);
}

// Black says nothing about the exposure: a frame with nothing lit keeps the exposure it had, and without history
// takes EV 0.
TEST(AutoExposure, AFrameWithNothingLitKeepsTheExposure) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(160, 90);
  const RenderSettings lit = autoExposure();
  RenderSettings black = lit;
  black.of<LightingSettings>().sunIntensity = 0.0f;
  black.of<LightingSettings>().environmentIntensity = 0.0f;
  const Exposure before = renderFrame(renderer, camera, lit);
  const Exposure after = renderFrame(renderer, camera, black, 0.5);
  EXPECT_NEAR(after.adapted, before.adapted, 2e-3f);
  EXPECT_NEAR(after.ev, before.ev, 2e-3f);
  Renderer fresh = test::makeRenderer();
  fresh.setScene(makeBuiltinScene());
  EXPECT_NEAR(renderFrame(fresh, camera, black).ev, 0.0f, 2e-3f);
}
