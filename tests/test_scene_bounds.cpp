// The passes that draw only over the scene's bounds on screen (PassContext::sceneRect: the AO's estimator, blur and
// upsample, the deferred lighting's shading, FXAA; docs/benchmarks.md, issue 26): the bounds hold every pixel the
// G-buffer pass drew, and the frame is the one the passes give over the whole frame, byte for byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "encoding/LinearDepthPacking.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

// A sphere and a box standing apart on nothing, seen from a distance: they cover a part of the frame, with the
// environment's background all around.
Scene twoObjects() {
  Scene scene;
  test::addStill(scene, makeSphere(1.0f, 24, 12), glm::vec3(0.8f, 0.7f, 0.6f));
  test::addStill(scene, makeBox(glm::vec3(1.5f, -1.0f, -0.5f), glm::vec3(2.5f, 0.5f, 0.5f)), glm::vec3(0.5f));
  return scene;
}

}  // namespace

TEST(SceneBounds, TheCoveredRectangleHoldsEveryPixelTheGBufferDrew) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(twoObjects());
  const Camera camera = test::makeCamera(glm::vec3(0.5f, 1.0f, 9.0f), glm::vec3(0.5f, 0.0f, 0.0f), 160, 90);
  RenderSettings settings;
  test::render(renderer, camera, settings, View::Final, test::retaining({"gbuffer"}));
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  const FrameCamera& frame = renderer.lastFrame().camera;
  const glm::ivec4 rect =
      renderer.gpuScene().coveredRect(frame.projection * frame.view, glm::ivec2(camera.width, camera.height));
  int drawn = 0, outside = 0;
  for (int row = 0; row < camera.height; ++row)
    for (int x = 0; x < camera.width; ++x) {
      const size_t i = (static_cast<size_t>(row) * camera.width + x) * 4;
      if (LinearDepthPacking::codeFromBytes(gbuffer[i + 2], gbuffer[i + 3]) == 65535) continue;
      ++drawn;
      const int y = camera.height - 1 - row;  // GL window coordinates, y up
      outside += x < rect.x || x >= rect.x + rect.z || y < rect.y || y >= rect.y + rect.w;
    }
  EXPECT_GT(drawn, 500) << "the objects are in view";
  EXPECT_EQ(outside, 0) << "G-buffer pixels outside the covered rectangle " << rect.x << "," << rect.y << " "
                        << rect.z << "x" << rect.w;
  EXPECT_LT(rect.z * rect.w, camera.width * camera.height / 2) << "the bounds leave most of the frame to the sky";
  EXPECT_TRUE(renderer.lastFrame().sceneBounds == rect) << "the frame's bounds are the scene's";

  Renderer empty = test::makeRenderer();
  empty.setScene(Scene{});
  test::render(empty, camera, settings, View::Final);
  const glm::ivec4 none = empty.gpuScene().coveredRect(frame.projection * frame.view, glm::ivec2(160, 90));
  EXPECT_EQ(none.z * none.w, 0) << "an empty scene covers nothing";
}

namespace {

// The frame of `settings` and `view` drawn with the passes limited to the scene's bounds, and over the whole frame.
std::pair<test::RenderedImage, test::RenderedImage> limitedAndWhole(const Scene& scene, const Camera& camera,
                                                                    const RenderSettings& settings, const View& view) {
  auto renderWith = [&](bool limit) {
    RendererOptions options;
    options.limitToScene = limit;
    Renderer renderer = test::makeRenderer(options);
    renderer.setScene(scene);
    return test::render(renderer, camera, settings, view);
  };
  return {renderWith(true), renderWith(false)};
}

const Camera kAfar = test::makeCamera(glm::vec3(0.5f, 1.0f, 9.0f), glm::vec3(0.5f, 0.0f, 0.0f), 160, 90);
const Camera kNear = test::makeCamera(glm::vec3(0.5f, 0.5f, 2.5f), glm::vec3(0.5f, 0.0f, 0.0f), 160, 90);

// A frame to compare: what it shows, its view and the settings it changes from the defaults.
struct FrameCase {
  const char* what;
  View view;
  std::vector<std::pair<const char*, const char*>> settings;
  RenderSettings renderSettings() const {
    RenderSettings made;
    for (const auto& [name, value] : settings) made.set(name, value);
    return made;
  }
};

}  // namespace

TEST(SceneBounds, PassesLimitedToTheScenesBoundsDrawTheFrameOfWholeFramePasses) {
  const std::vector<FrameCase> cases = {
      {"defaults", View::Final, {}},
      {"the AO view", View::Ao, {}},
      {"half-resolution AO", View::Final, {{"ao.half-res", "on"}}},
      {"preset low (the lighting into the output)", View::Final, {{"preset", "low"}}},
      {"fog, bloom and depth of field", View::Final, {{"fog", "on"}, {"bloom", "on"}, {"dof", "on"}}},
      {"split view (each half a region of the output)", View::Split, {}},
  };
  const Scene scene = twoObjects();
  // From afar the bounds are a part of the frame; from near they are all of it.
  for (const Camera* camera : {&kAfar, &kNear})
    for (const FrameCase& c : cases) {
      const auto [limited, whole] = limitedAndWhole(scene, *camera, c.renderSettings(), c.view);
      EXPECT_EQ(test::worstByteDifference(limited, whole), 0) << c.what << (camera == &kNear ? ", near" : ", afar");
    }
}

// Below render scale 1 FXAA's pass also upscales, and around the bounds its pass-through upscales without FXAA.
// FXAA then no longer smooths the environment's own edges there (the built-in sky's horizon, sharp at this frame's
// 80 x 45 pixels), and the same upscale compiled into a second program rounds apart by a level in places.
TEST(SceneBounds, BelowRenderScaleOneTheBackgroundIsUpscaledWithoutFxaa) {
  RenderSettings settings;
  settings.set("resolution.scale", "0.5");
  const auto [limited, whole] = limitedAndWhole(twoObjects(), kAfar, settings, View::Final);
  int apart = 0;
  for (size_t i = 0; i < limited.rgba.size(); i += 4) {
    int worst = 0;
    for (size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(limited.rgba[i + c] - whole.rgba[i + c]));
    apart += worst > 1;
  }
  EXPECT_LE(test::worstByteDifference(limited, whole), 16);
  EXPECT_LE(apart, limited.width * limited.height / 50) << "pixels more than a level apart";
}

namespace {

// twoObjects, and what kAfar cannot see: a sphere behind the eye, a box far to the left, and a row of boxes sharing a
// material (a static batch) from well inside the view to well outside it on both sides. With `outOfView` false, the
// row's middle alone and nothing else out of view.
Scene withObjectsOutOfView(bool outOfView) {
  Scene scene = twoObjects();
  auto place = [&](const glm::vec3& at) { scene.instances.back().world = glm::translate(glm::mat4(1.0f), at); };
  if (outOfView) {
    test::addStill(scene, makeSphere(1.0f, 24, 12), glm::vec3(0.3f, 0.6f, 0.9f));
    place({0.5f, 1.0f, 15.0f});
    test::addStill(scene, makeBox(glm::vec3(-1.0f), glm::vec3(1.0f)), glm::vec3(0.9f, 0.3f, 0.3f));
    place({-40.0f, 0.0f, 0.0f});
  }
  Mesh block = makeBox(glm::vec3(-0.4f), glm::vec3(0.4f));
  block.material = test::addMaterial(scene, glm::vec3(0.6f));
  scene.meshes.push_back(std::move(block));
  for (int k = -8; k <= 8; ++k) {
    if (!outOfView && std::abs(k) > 1) continue;
    scene.instances.push_back({static_cast<int>(scene.meshes.size()) - 1, glm::mat4(1.0f), -1, -1});
    place({0.5f + 5.0f * static_cast<float>(k), -1.5f, 0.0f});
  }
  return scene;
}

}  // namespace

// Frustum culling (GpuScene::cullToView): the instances the view cannot see are not drawn, and the frame is the same
// bytes as with every instance drawn, through every pass that draws the scene.
TEST(SceneBounds, InstancesOutOfViewAreNotDrawnAndTheFrameIsTheSame) {
  const std::vector<FrameCase> cases = {
      {"defaults", View::Final, {}},
      {"the AO view, two depth layers", View::Ao, {{"ao.layers", "2"}}},
      {"preset low", View::Final, {{"preset", "low"}}},
      {"fog, bloom, depth of field and edges", View::Final, {{"fog", "on"}, {"bloom", "on"}, {"dof", "on"},
                                                            {"edges", "on"}}},
      {"motion blur and TAA", View::Final, {{"motion-blur", "on"}, {"taa", "on"}}},
      {"split view", View::Split, {}},
  };
  const Scene scene = withObjectsOutOfView(true);
  RendererOptions wholeScene;
  wholeScene.cullToView = false;
  Renderer culled = test::makeRenderer();
  Renderer whole = test::makeRenderer(wholeScene);
  culled.setScene(scene);
  whole.setScene(scene);
  for (const FrameCase& c : cases) {
    const test::RenderedImage a = test::render(culled, kAfar, c.renderSettings(), c.view);
    const test::RenderedImage b = test::render(whole, kAfar, c.renderSettings(), c.view);
    EXPECT_EQ(test::worstByteDifference(a, b), 0) << c.what;
  }

  // The G-buffer's draws (the defaults' only geometry pass): culled, exactly the triangles of the instances in view.
  const RenderSettings defaults;
  test::render(culled, kAfar, defaults, View::Final);
  test::render(whole, kAfar, defaults, View::Final);
  Renderer inViewOnly = test::makeRenderer();
  inViewOnly.setScene(withObjectsOutOfView(false));
  test::render(inViewOnly, kAfar, defaults, View::Final);
  const GpuScene::Counts culledCounts = culled.gpuScene().lastDrawCounts();
  const GpuScene::Counts wholeCounts = whole.gpuScene().lastDrawCounts();
  const GpuScene::Counts inViewCounts = inViewOnly.gpuScene().lastDrawCounts();
  EXPECT_EQ(culledCounts.triangles, inViewCounts.triangles);
  EXPECT_LT(culledCounts.triangles, wholeCounts.triangles);
  EXPECT_EQ(culled.gpuScene().staticBatchCount(), 1) << "the row of boxes is one batch";
  EXPECT_EQ(culledCounts.batchedInstances, 3) << "the row's three boxes in view";
  EXPECT_EQ(wholeCounts.batchedInstances, 17);
  EXPECT_LT(culledCounts.draws, wholeCounts.draws) << "the sphere behind the eye and the box to the left";
}
