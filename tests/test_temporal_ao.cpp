// Temporal AO (ao.temporal; effects/ao/AoTemporal.h, shaders_es2/ao/ao_temporal.frag): the CPU mirror's arithmetic, the
// GPU pass held to it, the history's lifetime, and the accumulated AO measured against the ray-traced reference on a
// still scene (accuracy for the taps spent) and on a moving one (no trail where the object uncovered the floor).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "TestSupport.h"
#include "effects/ao/AoTemporal.h"
#include "metrics/AoMetrics.h"
#include "reference/AoReferenceTracer.h"
#include "renderer/AccumulationReference.h"
#include "scene/Animation.h"
#include "scene/BuiltinScene.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

// --- The CPU mirror ---------------------------------------------------------------------------------------------

TEST(TemporalAo, FrameOffsetsAreStratifiedOverTheSequence) {
  std::vector<float> rotations, jitters;
  for (std::uint64_t frame = 0; frame < AoTemporal::kSequenceLength; ++frame) {
    const glm::vec2 offset = AoTemporal::frameOffset(frame);
    rotations.push_back(offset.x);
    jitters.push_back(offset.y);
    EXPECT_EQ(AoTemporal::frameOffset(frame + AoTemporal::kSequenceLength), offset) << "the sequence repeats";
  }
  // Eight rotations and eight distances, each in its own eighth of [0, 1): new directions every frame.
  for (std::vector<float>* values : {&rotations, &jitters}) {
    std::set<int> eighths;
    for (float v : *values) {
      ASSERT_GE(v, 0.0f);
      ASSERT_LT(v, 1.0f);
      eighths.insert(static_cast<int>(v * 8.0f));
    }
    EXPECT_EQ(eighths.size(), 8u);
  }
}

TEST(TemporalAo, TheRunningMeanIsExactForNFramesThenExponential) {
  const int maxFrames = 8;
  const float values[] = {0.2f, 0.9f, 0.4f, 0.7f, 0.1f, 0.6f, 0.3f, 0.8f};
  float history = 0.0f, sum = 0.0f;
  int frames = 0;
  for (int i = 0; i < 8; ++i) {
    const AoTemporal::Accumulated next = AoTemporal::accumulate(history, frames, values[i], 0.0f, 1.0f, maxFrames);
    sum += values[i];
    history = next.ao;
    frames = next.frames;
    EXPECT_EQ(frames, i + 1);
    EXPECT_NEAR(history, sum / static_cast<float>(i + 1), 1e-6f) << "the mean of every frame so far";
  }
  // Capped: a new frame weighs 1/N from then on.
  const AoTemporal::Accumulated capped = AoTemporal::accumulate(history, frames, 1.0f, 0.0f, 1.0f, maxFrames);
  EXPECT_EQ(capped.frames, maxFrames);
  EXPECT_NEAR(capped.ao, history + (1.0f - history) / 8.0f, 1e-6f);
  // No history (rejected): this frame alone.
  EXPECT_EQ(AoTemporal::accumulate(0.3f, 0, 0.9f, 0.0f, 1.0f, maxFrames).ao, 0.9f);
  EXPECT_EQ(AoTemporal::accumulate(0.3f, 0, 0.9f, 0.0f, 1.0f, maxFrames).frames, 1);
  // Rectified: a history outside this frame's range is clamped into it first.
  EXPECT_NEAR(AoTemporal::accumulate(0.2f, 7, 0.9f, 0.8f, 1.0f, maxFrames).ao, 0.8f + (0.9f - 0.8f) / 8.0f, 1e-6f);
}

TEST(TemporalAo, SomethingMovingNearbyShortensTheMemory) {
  EXPECT_EQ(AoTemporal::maxFramesAt(0.0f, 8), 8);
  EXPECT_EQ(AoTemporal::maxFramesAt(0.5f, 8), 8);  // up to half a pixel a frame: not rectified
  EXPECT_EQ(AoTemporal::maxFramesAt(1.0f, 8), 4);  // a pixel a frame: 4 frames, a lag of about 2 pixels
  EXPECT_EQ(AoTemporal::maxFramesAt(3.0f, 8), 1);
  EXPECT_EQ(AoTemporal::maxFramesAt(0.6f, 3), 3);
}

TEST(TemporalAo, StochasticRoundingIsUnbiased) {
  // Over the dither's values, the mean stored level is the value (nearest rounding would stall at the level).
  for (float ao : {0.0f, 0.1234f, 0.5f, 0.77f, 0.999f, 1.0f}) {
    const int n = 1024;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += AoTemporal::quantise(ao, (static_cast<float>(i) + 0.5f) / n);
    EXPECT_NEAR(sum / n / 255.0, ao, 0.5 / 255.0 / n + 1e-6) << ao;
  }
  EXPECT_EQ(AoTemporal::quantise(1.0f, 0.999f), 255);
  EXPECT_EQ(AoTemporal::quantise(0.0f, 0.0f), 0);
}

TEST(TemporalAo, TheTangentPlaneTestKeepsTheSurfaceAndRejectsAnother) {
  const glm::vec3 n = glm::normalize(glm::vec3(0.0f, 1.0f, 0.3f));
  const glm::vec3 c(0.5f, -1.0f, -4.0f);
  const glm::vec3 along = glm::normalize(glm::cross(n, glm::vec3(1.0f, 0.0f, 0.0f)));
  // A sub-pixel jitter, or a slanted plane: the history's point lies elsewhere on the same plane.
  EXPECT_TRUE(AoTemporal::keepsHistory(n, c, c + 0.3f * along, 0.1f));
  // A disocclusion: the history saw the object 0.5 above the floor.
  EXPECT_FALSE(AoTemporal::keepsHistory(n, c, c + 0.5f * n, 0.1f));
}

TEST(TemporalAo, IsASwitchOffByDefaultThatBruteForceReferencesTurnOff) {
  RenderSettings settings;
  EXPECT_EQ(settings.get("ao.temporal"), "off");
  settings.set("ao.temporal", "on");
  settings.set("ao.temporal-frames", "12");
  EXPECT_TRUE(settings.ao().temporal);
  EXPECT_EQ(settings.ao().temporalFrames, 12);
  EXPECT_FALSE(withoutTemporalEffects(settings).ao().temporal);
  EXPECT_TRUE(withoutTemporalEffects(settings).ao().enabled);
}

// --- The pass on the GPU ----------------------------------------------------------------------------------------

RenderSettings temporalSettings(int samples, int maxFrames = 8) {
  RenderSettings settings;
  settings.ao().samples = samples;
  settings.ao().temporal = true;
  settings.ao().temporalFrames = maxFrames;
  return settings;
}

// The frame counts (A) and AO levels (R) of "ao-temporal" and the raw AO (R) after one frame.
struct Targets {
  std::vector<std::uint8_t> temporal, raw;
};
Targets renderTargets(Renderer& renderer, const Camera& camera, const RenderSettings& settings, double time = 0.0) {
  FrameOptions options = test::retaining({"ao-temporal", "ao-raw"});
  options.time = time;
  test::render(renderer, camera, settings, View::Ao, options);
  return {renderer.retained("ao-temporal").readRgba(), renderer.retained("ao-raw").readRgba()};
}

TEST(TemporalAo, TheHistoryCountsItsFramesAndIsDroppedOnResizeAndSceneChange) {
  Renderer renderer = test::makeRenderer();
  const Scene scene = makeBuiltinScene(BuiltinSceneOptions::still());
  renderer.setScene(scene);
  const Camera camera = builtinSceneCamera(96, 54);
  const RenderSettings settings = temporalSettings(4, 5);
  auto counts = [](const Targets& t) {
    std::set<int> out;
    for (size_t i = 3; i < t.temporal.size(); i += 4) out.insert(t.temporal[i]);
    return out;
  };
  // A still scene: every geometry pixel keeps its history; the count climbs to N = 5 and stays (background: 0).
  for (int frame = 1; frame <= 7; ++frame) {
    const std::set<int> seen = counts(renderTargets(renderer, camera, settings));
    EXPECT_EQ(seen, (std::set<int>{0, std::min(frame, 5)})) << "frame " << frame;
  }
  // A new size, a new scene: every pixel starts afresh.
  EXPECT_EQ(counts(renderTargets(renderer, builtinSceneCamera(80, 45), settings)), (std::set<int>{0, 1}));
  EXPECT_EQ(counts(renderTargets(renderer, builtinSceneCamera(80, 45), settings)), (std::set<int>{0, 2}));
  renderer.setScene(scene);
  EXPECT_EQ(counts(renderTargets(renderer, builtinSceneCamera(80, 45), settings)), (std::set<int>{0, 1}));
  // Another estimator: the history held another AO.
  RenderSettings sao = settings;
  sao.ao().estimator = AoEstimator::Sao;
  EXPECT_EQ(counts(renderTargets(renderer, builtinSceneCamera(80, 45), sao)), (std::set<int>{0, 1}));
  EXPECT_EQ(counts(renderTargets(renderer, builtinSceneCamera(80, 45), sao)), (std::set<int>{0, 2}));
  // A frame without the temporal AO: the history is not the previous frame's any more.
  RenderSettings off = sao;
  off.ao().temporal = false;
  test::render(renderer, builtinSceneCamera(80, 45), off, View::Ao);
  EXPECT_EQ(counts(renderTargets(renderer, builtinSceneCamera(80, 45), sao)), (std::set<int>{0, 1}));
  // Half resolution: its own history, at its own size.
  RenderSettings half = sao;
  half.ao().halfResolution = true;
  for (int frame = 1; frame <= 3; ++frame)
    EXPECT_EQ(counts(renderTargets(renderer, builtinSceneCamera(80, 45), half)), (std::set<int>{0, frame}));
}

TEST(TemporalAo, SubPixelShiftsOfTheSamplesKeepTheHistory) {
  // TAA's jitter moves every G-buffer sample by a fraction of a pixel each frame. Here the camera turns by a quarter
  // pixel a frame, to and fro (Halton-like offsets), which moves the samples the same way: the nearest history texel
  // then lies up to half a pixel off along the surface, and the tangent-plane test must keep it. Pixels losing their
  // history are those near depth edges, where the nearest texel may be another surface.
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const int maxFrames = 6;
  const RenderSettings settings = temporalSettings(4, maxFrames);
  const float offsets[] = {0.0f, 0.25f, -0.25f, 0.375f, -0.125f, 0.125f, -0.375f};
  std::vector<std::uint8_t> bytes;
  for (float offset : offsets) {
    Camera camera = builtinSceneCamera(160, 90);
    // A turn of `offset` pixels: the target moves sideways by offset pixels' worth of angle at its distance.
    const float pixelAngle = glm::radians(camera.fovyDegrees) / static_cast<float>(camera.height);
    const glm::vec3 forward = camera.target - camera.eye;
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    camera.target += right * (offset * pixelAngle * glm::length(forward));
    FrameOptions options = test::retaining({"ao-temporal"});
    test::render(renderer, camera, settings, View::Ao, options);
    bytes = renderer.retained("ao-temporal").readRgba();
  }
  size_t geometry = 0, full = 0;
  for (size_t i = 3; i < bytes.size(); i += 4) {
    if (bytes[i] == 0) continue;
    ++geometry;
    full += bytes[i] == maxFrames;
  }
  const double kept = static_cast<double>(full) / static_cast<double>(geometry);
  std::printf("sub-pixel shifts: %.1f %% of the geometry pixels hold %d frames after %zu frames\n", 100.0 * kept,
              maxFrames, std::size(offsets));
  EXPECT_GE(kept, 0.9);
}

TEST(TemporalAo, TheSplitViewDrawingTheAoTwiceAFrameKeepsAccumulating) {
  // Comparing FXAA, both halves run the AO from one frame context: the second run reads the same previous history.
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const Camera camera = builtinSceneCamera(96, 54);
  View split = View::Split;
  split.compare = "fxaa";
  std::set<int> seen;
  for (int frame = 1; frame <= 6; ++frame) {
    test::render(renderer, camera, temporalSettings(4, 8), split, test::retaining({"ao-temporal"}));
    const std::vector<std::uint8_t> bytes = renderer.retained("ao-temporal").readRgba();
    seen.clear();
    for (size_t i = 3; i < bytes.size(); i += 4) seen.insert(bytes[i]);
  }
  EXPECT_EQ(seen, (std::set<int>{0, 6}));
}

TEST(TemporalAo, ThePassIsTheCpuMirrorsRunningMeanOfTheRawFrames) {
  // On a still scene nothing moves, so nothing is rectified: the stored AO after f frames is the mean of the f raw
  // frames, up to the stochastic rounding (each step adds less than one level; the mean of the errors is ~0).
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const Camera camera = builtinSceneCamera(96, 54);
  const int frames = 6;
  const RenderSettings settings = temporalSettings(4, 64);
  std::vector<float> mirror;
  std::vector<int> mirrorFrames;
  Targets t;
  int differentRaw = 0;
  std::vector<std::uint8_t> firstRaw;
  for (int f = 0; f < frames; ++f) {
    t = renderTargets(renderer, camera, settings);
    if (f == 0) {
      firstRaw = t.raw;
      mirror.assign(t.raw.size() / 4, 0.0f);
      mirrorFrames.assign(t.raw.size() / 4, 0);
    } else {
      for (size_t i = 0; i < t.raw.size(); i += 4) differentRaw += t.raw[i] != firstRaw[i];
    }
    for (size_t p = 0; p < mirror.size(); ++p) {
      if (t.temporal[p * 4 + 3] == 0) continue;  // background
      const AoTemporal::Accumulated next =
          AoTemporal::accumulate(mirror[p], mirrorFrames[p], t.raw[p * 4] / 255.0f, 0.0f, 1.0f, 64);
      mirror[p] = next.ao;
      mirrorFrames[p] = next.frames;
    }
  }
  // The taps turned: the raw AO changed from frame to frame.
  EXPECT_GT(differentRaw, static_cast<int>(firstRaw.size() / 4 / 10));
  double worst = 0.0, sum = 0.0;
  size_t pixels = 0;
  for (size_t p = 0; p < mirror.size(); ++p) {
    if (t.temporal[p * 4 + 3] == 0) continue;
    ASSERT_EQ(t.temporal[p * 4 + 3], frames);
    const double error = t.temporal[p * 4] / 255.0 - mirror[p];
    worst = std::max(worst, std::abs(error));
    sum += error;
    ++pixels;
  }
  std::printf("GPU against the CPU mirror after %d frames: worst %.4f, mean %+.5f over %zu pixels\n", frames, worst,
              sum / static_cast<double>(pixels), pixels);
  EXPECT_LE(worst, 2.0 / 255.0);  // at most two levels: each step's rounding is one level, averaged by later steps
  EXPECT_LE(std::abs(sum / static_cast<double>(pixels)), 0.25 / 255.0);  // unbiased
}

// --- Against the ray-traced reference ---------------------------------------------------------------------------

GreyImage aoOf(const test::RenderedImage& image) {
  return GreyImage::fromRed(Image{image.width, image.height, image.rgba});
}

// The default AO (GTAO, preset medium: 2 slices x 2 sides x 3 steps = 12 taps, the "11-sample" budget) in one frame
// against 4 taps a pixel (GTAO's one side x 4 steps) accumulated over 8 frames, on the still built-in room.
TEST(TemporalAo, FourTapsOverEightFramesAreAtLeastAsAccurateAsTheDefaultSingleFrame) {
  const Scene scene = makeBuiltinScene(BuiltinSceneOptions::still());
  const Camera camera = builtinSceneCamera(320, 180);
  const ReferenceFrame reference = AoReferenceTracer(scene).trace(camera, {1.0f, 256, 2});
  const GreyImage truth = GreyImage::fromRed(reference.aoImage());
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  const AoComparison single =
      compareAo(truth, aoOf(test::render(renderer, camera, RenderSettings(), View::Ao)), reference.mask);
  renderer.setScene(scene);
  const RenderSettings temporal = temporalSettings(4);
  test::RenderedImage image;
  for (int frame = 0; frame < 8; ++frame) image = test::render(renderer, camera, temporal, View::Ao);
  const AoComparison accumulated = compareAo(truth, aoOf(image), reference.mask);
  // The configuration that also halves the cost (docs/benchmarks.md, "Temporal AO"): a 5-tap blur each way instead
  // of 9, the accumulated AO needing less smoothing.
  renderer.setScene(scene);
  RenderSettings cheap = temporal;
  cheap.ao().blurRadius = 2;
  for (int frame = 0; frame < 8; ++frame) image = test::render(renderer, camera, cheap, View::Ao);
  const AoComparison cheaper = compareAo(truth, aoOf(image), reference.mask);
  renderer.setScene(scene);
  cheap.ao().blurRadius = 1;
  for (int frame = 0; frame < 8; ++frame) image = test::render(renderer, camera, cheap, View::Ao);
  const AoComparison cheapest = compareAo(truth, aoOf(image), reference.mask);
  renderer.setScene(scene);
  const AoComparison oneFrame =
      compareAo(truth, aoOf(test::render(renderer, camera, temporal, View::Ao)), reference.mask);
  std::printf("still room, 320x180: default single frame (12 taps) MAE %.4f Pearson %.4f SSIM %.4f | 4 taps, first "
              "frame MAE %.4f Pearson %.4f SSIM %.4f | 4 taps after 8 frames MAE %.4f Pearson %.4f SSIM %.4f\n",
              single.mae, single.pearson, single.ssim, oneFrame.mae, oneFrame.pearson, oneFrame.ssim,
              accumulated.mae, accumulated.pearson, accumulated.ssim);
  std::printf("  the same with blur-radius 2: MAE %.4f Pearson %.4f SSIM %.4f; blur-radius 1: MAE %.4f Pearson %.4f "
              "SSIM %.4f\n",
              cheaper.mae, cheaper.pearson, cheaper.ssim, cheapest.mae, cheapest.pearson, cheapest.ssim);
  // The target, with no allowance: at least as accurate on both figures.
  EXPECT_LE(accumulated.mae, single.mae);
  EXPECT_GE(accumulated.pearson, single.pearson);
  EXPECT_LE(cheaper.mae, single.mae);
  EXPECT_GE(cheaper.pearson, single.pearson);
  // And accumulating is what gets it there: 8 frames beat the first frame's 4 taps.
  EXPECT_LT(accumulated.mae, oneFrame.mae);
  EXPECT_GT(accumulated.ssim, oneFrame.ssim);
}

// A floor and a box (1 m, on the floor) sliding along x at 3 m/s, seen from above at an angle; AO radius 1 m.
Scene floorAndSlidingBox() {
  Scene scene;
  scene.meshes.push_back(test::makeRectangle({-20, 0, 20}, {40, 0, 0}, {0, 0, -40}));
  scene.meshes.push_back(makeBox({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}));
  scene.instances.push_back(Instance{0, glm::mat4(1.0f), -1, -1});
  test::addSlidingInstance(scene, 1, {-6, 0, 0}, {6, 0, 0}, 4.0f);
  return scene;
}

TEST(TemporalAo, AMovingObjectLeavesNoTrail) {
  const Scene scene = floorAndSlidingBox();
  const int width = 240, height = 135;
  // Far at 12 m: the depth view's 8 bits then tell the box's top (0.5 m nearer than the floor behind it) from the
  // floor.
  const Camera camera = test::makeCamera({0.0f, 4.0f, 6.0f}, {0.0f, 0.0f, 0.0f}, width, height, 0.1f, 12.0f);
  const double fps = 60.0, start = 1.8;
  const int frames = 16;
  const double last = start + (frames - 1) / fps;
  // The box's pixels in each frame: where the frame's depth is nearer than the floor's alone.
  Scene floorOnly = scene;
  floorOnly.instances.pop_back();
  Renderer depthRenderer = test::makeRenderer();
  depthRenderer.setScene(floorOnly);
  const test::RenderedImage floorDepth = test::render(depthRenderer, camera, RenderSettings(), View::Depth);
  depthRenderer.setScene(scene);
  std::vector<std::vector<bool>> box;
  for (int f = 0; f < frames; ++f) {
    FrameOptions options;
    options.time = start + f / fps;
    const test::RenderedImage depth = test::render(depthRenderer, camera, RenderSettings(), View::Depth, options);
    std::vector<bool> mask(static_cast<size_t>(width * height));
    for (int i = 0; i < width * height; ++i)
      mask[static_cast<size_t>(i)] =
          depth.rgba[static_cast<size_t>(i) * 4] + 2 < floorDepth.rgba[static_cast<size_t>(i) * 4];
    box.push_back(mask);
  }
  // The band the box uncovered: its pixels in any of the earlier frames that are floor now; and its wake, the floor
  // within the AO's reach of them (a contact shadow left behind would lie there), outside the box's reach now.
  auto dilate = [&](const std::vector<bool>& mask, int radius) {
    std::vector<bool> out(mask.size());
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        if (!mask[static_cast<size_t>(y * width + x)]) continue;
        for (int dy = -radius; dy <= radius; ++dy)
          for (int dx = -radius; dx <= radius; ++dx) {
            const int u = x + dx, v = y + dy;
            if (u >= 0 && v >= 0 && u < width && v < height) out[static_cast<size_t>(v * width + u)] = true;
          }
      }
    return out;
  };
  std::vector<bool> earlier(box[0].size());
  for (int f = 0; f < frames - 1; ++f)
    for (size_t i = 0; i < earlier.size(); ++i) earlier[i] = earlier[i] || box[static_cast<size_t>(f)][i];
  const int reach = 12;  // pixels: about the AO radius projected at the box (1 m at ~7 m, 135 px for 50 degrees)
  const std::vector<bool> nowNear = dilate(box.back(), reach), earlierNear = dilate(earlier, reach);
  std::vector<std::uint8_t> uncovered(earlier.size()), wake(earlier.size());
  size_t uncoveredPixels = 0, wakePixels = 0;
  for (size_t i = 0; i < earlier.size(); ++i) {
    uncovered[i] = earlier[i] && !box.back()[i];
    wake[i] = earlierNear[i] && !nowNear[i];
    uncoveredPixels += uncovered[i];
    wakePixels += wake[i];
  }
  ASSERT_GT(uncoveredPixels, 200u);
  ASSERT_GT(wakePixels, 200u);

  // The reference at the last frame's pose.
  const Scene posed = posedScene(scene, evaluatePose(scene, last, PoseOptions{}));
  const ReferenceFrame reference = AoReferenceTracer(posed).trace(camera, {1.0f, 256, 2});
  const GreyImage truth = GreyImage::fromRed(reference.aoImage());

  // The default single frame at the last time, and 4 taps accumulated over the 16 frames (the history through
  // every earlier pose).
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  FrameOptions lastFrame;
  lastFrame.time = last;
  lastFrame.previousTime = last - 1.0 / fps;
  const GreyImage single = aoOf(test::render(renderer, camera, RenderSettings(), View::Ao, lastFrame));
  renderer.setScene(scene);
  test::RenderedImage image;
  for (int f = 0; f < frames; ++f) {
    FrameOptions options;
    options.time = start + f / fps;
    image = test::render(renderer, camera, temporalSettings(4), View::Ao, options);
  }
  const GreyImage accumulated = aoOf(image);
  // 4 taps with no memory (N = 1): the noise floor of the taps alone.
  renderer.setScene(scene);
  for (int f = 0; f < frames; ++f) {
    FrameOptions options;
    options.time = start + f / fps;
    image = test::render(renderer, camera, temporalSettings(4, 1), View::Ao, options);
  }
  const GreyImage fourTaps = aoOf(image);
  auto maeOver = [&](const GreyImage& ao, const std::vector<std::uint8_t>& band) {
    return compareAo(truth, ao, band, {}, false).mae;
  };
  const double singleUncovered = maeOver(single, uncovered), temporalUncovered = maeOver(accumulated, uncovered);
  const double singleWake = maeOver(single, wake), temporalWake = maeOver(accumulated, wake);
  std::printf("sliding box, 240x135, %d frames at 3 m/s: MAE in the uncovered band (%zu px): single frame %.4f, "
              "temporal %.4f (4 taps, N = 1: %.4f); in the wake (%zu px): single %.4f, temporal %.4f (N = 1: %.4f)\n",
              frames, uncoveredPixels, singleUncovered, temporalUncovered, maeOver(fourTaps, uncovered), wakePixels,
              singleWake, temporalWake, maeOver(fourTaps, wake));
  // No worse than the single frame's, with a tenth of its error plus half a level for the noise of 4 taps. (The
  // wake's bound fails without the rectification's memory cap: 0.0075, docs/temporal-effects.md.)
  EXPECT_LE(temporalUncovered, singleUncovered * 1.1 + 0.5 / 255.0);
  EXPECT_LE(temporalWake, singleWake * 1.1 + 0.5 / 255.0);
}

}  // namespace
