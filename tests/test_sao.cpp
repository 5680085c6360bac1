// SAO behaviour on synthetic scenes, and the shader against its CPU mirror (effects/ao/SaoKernel.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "apps/SceneInput.h"
#include "effects/ao/SaoKernel.h"
#include "encoding/LinearDepthPacking.h"
#include "encoding/NormalEncoding.h"
#include "frame/FrameContext.h"
#include "scene/BuiltinScene.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

AoSettings rawAoSettings() {
  AoSettings settings;
  settings.blur = false;
  return settings;
}

// Every estimator with its fitted defaults, and SAO with the SAO paper's own sigma, beta, k.
std::vector<std::pair<const char*, AoSettings>> defaultAndPaperEstimators() {
  AoSettings paper = rawAoSettings();
  paper.intensity = kPaperEstimatorParameters.intensity;
  paper.bias = kPaperEstimatorParameters.bias;
  paper.contrast = kPaperEstimatorParameters.contrast;
  std::vector<std::pair<const char*, AoSettings>> all = {{"SAO, fitted defaults", rawAoSettings()},
                                                         {"SAO paper's parameters", paper}};
  const std::pair<const char*, AoEstimator> others[] = {{"GTAO, fitted defaults", AoEstimator::Gtao},
                                                        {"HBAO, fitted defaults", AoEstimator::Hbao},
                                                        {"VO, fitted defaults", AoEstimator::Vo},
                                                        {"Crytek, fitted defaults", AoEstimator::Crytek}};
  for (const auto& [name, estimator] : others) {
    AoSettings settings = rawAoSettings();
    settings.estimator = estimator;
    all.push_back({name, settings});
  }
  return all;
}

// Every estimator, blurred, with its fitted defaults.
std::vector<AoSettings> everyEstimator() {
  std::vector<AoSettings> all;
  for (AoEstimator estimator : allAoEstimators()) {
    AoSettings settings;
    settings.estimator = estimator;
    all.push_back(settings);
  }
  return all;
}

// The darkest AO over the geometry, and where it is (for the failure's message).
struct Darkest {
  float ao = 1.0f;
  int x = -1, y = -1;
};

Darkest darkestOverGeometry(const test::RenderedImage& ao, const test::RenderedImage& depth) {
  Darkest darkest;
  for (int y = 0; y < ao.height; ++y)
    for (int x = 0; x < ao.width; ++x)
      if (depth.channel(x, y, 0) < 255 && ao.red(x, y) < darkest.ao) darkest = {ao.red(x, y), x, y};
  return darkest;
}

// Mean AO over a small window.
float meanAo(const test::RenderedImage& ao, int cx, int cy, int half = 2) {
  float sum = 0.0f;
  int count = 0;
  for (int y = cy - half; y <= cy + half; ++y)
    for (int x = cx - half; x <= cx + half; ++x) {
      sum += ao.red(x, y);
      ++count;
    }
  return sum / static_cast<float>(count);
}

Mesh floorMesh(float half = 50.0f) {
  return test::makeRectangle(glm::vec3(-half, 0.0f, half), glm::vec3(2 * half, 0, 0), glm::vec3(0, 0, -2 * half));
}

}  // namespace

TEST(Sao, FlatPlaneFacingTheCameraIsUnoccluded) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(test::sceneOf({test::makeRectangle({-20, -20, 0}, {40, 0, 0}, {0, 40, 0})}));
  const Camera camera = test::makeCamera({0.3f, -0.2f, 4.0f}, {0.3f, -0.2f, 0.0f}, 200, 150);
  for (const auto& [name, settings] : defaultAndPaperEstimators()) {
    const auto ao = test::render(renderer, camera, settings, View::AoRaw);
    const auto depth = test::render(renderer, camera, settings, View::Depth);
    const Darkest darkest = darkestOverGeometry(ao, depth);
    EXPECT_GE(darkest.ao, 0.98f) << name << ": at pixel " << darkest.x << ", " << darkest.y << " of " << ao.width
                                 << " x " << ao.height;
  }
}

TEST(Sao, PlaneAtAGrazingAngleIsUnoccluded) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(test::sceneOf({floorMesh()}));
  // Eye 0.5 m above an endless floor, looking at a point 12 m ahead: the floor is seen at 2 to 20 degrees.
  const Camera camera = test::makeCamera({0.0f, 0.5f, 0.0f}, {0.0f, 0.0f, -12.0f}, 200, 150, 0.05f, 60.0f);
  for (const auto& [name, estimator] : defaultAndPaperEstimators()) {
    for (Falloff falloff : {Falloff::Sao2012, Falloff::Alchemy2011}) {
      AoSettings settings = estimator;
      settings.falloff = falloff;
      const auto ao = test::render(renderer, camera, settings, View::AoRaw);
      const auto depth = test::render(renderer, camera, settings, View::Depth);
      if (settings.estimator == AoEstimator::Crytek || settings.estimator == AoEstimator::Hbao) {
        // Exempt from the bound, held to a fraction of the pixels instead. Crytek's test (shaders_es2/ao/crytek.frag)
        // compares the depths of sample points with the depth buffer at the pixels they project to, with no normal,
        // and on a plane this far from face-on the depth changes across one pixel (or across a hierarchy block, for
        // far taps) by more than the bias, so some points just above the plane test as behind it: the original's
        // self-occlusion at grazing angles, a sprinkle of pixels (measured 360 of 16000 below 0.98 with the
        // intensity fitted on 2026-11-28, 213 with the paper's; 64 with the fit before): at most 3 %. HBAO's fitted
        // angle bias is 0 at the largest radii in pixels, where it lowered the error against the reference, so a
        // near tap whose quantised depth lifts its elevation counts, and the fitted contrast (k up to 5) darkens it:
        // 5 pixels of 16000 (0.03 %): at most 0.1 %.
        size_t geometry = 0, darker = 0;
        for (int y = 0; y < ao.height; ++y)
          for (int x = 0; x < ao.width; ++x)
            if (depth.channel(x, y, 0) < 255) {
              ++geometry;
              darker += ao.red(x, y) < 0.98f;
            }
        const size_t allowed = settings.estimator == AoEstimator::Crytek ? geometry * 3 / 100 : geometry / 1000;
        EXPECT_LE(darker, allowed) << name << ", " << falloffName(falloff) << ": " << darker << " of " << geometry
                                   << " pixels below 0.98";
        continue;
      }
      EXPECT_GE(darkestOverGeometry(ao, depth).ao, 0.98f) << name << ", " << falloffName(falloff);
    }
  }
}

TEST(Sao, InsideCornerIsDarkerThanOpenFloor) {
  Renderer renderer = test::makeRenderer();
  // Floor y = 0 and a wall z = -3 facing +z.
  renderer.setScene(test::sceneOf({floorMesh(), test::makeRectangle({-50, 0, -3}, {100, 0, 0}, {0, 10, 0})}));
  const Camera camera = test::makeCamera({0.0f, 1.5f, 2.0f}, {0.0f, 0.5f, -3.0f}, 240, 180);
  // Project the corner point (0, 0.05, -2.95) and an open floor point (0, 0, 0.5) into the image.
  const FrameCamera frame = FrameCamera::from(camera, camera.width, camera.height);
  auto pixelOf = [&](glm::vec3 p) {
    const glm::vec4 clip = frame.projection * frame.view * glm::vec4(p, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return glm::ivec2(static_cast<int>((ndc.x * 0.5f + 0.5f) * static_cast<float>(camera.width)),
                      static_cast<int>((0.5f - ndc.y * 0.5f) * static_cast<float>(camera.height)));
  };
  const glm::ivec2 corner = pixelOf({0.0f, 0.05f, -2.95f});
  const glm::ivec2 open = pixelOf({0.0f, 0.0f, -0.8f});  // 2.2 m from the wall, more than the 1 m radius
  ASSERT_TRUE(corner.y > 2 && corner.y < camera.height - 3 && open.y > 2 && open.y < camera.height - 3);
  for (const AoSettings& settings : everyEstimator()) {
    const auto ao = test::render(renderer, camera, settings, View::Ao);
    const float cornerAo = meanAo(ao, corner.x, corner.y);
    const float openAo = meanAo(ao, open.x, open.y);
    // Crytek's grazing-angle sprinkle (PlaneAtAGrazingAngleIsUnoccluded) reaches the open floor's few pixels: 0.977
    // with its 2026-11-28 fit.
    EXPECT_GE(openAo, settings.estimator == AoEstimator::Crytek ? 0.97f : 0.98f) << estimatorName(settings.estimator);
    EXPECT_LT(cornerAo, openAo - 0.2f) << estimatorName(settings.estimator) << ": corner " << cornerAo
                                       << ", open floor " << openAo;
  }
}

TEST(Sao, SphereOnTheFloorCastsAContactShadow) {
  Renderer renderer = test::makeRenderer();
  Mesh sphere = makeSphere(0.5f, 64, 32);
  for (glm::vec3& p : sphere.positions) p += glm::vec3(0.0f, 0.5f, 0.0f);
  renderer.setScene(test::sceneOf({floorMesh(), std::move(sphere)}));
  // Looking down at the sphere from the front and above.
  const Camera camera = test::makeCamera({0.0f, 2.5f, 3.0f}, {0.0f, 0.0f, 0.0f}, 240, 180);
  const FrameCamera frame = FrameCamera::from(camera, camera.width, camera.height);
  for (const AoSettings& settings : everyEstimator()) {
  const auto ao = test::render(renderer, camera, settings, View::Ao);
  auto aoAt = [&](glm::vec3 p) {
    const glm::vec4 clip = frame.projection * frame.view * glm::vec4(p, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return meanAo(ao, static_cast<int>((ndc.x * 0.5f + 0.5f) * static_cast<float>(camera.width)),
                  static_cast<int>((0.5f - ndc.y * 0.5f) * static_cast<float>(camera.height)), 1);
  };
  // Floor beside the contact point (left of the sphere, 0.15 m from where it touches) vs open floor 2 m away.
  const float contact = aoAt({-0.32f, 0.0f, 0.1f});
  const float open = aoAt({-2.0f, 0.0f, 0.5f});
  EXPECT_GE(open, 0.97f) << estimatorName(settings.estimator);
  EXPECT_LT(contact, open - 0.25f) << estimatorName(settings.estimator) << ": contact " << contact << ", open "
                                   << open;
  }
}

TEST(Sao, NearAndFarPlanesDoNotChangeTheAo) {
  Renderer renderer = test::makeRenderer();
  Mesh sphere = makeSphere(0.5f, 64, 32);
  for (glm::vec3& p : sphere.positions) p += glm::vec3(0.3f, 0.5f, -0.5f);
  renderer.setScene(test::sceneOf({floorMesh(20.0f), test::makeRectangle({-20, 0, -3}, {40, 0, 0}, {0, 6, 0}),
                                   makeBox({-1.8f, 0, -1.5f}, {-0.8f, 0.8f, -0.5f}), std::move(sphere)}));
  const Camera a = test::makeCamera({1.0f, 1.6f, 3.5f}, {-0.2f, 0.4f, -1.0f}, 240, 180, 0.1f, 40.0f);
  Camera b = a;
  b.near = 0.5f;
  b.far = 120.0f;
  // A tap whose depth code lands across the radius's hard cut (SAO's Alchemy falloff) or across a horizon (GTAO
  // keeps each side's highest) moves its pixel's estimate: measured blurred max 3/255 (SAO) and 4/255 (GTAO), 35 and
  // 45 raw pixels of 43200 beyond 2/255.
  struct Bounds {
    AoEstimator estimator;
    int blurredMax;
    size_t rawOutsideDivisor;
  };
  // HBAO's nearest taps, a pixel out, read depths whose quantisation moves their elevation by more than the angle
  // bias: 356 raw pixels beyond 2/255, by a few 255ths, which the blur averages (blurred max 1/255). Crytek's
  // depth tests are all or nothing (no falloff), so a depth quantised differently flips whole tests, and its fitted
  // intensity (sigma about 10: one pair of five occluded on both sides darkens a pixel fully) makes a flipped test a
  // flipped pixel: blurred max 19/255 (7 with the paper's sigma = 1). VO: 2/255, 19 raw pixels.
  for (const Bounds& bounds : {Bounds{AoEstimator::Sao, 5, 500}, Bounds{AoEstimator::Gtao, 5, 500},
                               Bounds{AoEstimator::Hbao, 5, 100}, Bounds{AoEstimator::Vo, 5, 500},
                               Bounds{AoEstimator::Crytek, 24, 500}}) {
    AoSettings settings;
    settings.estimator = bounds.estimator;
    const char* name = estimatorName(bounds.estimator);
    // The blurred AO (what the image uses) agrees everywhere within a few 255ths.
    {
      const auto first = test::render(renderer, a, settings, View::Ao);
      const auto second = test::render(renderer, b, settings, View::Ao);
      int worst = 0;
      for (size_t i = 0; i < first.rgba.size(); i += 4)
        worst = std::max(worst, std::abs(first.rgba[i] - second.rgba[i]));
      EXPECT_LE(worst, bounds.blurredMax) << name << ": blurred AO: max difference " << worst << "/255";
    }
    // The raw AO agrees almost everywhere: a depth quantised differently can move a tap across a silhouette, which
    // changes that one pixel's estimate until the blur averages it with its neighbours.
    {
      const auto first = test::render(renderer, a, settings, View::AoRaw);
      const auto second = test::render(renderer, b, settings, View::AoRaw);
      size_t outside = 0, pixels = first.rgba.size() / 4;
      double sum = 0.0;
      for (size_t i = 0; i < first.rgba.size(); i += 4) {
        const int diff = std::abs(first.rgba[i] - second.rgba[i]);
        sum += diff;
        outside += diff > 2;
      }
      EXPECT_LE(sum / static_cast<double>(pixels), 0.25) << name << ": raw AO mean difference (of 255)";
      EXPECT_LE(outside, pixels / bounds.rawOutsideDivisor)
          << name << ": " << outside << " raw AO pixels differ by more than 2/255";
    }
  }
}

// The estimator measures distances in units of the radius (SaoKernel.h), and the blur's depth sigma is a fraction of
// it, so the built-in scene scaled by s and seen with its camera scaled by s (eye, target, near, far) gives the same
// AO at radius s as the scene in metres at 1 m: within 1/255 everywhere, from millimetres to hectometres, at full
// (medium) and half (low) resolution, for every estimator.
// The moving scene (at rest): scaleScene scales the nodes its pendulum and limb are posed by too.
TEST(Sao, ScalingTheSceneAndTheRadiusTogetherGivesTheSameAo) {
  const Scene metres = makeBuiltinScene();
  const Camera camera = builtinSceneCamera(320, 180);
  Renderer renderer = test::makeRenderer();
  // Every estimator, and GTAO with each option of the depth layers and the normals (ao.layers 2: the peel's
  // separation is in units of r; gbuffer.normals reconstructed: the differences are of scaled depths alike).
  struct Variant {
    AoEstimator estimator;
    QualityPreset preset;
    const char* layers;
    const char* normals;
  };
  for (const Variant& variant :
       {Variant{AoEstimator::Sao, QualityPreset::Medium, "1", "stored"},
        Variant{AoEstimator::Sao, QualityPreset::Low, "1", "stored"},
        Variant{AoEstimator::Gtao, QualityPreset::Medium, "1", "stored"},
        Variant{AoEstimator::Gtao, QualityPreset::Medium, "2", "stored"},
        Variant{AoEstimator::Gtao, QualityPreset::Medium, "1", "reconstructed"},
        Variant{AoEstimator::Gtao, QualityPreset::Low, "2", "reconstructed"},
        Variant{AoEstimator::Hbao, QualityPreset::Medium, "1", "stored"},
        Variant{AoEstimator::Vo, QualityPreset::Medium, "1", "stored"},
        Variant{AoEstimator::Crytek, QualityPreset::Medium, "1", "stored"}}) {
    const AoEstimator estimator = variant.estimator;
    const QualityPreset preset = variant.preset;
    RenderSettings settings;
    settings.ao().applyPreset(preset);
    settings.ao().estimator = estimator;
    settings.set("ao.layers", variant.layers);
    settings.set("gbuffer.normals", variant.normals);
    renderer.setScene(metres);
    const test::RenderedImage expected = test::render(renderer, camera, settings, View::Ao);
    for (float scale : {0.001f, 0.01f, 100.0f}) {
      Scene scaled = metres;
      scaleScene(scaled, scale);
      renderer.setScene(scaled);
      Camera scaledCamera = camera;
      scaledCamera.eye *= scale;
      scaledCamera.target *= scale;
      scaledCamera.near *= scale;
      scaledCamera.far *= scale;
      RenderSettings scaledSettings = settings;
      scaledSettings.ao().radius = settings.ao().radius * scale;
      const test::RenderedImage ao = test::render(renderer, scaledCamera, scaledSettings, View::Ao);
      int worst = 0;
      for (size_t i = 0; i < ao.rgba.size(); i += 4) worst = std::max(worst, std::abs(ao.rgba[i] - expected.rgba[i]));
      EXPECT_LE(worst, 1) << estimatorName(estimator) << ", " << presetName(preset) << ", " << variant.layers
                          << " layers, normals " << variant.normals << ", scale " << scale << ": max difference "
                          << worst << "/255";
    }
  }
}

// The shader against the CPU mirror: both evaluate SAO over the same G-buffer, with and without the hierarchy.
TEST(Sao, ShaderMatchesTheCpuMirror) {
  Renderer renderer = test::makeRenderer();
  Mesh sphere = makeSphere(0.5f, 48, 24);
  for (glm::vec3& p : sphere.positions) p += glm::vec3(0.0f, 0.5f, 0.0f);
  renderer.setScene(test::sceneOf({floorMesh(20.0f), std::move(sphere),
                                   test::makeRectangle({-20, 0, -2}, {40, 0, 0}, {0, 6, 0})}));
  const Camera camera = test::makeCamera({0.8f, 1.4f, 3.0f}, {0.0f, 0.4f, -0.5f}, 160, 120);
  for (bool hierarchy : {false, true}) {
    for (Falloff falloff : {Falloff::Sao2012, Falloff::Alchemy2011}) {
      AoSettings settings = rawAoSettings();
      settings.estimator = AoEstimator::Sao;  // the estimator SaoKernel mirrors
      settings.falloff = falloff;
      settings.samples = 16;
      settings.spiralTurns = SaoKernel::bestSpiralTurns(16);
      settings.depthHierarchy = hierarchy ? DepthHierarchy::On : DepthHierarchy::Off;
      settings.radius = 2.0f;  // far taps reach hierarchy levels 1 and 2 at this size
      const EstimatorKnots knots = settings.estimatorKnots();
      const auto gpu = test::render(renderer, camera, settings, View::AoRaw, test::retaining({"gbuffer"}));
      const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
      const FrameCamera frame = FrameCamera::from(camera, camera.width, camera.height);
      const int w = camera.width, h = camera.height;
      const glm::ivec2 size(w, h);
      // G-buffer texel at integer pixel (x, y) counted from the bottom, as the shader addresses it.
      auto texel = [&](glm::ivec2 p) { return &gbuffer[(static_cast<size_t>(h - 1 - p.y) * w + p.x) * 4]; };
      auto code = [&](glm::ivec2 p) { return LinearDepthPacking::codeFromBytes(texel(p)[2], texel(p)[3]); };
      auto position = [&](glm::ivec2 p, std::uint16_t depthCode) {
        const glm::vec2 uv((static_cast<float>(p.x) + 0.5f) / static_cast<float>(w),
                           (static_cast<float>(p.y) + 0.5f) / static_cast<float>(h));
        return frame.reconstruction.viewPosition(uv, LinearDepthPacking::depthFromCode(depthCode));
      };
      double sumDiff = 0.0;
      int count = 0, large = 0;
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const glm::ivec2 pixel(x, y);
          if (code(pixel) == LinearDepthPacking::kBackgroundCode) continue;
          const glm::vec3 c = position(pixel, code(pixel));
          const glm::vec3 n = decodeNormal(texel(pixel)[0], texel(pixel)[1]);
          const float disk = SaoKernel::diskRadiusPixels(settings.radius, c.z, frame.projScale(h),
                                                         settings.maxScreenRadius * static_cast<float>(h));
          const float spin = SaoKernel::rotationAngle(static_cast<float>(x), static_cast<float>(y));
          const EstimatorParameters estimator = knots.interpolate(disk);  // this pixel's, at its radius in pixels
          float sum = 0.0f;
          for (int i = 0; i < settings.samples; ++i) {
            float alpha = 0.0f;
            const glm::vec2 dir = SaoKernel::tapDirection(i, settings.samples, settings.spiralTurns, spin, &alpha);
            const float distance = alpha * disk;
            const glm::ivec2 tap =
                glm::clamp(glm::ivec2(glm::floor(glm::vec2(pixel) + 0.5f + distance * dir)), glm::ivec2(0), size - 1);
            // The pixel whose surface point the tap reads: itself, or the hierarchy level's pick for its block.
            glm::ivec2 source = tap;
            if (hierarchy) {
              const int level = SaoKernel::hierarchyLevel(distance);
              source = SaoKernel::hierarchySourcePixel(
                  glm::min(tap / (1 << level), SaoKernel::hierarchyLevelSize(size, level) - 1), level, size);
            }
            sum += SaoKernel::tapObscurance(falloff, position(source, code(source)) - c, n, settings.radius,
                                            estimator.bias);
          }
          const float cpu = SaoKernel::ambientVisibility(falloff, sum, settings.samples, estimator.intensity,
                                                         estimator.contrast);
          const float diff = std::abs(cpu * 255.0f - static_cast<float>(gpu.channel(x, h - 1 - y, 0)));
          sumDiff += diff;
          large += diff > 4.0f;
          ++count;
        }
      }
      ASSERT_GT(count, w * h / 2);
      // Float evaluation differs a little (cos/sin, fused multiply-add), which can move a tap to the neighbouring
      // texel; the mean agrees to well under one code and almost every pixel within four codes.
      EXPECT_LE(sumDiff / count, 1.0) << falloffName(falloff) << " hierarchy " << hierarchy;
      EXPECT_LE(large, count / 100) << falloffName(falloff) << " hierarchy " << hierarchy;
    }
  }
}
