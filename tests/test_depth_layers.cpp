// The AO's second depth layer (ao.layers 2): the depth peel against its CPU mirror on a slab over a floor, and the halo
// it exists to remove, against the ray-traced reference, on a thin pole in front of a far wall.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "TestSupport.h"
#include "effects/ao/DepthPeelPass.h"
#include "encoding/LinearDepthPacking.h"
#include "metrics/AoMetrics.h"
#include "reference/AoReferenceTracer.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

// The 16-bit depth code in a target's BA bytes at pixel (x, y), rows as read back (top to bottom).
std::uint16_t depthCode(const std::vector<std::uint8_t>& rgba, int width, int x, int y) {
  const size_t i = (static_cast<size_t>(y) * width + x) * 4;
  return LinearDepthPacking::codeFromBytes(rgba[i + 2], rgba[i + 3]);
}

// The parameters s (view-space point s * farRay, s = 1 on the far plane) where the ray from `eye` along `direction`
// (world, the far-plane point's offset from the eye) enters and leaves the box [lo, hi]; empty when it misses.
std::vector<float> boxCrossings(const glm::vec3& eye, const glm::vec3& direction, const glm::vec3& lo,
                                const glm::vec3& hi) {
  float enter = -1e30f, leave = 1e30f;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(direction[a]) < 1e-12f) {
      if (eye[a] < lo[a] || eye[a] > hi[a]) return {};
      continue;
    }
    float t0 = (lo[a] - eye[a]) / direction[a], t1 = (hi[a] - eye[a]) / direction[a];
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
  }
  if (enter > leave || leave <= 0.0f) return {};
  return {enter, leave};
}

}  // namespace

// A slab 0.2 m thick floating 0.6 m over a floor, seen from above and in front. Each pixel's surfaces along its ray
// are found analytically (the slab's entry and exit, the floor), and the peel's rule (DepthPeelPass::secondLayerCode)
// gives the second layer: with the default separation, the slab's underside behind its top and sides; with a
// separation larger than the slab's depth extent, the floor under the slab. The GPU's second layer matches the mirror
// to a depth code except along silhouettes, where rasterised coverage and the ray through the pixel centre differ.
TEST(DepthLayers, TheSecondLayerOfASlabOverAFloorMatchesTheCpuMirror) {
  constexpr int kWidth = 160, kHeight = 120;
  const glm::vec3 lo(-0.5f, 0.6f, -0.5f), hi(0.5f, 0.8f, 0.5f);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(
      test::sceneOf({test::makeRectangle({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}), makeBox(lo, hi)}));
  const Camera camera = test::makeCamera({1.2f, 2.4f, 2.2f}, {0.0f, 0.5f, 0.0f}, kWidth, kHeight, 0.1f, 20.0f);
  const FrameCamera frame = FrameCamera::from(camera, kWidth, kHeight);
  const glm::mat4 viewToWorld = glm::inverse(frame.view);

  for (float separation : {0.01f, 0.4f}) {
    RenderSettings settings;
    settings.set("ao.layers", "2");
    settings.set("ao.layer-separation", std::to_string(separation));
    test::render(renderer, camera, settings, View::Ao, test::retaining({"gbuffer", "second-layer"}));
    const std::vector<std::uint8_t> first = renderer.retained("gbuffer").readRgba();
    const std::vector<std::uint8_t> second = renderer.retained("second-layer").readRgba();
    const float minSeparation = DepthPeelPass::separation(settings.ao(), frame);

    int firstMismatches = 0, secondMismatches = 0, floorUnderSlab = 0, slabUnderside = 0, slabPixels = 0;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        // Row y of the read-back image (top to bottom) is GL row kHeight - 1 - y.
        const glm::vec2 uv((static_cast<float>(x) + 0.5f) / kWidth,
                           (static_cast<float>(kHeight - 1 - y) + 0.5f) / kHeight);
        const glm::vec3 farPoint = frame.reconstruction.farPlaneRay(uv);
        const glm::vec3 direction = glm::vec3(viewToWorld * glm::vec4(farPoint, 0.0f));
        // s along the ray is the fraction of the far plane's depth: linear depth (s far - near) / (far - near).
        auto linear = [&](float s) { return (s * camera.far - camera.near) / (camera.far - camera.near); };
        std::vector<float> crossings;
        for (float s : boxCrossings(camera.eye, direction, lo, hi)) crossings.push_back(linear(s));
        const bool slab = !crossings.empty();
        const float floorS = direction.y < 0.0f ? -camera.eye.y / direction.y : -1.0f;
        const glm::vec3 floorPoint = camera.eye + floorS * direction;
        const bool floorHit = floorS > 0.0f && std::abs(floorPoint.x) < 10.0f && std::abs(floorPoint.z) < 10.0f;
        if (floorHit) crossings.push_back(linear(floorS));
        float nearest = 2.0f;
        for (float d : crossings)
          if (d >= 0.0f) nearest = std::min(nearest, d);
        const std::uint16_t firstMirror =
            nearest > 1.0f ? LinearDepthPacking::kBackgroundCode : LinearDepthPacking::codeFromDepth(nearest);
        const std::uint16_t firstGpu = depthCode(first, kWidth, x, y);
        // Compared where the GPU and the ray agree on the visible surface (not on a silhouette's pixels).
        if (std::abs(static_cast<int>(firstGpu) - static_cast<int>(firstMirror)) > 1) {
          ++firstMismatches;
          continue;
        }
        const std::uint16_t secondMirror = DepthPeelPass::secondLayerCode(firstGpu, crossings, minSeparation);
        const std::uint16_t secondGpu = depthCode(second, kWidth, x, y);
        if (std::abs(static_cast<int>(secondGpu) - static_cast<int>(secondMirror)) > 1) ++secondMismatches;
        if (slab) {
          ++slabPixels;
          if (floorHit && secondMirror == LinearDepthPacking::codeFromDepth(linear(floorS))) ++floorUnderSlab;
          else if (secondMirror != LinearDepthPacking::kBackgroundCode) ++slabUnderside;
        }
      }
    }
    const int pixels = kWidth * kHeight;
    std::printf("separation %.2f r: first layer off the mirror at %d px, second at %d px of %d; of the slab's %d px, "
                "the second layer is the floor at %d and the slab's own far side at %d\n",
                separation, firstMismatches, secondMismatches, pixels, slabPixels, floorUnderSlab, slabUnderside);
    EXPECT_GT(slabPixels, pixels / 20);
    EXPECT_LE(firstMismatches, pixels / 200) << "silhouette pixels only";
    EXPECT_LE(secondMismatches, pixels / 200) << "separation " << separation;
    if (separation < 0.1f) EXPECT_GT(slabUnderside, slabPixels * 9 / 10) << "the slab's far side";
    else EXPECT_GT(floorUnderSlab, slabPixels * 9 / 10) << "the floor under the slab";
  }
}

// The halo: a pole 0.1 m thick standing 0.7 m in front of a wall, r = 1 m. A height field takes the pole for a wall
// of its own reaching back to the far one, so the wall beside the pole darkens; the reference traces a thin pole,
// which hides little of the wall's sky. Measured in the band of wall pixels within 8 px of the pole's silhouette,
// against the reference, with one layer (the default thickness heuristic) and with two.
TEST(DepthLayers, TheWallBesideAThinPoleStaysNearTheReference) {
  constexpr int kWidth = 200, kHeight = 150;
  Scene scene = test::sceneOf({test::makeRectangle({-4, -1, -2}, {8, 0, 0}, {0, 5, 0}),
                               makeBox({-0.05f, -1.0f, -1.35f}, {0.05f, 3.0f, -1.25f})});
  const Camera camera = test::makeCamera({0.6f, 1.0f, 1.5f}, {0.0f, 1.0f, -2.0f}, kWidth, kHeight, 0.1f, 20.0f);
  const ReferenceFrame reference = AoReferenceTracer(scene).trace(camera, {1.0f, 256, 2});
  const GreyImage truth = GreyImage::fromRed(reference.aoImage());
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);

  // The wall's pixels within 8 px of a pole pixel (the pole: nearer than 3.2 m; the wall lies 3.5 m away).
  test::render(renderer, camera, RenderSettings(), View::Depth, test::retaining({"gbuffer"}));
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  std::vector<bool> pole(kWidth * kHeight), band(kWidth * kHeight);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const float d = LinearDepthPacking::depthFromCode(depthCode(gbuffer, kWidth, x, y));
      pole[static_cast<size_t>(y * kWidth + x)] = camera.near + d * (camera.far - camera.near) < 3.2f;
    }
  // The wall's interior: its pixels more than 32 px from the pole, where neither layer count changes anything.
  std::vector<bool> interior(kWidth * kHeight);
  int bandPixels = 0, interiorPixels = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const size_t i = static_cast<size_t>(y * kWidth + x);
      if (pole[i] || !reference.mask[i]) continue;
      int distance = 1 << 20;
      for (int xx = std::max(x - 32, 0); xx <= std::min(x + 32, kWidth - 1); ++xx)
        if (pole[static_cast<size_t>(y * kWidth + xx)]) distance = std::min(distance, std::abs(xx - x));
      if (distance <= 8) {
        band[i] = true;
        ++bandPixels;
      } else if (distance > 32) {
        interior[i] = true;
        ++interiorPixels;
      }
    }
  ASSERT_GT(bandPixels, 1000);
  ASSERT_GT(interiorPixels, 1000);

  // One layer (the knots' thickness), two layers, and one layer told the pole's real depth (0.1 r) or the knots'
  // own 0.5 r explicitly: the explicit thickness reaches the shader in place of the knots' value.
  const std::vector<std::pair<const char*, const char*>> configurations = {
      {"ao.layers", "1"}, {"ao.layers", "2"}, {"ao.thickness", "0.1"}, {"ao.thickness", "0.5"}};
  std::vector<double> bandError(configurations.size()), bandBias(configurations.size()),
      interiorError(configurations.size());
  std::vector<std::vector<std::uint8_t>> images;
  for (size_t k = 0; k < configurations.size(); ++k) {
    RenderSettings settings;
    settings.set(configurations[k].first, configurations[k].second);
    const test::RenderedImage ao = test::render(renderer, camera, settings, View::Ao);
    images.push_back(ao.rgba);
    for (size_t i = 0; i < band.size(); ++i) {
      const double e = ao.rgba[i * 4] / 255.0 - truth.values[i];
      if (interior[i]) interiorError[k] += std::abs(e) / interiorPixels;
      if (!band[i]) continue;
      bandError[k] += std::abs(e) / bandPixels;
      bandBias[k] += e / bandPixels;
    }
  }
  std::printf("wall band beside the pole (%d px): MAE %.4f (bias %+.4f) with one layer, %.4f (bias %+.4f) with two; "
              "the wall's interior (%d px): MAE %.4f and %.4f\n",
              bandPixels, bandError[0], bandBias[0], bandError[1], bandBias[1], interiorPixels, interiorError[0],
              interiorError[1]);
  // Measured on llvmpipe: band MAE 0.343 (bias -0.343) with one layer, 0.019 (bias +0.019) with two, interior 0.001
  // and 0.0005. Two layers leave the band a little bright: a tap's two layers bound the pole along the camera's ray,
  // which from the wall's point of view covers less of the pole's cross-section than the pole does, and the taps see
  // the pole's edge only where they land on it (reaching to the midpoint before each tap, gtao.frag: 0.047 without).
  // The bounds: within 0.03 of the reference, and less than a tenth of one layer's error.
  EXPECT_LT(bandError[1], 0.03);
  EXPECT_LT(bandError[1], 0.1 * bandError[0]);
  // One layer told the pole's own thickness: the halo goes (measured: band MAE 0.043, bias +0.043, as close as two
  // layers). The shipped knots hold 0.5 r, so setting that explicitly draws the same image.
  std::printf("one layer, ao.thickness 0.1: band MAE %.4f (bias %+.4f)\n", bandError[2], bandBias[2]);
  EXPECT_LT(bandError[2], 0.5 * bandError[0]);
  EXPECT_EQ(images[3], images[0]);

  // Two layers read through the depth hierarchy (ao.hierarchy on: the atlas folds both layers' depths into one texel
  // a tap; the default reads the peel's target beside the G-buffer) bound the pole as well.
  RenderSettings atlas;
  atlas.set("ao.layers", "2");
  atlas.set("ao.hierarchy", "on");
  const test::RenderedImage atlasAo = test::render(renderer, camera, atlas, View::Ao);
  const std::vector<std::string> ran = test::livePasses(renderer);
  EXPECT_NE(std::find(ran.begin(), ran.end(), "hierarchy"), ran.end());
  double atlasBandError = 0.0;
  for (size_t i = 0; i < band.size(); ++i)
    if (band[i]) atlasBandError += std::abs(atlasAo.rgba[i * 4] / 255.0 - truth.values[i]) / bandPixels;
  std::printf("two layers through the hierarchy: band MAE %.4f\n", atlasBandError);
  EXPECT_LT(atlasBandError, 0.03);
}
