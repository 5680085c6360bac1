// Cameras through the frame: an orthographic camera draws equal objects at equal sizes whatever their depth, the
// scene's cameras draw what the camera they stand for draws, and changing cameras is a cut.
#include <gtest/gtest.h>

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "scene/Animation.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

// The columns and rows the mask view covers in the left and the right half of the image: x0, x1, y0, y1 of each.
struct Extent {
  int x0 = 1 << 30, x1 = -1, y0 = 1 << 30, y1 = -1;
  int width() const { return x1 - x0 + 1; }
  int height() const { return y1 - y0 + 1; }
};

std::pair<Extent, Extent> halves(const test::RenderedImage& mask) {
  Extent left, right;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) {
      if (mask.channel(x, y, 0) < 128) continue;  // the mask view: white where something was drawn
      Extent& e = x < mask.width / 2 ? left : right;
      e.x0 = std::min(e.x0, x);
      e.x1 = std::max(e.x1, x);
      e.y0 = std::min(e.y0, y);
      e.y1 = std::max(e.y1, y);
    }
  return {left, right};
}

}  // namespace

// Two equal cubes, one 8 m behind the other: through an orthographic camera they cover the same number of pixels
// across and down; through a perspective camera the far one is smaller (so the test can tell).
TEST(Cameras, EqualCubesAtDifferentDepthsProjectToTheSameSizeOrthographically) {
  Scene scene = test::sceneOf({makeBox({-2.5f, -0.5f, -0.5f}, {-1.5f, 0.5f, 0.5f}),
                               makeBox({1.5f, -0.5f, -8.5f}, {2.5f, 0.5f, -7.5f})});
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  Camera camera = test::makeCamera({0.0f, 0.0f, 10.0f}, {0.0f, 0.0f, 0.0f}, 200, 120, 1.0f, 30.0f);
  RenderSettings settings;
  const auto [nearPerspective, farPerspective] = halves(test::render(renderer, camera, settings, View::Mask));
  std::printf("perspective: near %d..%d x %d..%d, far %d..%d x %d..%d\n", nearPerspective.x0, nearPerspective.x1,
              nearPerspective.y0, nearPerspective.y1, farPerspective.x0, farPerspective.x1, farPerspective.y0,
              farPerspective.y1);
  EXPECT_GT(nearPerspective.width(), farPerspective.width() + 5) << "perspective: the far cube is smaller";

  camera.orthographic = true;
  camera.ymag = 3.0f;  // 6 m over 120 rows: 20 pixels a metre
  const auto [nearCube, farCube] = halves(test::render(renderer, camera, settings, View::Mask));
  EXPECT_EQ(nearCube.width(), farCube.width());
  EXPECT_EQ(nearCube.height(), farCube.height());
  EXPECT_NEAR(nearCube.width(), 20, 1) << "1 m at 20 pixels a metre";
  EXPECT_EQ(nearCube.y0, farCube.y0) << "and at the same height";
}

// A scene camera draws exactly what its posed camera (sceneCameraAt), handed over as a free camera, draws; two
// cameras draw different images; and changing cameras, or the projection, drops the history.
TEST(Cameras, ASceneCameraDrawsWhatItsPosedCameraDraws) {
  Scene scene = test::sceneOf({makeBox({-1.0f, 0.0f, -1.0f}, {1.0f, 1.5f, 1.0f}),
                               test::makeRectangle({-6, 0, 6}, {12, 0, 0}, {0, 0, -12})});
  scene.nodes.push_back(Node{});  // the first camera's node, turning about y over 4 s
  scene.nodes[0].translation = {0.0f, 2.0f, 7.0f};
  AnimationSampler turn;
  turn.times = {0.0f, 4.0f};
  const glm::quat a = glm::angleAxis(-0.3f, glm::vec3(0, 1, 0)), b = glm::angleAxis(0.3f, glm::vec3(0, 1, 0));
  turn.values = {a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w};
  turn.components = 4;
  scene.animations.push_back(Animation{"turn", {turn}, {{0, 0, AnimationPath::Rotation}}});
  SceneCamera front;
  front.yfov = 0.7f;
  front.znear = 0.5f;
  front.node = 0;
  scene.cameras.push_back(front);
  SceneCamera plan;
  plan.orthographic = true;
  plan.xmag = plan.ymag = 5.0f;
  plan.znear = 0.0f;
  plan.zfar = 30.0f;
  plan.world = glm::translate(glm::mat4(1.0f), glm::vec3(0, 12, 0)) *
               glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1, 0, 0));
  scene.cameras.push_back(plan);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  const Camera size = test::makeCamera({0, 0, 1}, {0, 0, 0}, 96, 64);
  RenderSettings settings;
  FrameOptions options;
  options.time = 1.0;
  std::vector<std::vector<std::uint8_t>> images;
  for (int index : {0, 1}) {
    options.sceneCamera = index;
    const test::RenderedImage viaScene = test::render(renderer, size, settings, View::Final, options);
    const Camera posed = renderer.frameCamera(size, 96, 64, options);
    EXPECT_EQ(posed.orthographic, index == 1);
    FrameOptions free = options;
    free.sceneCamera = -1;
    Renderer other = test::makeRenderer();
    other.setScene(scene);
    const test::RenderedImage viaCamera = test::render(other, posed, settings, View::Final, free);
    EXPECT_EQ(viaScene.rgba, viaCamera.rgba) << "camera " << index;
    images.push_back(viaScene.rgba);
  }
  EXPECT_NE(images[0], images[1]);

  // Cuts: another scene camera, the free camera, its projection.
  const int drops = renderer.historyDrops();
  options.sceneCamera = 1;
  test::render(renderer, size, settings, View::Final, options);
  EXPECT_EQ(renderer.historyDrops(), drops) << "the same camera: no cut";
  options.sceneCamera = 0;
  test::render(renderer, size, settings, View::Final, options);
  EXPECT_EQ(renderer.historyDrops(), drops + 1);
  options.sceneCamera = -1;
  test::render(renderer, size, settings, View::Final, options);
  EXPECT_EQ(renderer.historyDrops(), drops + 2);
  Camera ortho = size;
  ortho.orthographic = true;
  test::render(renderer, ortho, settings, View::Final, options);
  EXPECT_EQ(renderer.historyDrops(), drops + 3);
  options.sceneCamera = 5;
  EXPECT_THROW(test::render(renderer, size, settings, View::Final, options), InputError);
}
