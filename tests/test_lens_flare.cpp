// Lens flare (effects/lens_flare/LensFlareEffect.h) and glare streaks (effects/glare/GlareEffect.h), fed from bloom's
// bright pass: with no pixel above the threshold nothing changes; the flare is its CPU mirror applied to the bright
// pass the GPU made; a bright spot off the centre gives ghosts where Chapman's method puts them (their discs against
// discs elsewhere); the streaks run along the stated angles (the energy by direction); the glare's weights compose to
// the exponential they stand for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "TestSupport.h"
#include "effects/bloom/BloomEffect.h"
#include "effects/glare/GlareEffect.h"
#include "effects/lens_flare/LensFlareEffect.h"
#include "effects/lighting/LightingEffect.h"
#include "encoding/HdrEncoding.h"
#include "encoding/ToneMapping.h"
#include "scene/BuiltinScene.h"

using namespace obscura;

namespace {

using test::HdrImage;
using test::retainedHdr;

// The flare at full intensity over the built-in scene's bright pass (threshold 0.5: the sky and the lit faces), FXAA
// off so that pixels compare one to one.
RenderSettings builtinSceneFlare() {
  RenderSettings settings;
  settings.set("fxaa", "off");
  settings.set("lens-flare", "on");
  settings.set("lens-flare.intensity", "1");
  settings.set("bloom.threshold", "0.5");
  return settings;
}

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// A dark room with one small glowing square facing the camera (emission 200, linear) at `spot` (uv of a 16:9 frame),
// nothing else lit: the bright pass holds one spot.
struct SpotScene {
  Scene scene;
  Camera camera;
};
SpotScene spotAt(glm::vec2 spot, glm::ivec2 size = {320, 180}) {
  SpotScene s;
  s.camera = test::makeCamera({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, size.x, size.y, 0.1f, 100.0f, 50.0f);
  // The point on the plane z = 0 that projects to `spot`.
  const float halfHeight = 5.0f * std::tan(glm::radians(25.0f));
  const glm::vec2 ndc = spot * 2.0f - 1.0f;
  const glm::vec3 centre(ndc.x * halfHeight * 16.0f / 9.0f, ndc.y * halfHeight, 0.0f);
  const float half = 0.04f;
  Mesh square = test::makeRectangle(centre - glm::vec3(half, half, 0.0f), {2.0f * half, 0.0f, 0.0f},
                                    {0.0f, 2.0f * half, 0.0f});
  const int material = test::addMaterial(s.scene, glm::vec3(0.0f));
  s.scene.materials[static_cast<size_t>(material)].emissiveFactor = glm::vec3(1.0f);
  s.scene.materials[static_cast<size_t>(material)].emissiveStrength = 200.0f;
  square.material = material;
  s.scene.meshes.push_back(std::move(square));
  Instance instance;
  instance.mesh = 0;
  s.scene.instances.push_back(instance);
  return s;
}

RenderSettings dark() {
  RenderSettings settings;
  settings.set("fxaa", "off");
  settings.set("ao", "off");
  settings.set("lighting.environment", "uniform");
  settings.set("lighting.environment-intensity", "0");
  settings.of<LightingSettings>().sunIntensity = 0.0f;
  return settings;
}

// The mean luminance over a disc of `radius` texels round uv in an image.
double discMean(const HdrImage& image, glm::vec2 uv, float radius) {
  const glm::vec2 centre = uv * glm::vec2(image.size);
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < image.size.y; ++y)
    for (int x = 0; x < image.size.x; ++x) {
      const glm::vec2 p(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      if (glm::length(p - centre) > radius) continue;
      sum += luminance(image.at(x, y));
      ++count;
    }
  return count ? sum / count : 0.0;
}

}  // namespace

// With no pixel above the threshold, the frame is the frame without them (within 1/255): bloom's threshold at the
// built-in scene's brightest channel, bloom off, flare and glare on. Below it the frame changes, so the test can fail.
TEST(LensFlare, NoPixelAboveTheThresholdLeavesTheFrameUnchanged) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(160, 90);
  RenderSettings plain;
  plain.set("fxaa", "off");
  const test::RenderedImage reference =
      test::render(renderer, camera, plain, View::Final, test::retaining({"scene-color"}));
  const float brightest = test::brightestChannel(retainedHdr(renderer, "scene-color"));
  auto worstChange = [&](float threshold) {
    RenderSettings settings = plain;
    settings.set("lens-flare", "on");
    settings.set("glare", "on");
    settings.of<LensFlareSettings>().intensity = 1.0f;
    settings.of<GlareSettings>().intensity = 1.0f;
    settings.of<BloomSettings>().threshold = threshold;
    return test::worstByteDifference(test::render(renderer, camera, settings, View::Final), reference);
  };
  EXPECT_LE(worstChange(brightest), 1) << "threshold at the brightest channel, " << brightest;
  EXPECT_GT(worstChange(0.3f * brightest), 4) << "below it the frame must change";
}

// The GPU's flare against lensFlareAt over the bright pass the GPU made (both sampling it NEAREST), with dispersion and
// a halo: almost every texel within RGB9E5's rounding.
TEST(LensFlare, TheFlareIsTheMirrorAppliedToTheBrightPass) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(320, 180);
  RenderSettings settings = builtinSceneFlare();
  settings.set("lens-flare.distortion", "0.02");
  test::render(renderer, camera, settings, View::Final, test::retaining({"bloom-bright", "lens-light"}));
  const HdrImage bright = retainedHdr(renderer, "bloom-bright");
  const HdrImage flare = retainedHdr(renderer, "lens-light");
  ASSERT_EQ(bright.size, flare.size);
  int close = 0;
  double total = 0.0, difference = 0.0;
  for (int y = 0; y < flare.size.y; ++y)
    for (int x = 0; x < flare.size.x; ++x) {
      const glm::vec2 uv((static_cast<float>(x) + 0.5f) / static_cast<float>(flare.size.x),
                         (static_cast<float>(y) + 0.5f) / static_cast<float>(flare.size.y));
      const glm::vec3 cpu = lensFlareAt(uv, bright.pixels, bright.size, 320.0f / 180.0f,
                                        settings.of<LensFlareSettings>());
      const glm::vec3 gpu = flare.at(x, y);
      total += luminance(gpu);
      difference += std::abs(luminance(gpu) - luminance(cpu));
      const float scale = std::max(std::max(cpu.r, std::max(cpu.g, cpu.b)), 1e-4f);
      if (glm::all(glm::lessThanEqual(glm::abs(gpu - cpu), glm::vec3(scale * 0.01f)))) ++close;
    }
  const int texels = flare.size.x * flare.size.y;
  std::printf("%d of %d texels within 1 %% of the mirror; mean flare luminance %.4f, mean difference %.3f %% of it\n",
              close, texels, total / texels, 100.0 * difference / total);
  EXPECT_GT(total / texels, 1e-2) << "the flare must not be black";
  // Where a sample lands within a rounding error of a texel's edge, the GPU and the CPU may take neighbours.
  EXPECT_GE(close, texels * 95 / 100);
  EXPECT_LT(difference / total, 0.02);
}

// A bright spot off the centre: ghost i lands at 1 - (p - i d / 2) / (1 - i d) (ghost 0: the spot mirrored through the
// centre). Each ghost's disc is far brighter than the same disc mirrored off the line the ghosts lie on.
TEST(LensFlare, ABrightSpotMakesGhostsWhereTheMethodPutsThem) {
  const glm::vec2 spot(0.62f, 0.58f);
  SpotScene s = spotAt(spot);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(s.scene);
  RenderSettings settings = dark();
  settings.set("lens-flare", "on");
  settings.set("lens-flare.ghosts", "4");
  settings.set("lens-flare.dispersal", "0.2");
  settings.set("lens-flare.halo-width", "0");
  settings.set("lens-flare.intensity", "1");
  test::render(renderer, s.camera, settings, View::Final, test::retaining({"lens-light", "bloom-bright"}));
  const HdrImage flare = retainedHdr(renderer, "lens-light");
  const HdrImage bright = retainedHdr(renderer, "bloom-bright");
  // The spot where the bright pass has it: its centroid.
  glm::dvec2 centroid(0.0);
  double weight = 0.0;
  for (int y = 0; y < bright.size.y; ++y)
    for (int x = 0; x < bright.size.x; ++x) {
      const double l = luminance(bright.at(x, y));
      centroid += l * glm::dvec2(x + 0.5, y + 0.5);
      weight += l;
    }
  ASSERT_GT(weight, 0.0);
  const glm::vec2 source = glm::vec2(centroid / weight) / glm::vec2(bright.size);
  std::printf("spot at (%.3f, %.3f), in the bright pass at (%.3f, %.3f)\n", spot.x, spot.y, source.x, source.y);
  for (int i = 0; i < 4; ++i) {
    const glm::vec2 ghost = lensFlareGhostPosition(source, i, 0.2f);
    ASSERT_TRUE(ghost.x > 0.05f && ghost.x < 0.95f && ghost.y > 0.05f && ghost.y < 0.95f) << "ghost " << i;
    // The same disc mirrored in the horizontal line through the centre: off the line the ghosts lie on.
    const glm::vec2 mirrored(ghost.x, 1.0f - ghost.y);
    const double at = discMean(flare, ghost, 3.0f), elsewhere = discMean(flare, mirrored, 3.0f);
    std::printf("ghost %d at (%.3f, %.3f): disc mean %.5f; mirrored to (%.3f, %.3f): %.6f\n", i, ghost.x, ghost.y, at,
                mirrored.x, mirrored.y, elsewhere);
    EXPECT_GT(at, 20.0 * elsewhere + 1e-4) << "ghost " << i;
  }
  // Ghost 0 is the spot mirrored through the centre.
  const glm::vec2 first = lensFlareGhostPosition(source, 0, 0.2f);
  EXPECT_NEAR(first.x, 1.0f - source.x, 1e-6f);
  EXPECT_NEAR(first.y, 1.0f - source.y, 1e-6f);
}

// Kawase's composition: three passes of 4 taps 4^n apart, each weighing a^(s 4^n), give each offset D = 0 .. 63 once
// (its digits in base 4), weighted a^D: the exponential streak, normalised, reaching 63 steps. A symmetric 7-tap pass
// (both rays of a line at once) would reach some offsets twice and not fall monotonically, which is why the rays are
// filtered one by one.
TEST(Glare, ThePassesComposeIntoAnExponentialStreakOf63Steps) {
  const float length = 0.05f;
  const double a = std::exp(-1.0 / (length * kGlareStepsPerWidth));
  std::vector<double> kernel(64, 0.0);
  for (int s0 = 0; s0 < 4; ++s0)
    for (int s1 = 0; s1 < 4; ++s1)
      for (int s2 = 0; s2 < 4; ++s2)
        kernel[static_cast<size_t>(s0 + 4 * s1 + 16 * s2)] += double(glareWeights(0, length)[s0]) *
                                                               glareWeights(1, length)[s1] *
                                                               glareWeights(2, length)[s2];
  double sum = 0.0, norm = 0.0;
  for (int d = 0; d < 64; ++d) {
    sum += kernel[static_cast<size_t>(d)];
    norm += std::pow(a, d);
  }
  EXPECT_NEAR(sum, 1.0, 1e-5);
  for (int d = 0; d < 64; ++d) EXPECT_NEAR(kernel[static_cast<size_t>(d)], std::pow(a, d) / norm, 1e-6) << d;
  // The symmetric alternative: 7 taps at 0, +-s 4^n, the same weights on both sides.
  std::vector<double> symmetric(127, 0.0);
  auto w = [&](int pass, int s) {
    const double x = std::exp(-std::abs(s) * std::pow(4.0, pass) / (length * kGlareStepsPerWidth));
    double n = 1.0;
    for (int t = 1; t <= 3; ++t) n += 2.0 * std::exp(-t * std::pow(4.0, pass) / (length * kGlareStepsPerWidth));
    return x / n;
  };
  for (int s0 = -3; s0 <= 3; ++s0)
    for (int s1 = -3; s1 <= 3; ++s1)
      for (int s2 = -3; s2 <= 3; ++s2)
        symmetric[static_cast<size_t>(s0 + 4 * s1 + 16 * s2 + 63)] += w(0, s0) * w(1, s1) * w(2, s2);
  int rises = 0;
  for (size_t d = 63; d < 126; ++d) rises += symmetric[d + 1] > symmetric[d];
  std::printf("the symmetric 7-tap composition rises %d times over 63 steps\n", rises);
  EXPECT_GT(rises, 0);
}

// A bright spot at the centre of a 1280 x 720 frame (the bright pass at 320 x 180: one step a texel) under a star of 6
// streaks at 20 degrees, and of 4 at 0: nearly all of the light beyond the spot's own footprint lies within 6 degrees
// of the stated directions, and each direction holds its share.
TEST(Glare, StreaksRunAlongTheStatedAngles) {
  SpotScene s = spotAt({0.5f, 0.5f}, {1280, 720});
  Renderer renderer = test::makeRenderer();
  renderer.setScene(s.scene);
  for (const auto& [streaks, angle] : {std::pair<int, float>{6, 20.0f}, std::pair<int, float>{4, 0.0f}}) {
    RenderSettings settings = dark();
    settings.set("glare", "on");
    settings.of<GlareSettings>().streaks = streaks;
    settings.of<GlareSettings>().angle = angle;
    settings.set("glare.intensity", "1");
    settings.set("glare.length", "0.1");
    test::render(renderer, s.camera, settings, View::Final, test::retaining({"lens-light"}));
    const HdrImage glare = retainedHdr(renderer, "lens-light");
    // Directions in pixels of the frame (the target is 1/4 of it in both axes, so angles are kept).
    const glm::vec2 centre = glm::vec2(glare.size) * 0.5f;
    double all = 0.0;
    std::vector<double> along(static_cast<size_t>(streaks), 0.0);
    for (int y = 0; y < glare.size.y; ++y)
      for (int x = 0; x < glare.size.x; ++x) {
        const glm::vec2 d = glm::vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f) - centre;
        if (glm::length(d) < 12.0f) continue;  // the spot and its bright pass's footprint
        const double l = luminance(glare.at(x, y));
        all += l;
        const float theta = glm::degrees(std::atan2(d.y, d.x));
        for (int k = 0; k < streaks; ++k) {
          const float stated = angle + 360.0f * static_cast<float>(k) / static_cast<float>(streaks);
          const float diff = std::fmod(std::abs(theta - stated), 360.0f);
          if (std::min(diff, 360.0f - diff) <= 6.0f) along[static_cast<size_t>(k)] += l;
        }
      }
    double sum = 0.0;
    std::printf("%d streaks at %.0f degrees, the light beyond 12 texels within 6 degrees of each:", streaks, angle);
    for (double a : along) {
      sum += a;
      std::printf(" %.1f %%", 100.0 * a / all);
    }
    std::printf(" (all: %.1f %%)\n", 100.0 * sum / all);
    ASSERT_GT(all, 0.0);
    EXPECT_GT(sum / all, 0.9) << streaks << " streaks";
    for (double a : along) EXPECT_NEAR(a / all, 1.0 / streaks, 0.25 / streaks) << streaks << " streaks";
  }
}

// The lens dirt multiplies the flare: with the built-in dirt, the flare is the clean flare times the dirt image (its
// sRGB bytes decoded to linear, filtered) at each pixel, in total within 3 %.
TEST(LensFlare, LensDirtModulatesTheFlare) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(320, 180);
  RenderSettings settings = builtinSceneFlare();
  test::render(renderer, camera, settings, View::Final, test::retaining({"lens-light"}));
  const HdrImage clean = retainedHdr(renderer, "lens-light");
  settings.set("lens-flare.dirt", "builtin");
  test::render(renderer, camera, settings, View::Final, test::retaining({"lens-light"}));
  const HdrImage dirty = retainedHdr(renderer, "lens-light");
  const Image dirt = builtinLensDirt();
  double expected = 0.0, measured = 0.0, plain = 0.0;
  for (int y = 0; y < clean.size.y; ++y)
    for (int x = 0; x < clean.size.x; ++x) {
      // The dirt image's rows run top to bottom, the target's bottom to top: the image stands upright on the frame.
      const int dx = (2 * x + 1) * dirt.width / (2 * clean.size.x), dy = (2 * y + 1) * dirt.height / (2 * clean.size.y);
      const size_t row = static_cast<size_t>(dirt.height - 1 - dy);
      const float d = srgbToLinear(dirt.rgba[(row * static_cast<size_t>(dirt.width) + static_cast<size_t>(dx)) * 4] /
                                   255.0f);
      expected += luminance(clean.at(x, y)) * d;
      measured += luminance(dirty.at(x, y));
      plain += luminance(clean.at(x, y));
    }
  std::printf("flare %.3f clean, %.3f through the dirt (expected %.3f)\n", plain, measured, expected);
  EXPECT_NEAR(measured / expected, 1.0, 0.03);
  EXPECT_LT(measured, 0.8 * plain);
}
