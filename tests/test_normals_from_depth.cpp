// Normals reconstructed from the G-buffer's depth (gbuffer.normals reconstructed: lib/normal_from_depth.glsl) against
// the normals the G-buffer stores, on a plane, a sphere and a crease; and the shader against its CPU mirror
// (frame/NormalFromDepth.h). The normals-from-depth view shows what the AO estimator reconstructs, black where it falls
// back to the stored normal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "TestSupport.h"
#include "encoding/LinearDepthPacking.h"
#include "frame/FrameContext.h"
#include "frame/NormalFromDepth.h"
#include "scene/BuiltinScene.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

glm::vec3 decodeViewNormal(const test::RenderedImage& image, size_t pixel) {
  const std::uint8_t* t = &image.rgba[pixel * 4];
  return glm::vec3(t[0], t[1], t[2]) * (2.0f / 255.0f) - 1.0f;
}
bool isFallback(const test::RenderedImage& image, size_t pixel) {
  const std::uint8_t* t = &image.rgba[pixel * 4];
  return t[0] == 0 && t[1] == 0 && t[2] == 0;
}

struct Comparison {
  int pixels = 0, fallbacks = 0, fallbacksOffEdges = 0, beyondTenDegrees = 0;
  double meanDegrees = 0, p95Degrees = 0, maxDegrees = 0;
};

// The reconstructed normals against the stored ones over the geometry; fallbacks counted apart, with those more than a
// pixel from a depth edge (a neighbour more than 10 % of the depth away, the shader's criterion).
Comparison compareNormals(Renderer& renderer, const Camera& camera) {
  test::render(renderer, camera, RenderSettings(), View::Depth, test::retaining({"gbuffer"}));
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  const test::RenderedImage stored = test::render(renderer, camera, RenderSettings(), View::Normals);
  const test::RenderedImage fromDepth =
      test::render(renderer, camera, RenderSettings(), parseView("normals-from-depth"));
  const int w = camera.width, h = camera.height;
  auto code = [&](int x, int y) {
    const size_t i = (static_cast<size_t>(y) * w + x) * 4;
    return LinearDepthPacking::codeFromBytes(gbuffer[i + 2], gbuffer[i + 3]);
  };
  auto nearEdge = [&](int x, int y) {
    const float d = static_cast<float>(code(x, y));
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
        if (std::abs(static_cast<float>(code(xx, yy)) - d) > 0.1f * d) return true;
      }
    return false;
  };
  Comparison c;
  std::vector<double> degrees;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (code(x, y) == LinearDepthPacking::kBackgroundCode) continue;
      ++c.pixels;
      if (isFallback(fromDepth, i)) {
        ++c.fallbacks;
        if (!nearEdge(x, y)) ++c.fallbacksOffEdges;
        continue;
      }
      const float cosine = glm::dot(glm::normalize(decodeViewNormal(stored, i)),
                                    glm::normalize(decodeViewNormal(fromDepth, i)));
      degrees.push_back(std::acos(std::clamp(cosine, -1.0f, 1.0f)) * 57.29578);
      c.beyondTenDegrees += degrees.back() > 10.0;
    }
  std::sort(degrees.begin(), degrees.end());
  for (double d : degrees) c.meanDegrees += d / static_cast<double>(degrees.size());
  c.p95Degrees = degrees[degrees.size() * 95 / 100];
  c.maxDegrees = degrees.back();
  return c;
}

void print(const char* what, const Comparison& c) {
  std::printf("%s: %d px, angle to the stored normal mean %.2f, 95th percentile %.2f, max %.1f degrees, %d px beyond "
              "10; falls back at %d px (%d more than two pixels from a depth edge)\n",
              what, c.pixels, c.meanDegrees, c.p95Degrees, c.maxDegrees, c.beyondTenDegrees, c.fallbacks,
              c.fallbacksOffEdges);
}

}  // namespace

// A floor seen at 35 degrees, 2 to 12 m away: one plane, so the only error is the 16-bit depth's and the views' 8-bit
// normals. No pixel falls back.
TEST(NormalsFromDepth, APlaneGivesItsNormal) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(test::sceneOf({test::makeRectangle({-20, 0, 20}, {40, 0, 0}, {0, 0, -40})}));
  const Camera camera = test::makeCamera({0, 3, 4}, {0, 0, -3}, 160, 120, 0.1f, 30.0f);
  const Comparison c = compareNormals(renderer, camera);
  print("plane", c);
  EXPECT_GT(c.pixels, 160 * 120 / 3);
  EXPECT_LT(c.meanDegrees, 1.5);
  EXPECT_LT(c.p95Degrees, 3.0);
  EXPECT_EQ(c.fallbacks, 0);
}

// A sphere 0.5 m in radius, 48 x 24 facets, 2.5 m away: the reconstruction follows the facets, the stored normal the
// smooth interpolation between them. Falls back only on the silhouette, where a neighbour on each side is the
// background.
TEST(NormalsFromDepth, ASphereGivesItsFacetsNormals) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(test::sceneOf({makeSphere(0.5f, 48, 24)}));
  const Camera camera = test::makeCamera({0, 0.5f, 2.5f}, {0, 0, 0}, 160, 120, 0.1f, 30.0f);
  const Comparison c = compareNormals(renderer, camera);
  print("sphere", c);
  EXPECT_GT(c.pixels, 2000);
  EXPECT_LT(c.meanDegrees, 4.0);
  EXPECT_LT(c.p95Degrees, 8.0);
  EXPECT_EQ(c.fallbacksOffEdges, 0);
  EXPECT_LT(c.fallbacks, c.pixels / 20);
}

// A floor meeting a wall (a crease of 90 degrees): the lesser one-sided difference keeps each pixel on its own plane,
// where a central difference would tilt the line of pixels along the crease by 45 degrees. On the line itself, a pixel
// that the rasteriser gives to one plane may take the other's normal (its step to the other plane is the smaller): at
// most one pixel per column of the crease, measured 130 of 160 columns.
TEST(NormalsFromDepth, ACreaseKeepsEachSidesNormal) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(test::sceneOf({test::makeRectangle({-20, 0, 20}, {40, 0, 0}, {0, 0, -40}),
                                   test::makeRectangle({-20, 0, -2}, {40, 0, 0}, {0, 10, 0})}));
  const Camera camera = test::makeCamera({1, 2, 3}, {0, 0.5f, -2}, 160, 120, 0.1f, 30.0f);
  const Comparison c = compareNormals(renderer, camera);
  print("crease", c);
  EXPECT_LT(c.meanDegrees, 1.5);
  EXPECT_LE(c.beyondTenDegrees, camera.width);
  EXPECT_EQ(c.fallbacks, 0);
}

// The shader against the CPU mirror on the built-in scene: the same normal within the view's 8-bit steps, and the same
// pixels falling back.
TEST(NormalsFromDepth, TheShaderMatchesTheCpuMirror) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const Camera camera = builtinSceneCamera(200, 120);
  test::render(renderer, camera, RenderSettings(), View::Depth, test::retaining({"gbuffer"}));
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  const test::RenderedImage fromDepth =
      test::render(renderer, camera, RenderSettings(), parseView("normals-from-depth"));
  const int w = camera.width, h = camera.height;
  const ViewReconstruction view = FrameCamera::from(camera, w, h).reconstruction;
  // The mirror's pixel (x, y) counts rows from the bottom (GL); the read-back images from the top.
  auto code = [&](int x, int y) {
    const size_t i = (static_cast<size_t>(h - 1 - y) * w + x) * 4;
    return LinearDepthPacking::codeFromBytes(gbuffer[i + 2], gbuffer[i + 3]);
  };
  int compared = 0, fallbacks = 0, fallbackDisagreements = 0;
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (code(x, y) == LinearDepthPacking::kBackgroundCode) continue;
      const size_t i = static_cast<size_t>(h - 1 - y) * w + x;
      const std::optional<glm::vec3> mirror = normalFromDepth(view, {w, h}, {x, y}, code);
      fallbacks += !mirror;
      if (!mirror || isFallback(fromDepth, i)) {
        fallbackDisagreements += mirror.has_value() != !isFallback(fromDepth, i);
        continue;
      }
      ++compared;
      const glm::vec3 gpu = decodeViewNormal(fromDepth, i);
      worst = std::max(worst, static_cast<double>(glm::length(gpu - *mirror)));
    }
  std::printf("shader against mirror: %d px, largest difference %.4f (the view's step is %.4f); the mirror falls back "
              "at %d px, %d disagree on falling back\n",
              compared, worst, 2.0 / 255.0, fallbacks, fallbackDisagreements);
  EXPECT_GT(compared, w * h / 2);
  EXPECT_LT(worst, 3.0 / 255.0);
  EXPECT_LE(fallbackDisagreements, 2);
}
