// View-space positions rebuilt from the packed G-buffer of a known plane match the true ones within the depth
// quantisation (CPU mirror core/ViewReconstruction.h over the G-buffer the GPU wrote).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "TestSupport.h"
#include "core/FrameContext.h"
#include "core/LinearDepthPacking.h"

using namespace obscura;

namespace {

struct Case {
  const char* name;
  glm::vec3 eye, target;
  float near, far;
};

void checkPlane(const Case& c) {
  // A large tilted plane through (0, 0, 0) with normal n (world space).
  const glm::vec3 n = glm::normalize(glm::vec3(0.2f, 1.0f, 0.35f));
  const glm::vec3 u = glm::normalize(glm::cross(n, glm::vec3(0, 0, 1))) * 200.0f;
  const glm::vec3 v = glm::normalize(glm::cross(n, u)) * 200.0f;  // u x v points along n
  Renderer renderer = test::makeRenderer();
  renderer.setScene(test::sceneOf({test::makeRectangle(-0.5f * (u + v), u, v)}));
  const Camera camera = test::makeCamera(c.eye, c.target, 160, 120, c.near, c.far);
  AoSettings settings;
  settings.enabled = false;
  test::render(renderer, camera, settings, View::Final);
  const std::vector<std::uint8_t> gbuffer = renderer.gbuffer().readRgba();

  const FrameCamera frame = FrameCamera::from(camera, camera.width, camera.height);
  // The plane in view space: normal nv, through point pv.
  const glm::vec3 nv = glm::normalize(glm::mat3(frame.view) * n);
  const glm::vec3 pv = glm::vec3(frame.view * glm::vec4(0, 0, 0, 1));
  int checked = 0;
  double worstRatio = 0.0;
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      const std::uint8_t* g = &gbuffer[(static_cast<size_t>(y) * camera.width + x) * 4];
      const std::uint16_t code = LinearDepthPacking::codeFromBytes(g[2], g[3]);
      if (code == LinearDepthPacking::kBackgroundCode) continue;
      // Pixel centre in uv, with v up (the read-back rows are top to bottom).
      const glm::vec2 uv((static_cast<float>(x) + 0.5f) / static_cast<float>(camera.width),
                         1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(camera.height));
      const glm::vec3 rebuilt = frame.reconstruction.viewPosition(uv, LinearDepthPacking::depthFromCode(code));
      const glm::vec3 ray = frame.reconstruction.farPlaneRay(uv);
      const glm::vec3 truth = ray * (glm::dot(pv, nv) / glm::dot(ray, nv));
      // Half a depth code in metres along z, scaled to the ray's length, plus float slack.
      const double zStep = 0.5 * (c.far - c.near) / 65535.0;
      const double bound = zStep * glm::length(ray) / c.far + 1e-5 * glm::length(truth);
      const double error = glm::length(rebuilt - truth);
      worstRatio = std::max(worstRatio, error / bound);
      ++checked;
    }
  }
  EXPECT_GT(checked, camera.width * camera.height / 2) << c.name;
  EXPECT_LE(worstRatio, 1.0) << c.name << ": worst error is " << worstRatio << " x the quantisation bound";
}

}  // namespace

TEST(Reconstruction, TiltedPlaneMatchesWithinDepthQuantisation) {
  checkPlane({"oblique", glm::vec3(3.0f, 4.0f, 6.0f), glm::vec3(0.0f, 0.0f, -1.0f), 0.1f, 60.0f});
}

TEST(Reconstruction, GrazingPlaneWithWideDepthRangeMatches) {
  checkPlane({"grazing", glm::vec3(0.0f, 1.2f, 8.0f), glm::vec3(0.0f, 0.6f, -20.0f), 0.05f, 400.0f});
}
