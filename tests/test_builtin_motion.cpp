// The built-in scene's motion on the GPU (scene/BuiltinScene.h): at time 0 the frame is the rest pose's, bit for
// bit; later the pendulum and the limb are drawn where the CPU mirror (posedScene) puts them, by the default
// skinning path and under GLES 2's minimum vertex limits; and they alone have motion vectors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <utility>

#include "TestSupport.h"
#include "encoding/VelocityPacking.h"
#include "scene/Animation.h"
#include "scene/BuiltinScene.h"

using namespace obscura;

namespace {

// The fraction of pixels whose first three channels differ by more than `tolerance`.
double differingFraction(const test::RenderedImage& a, const test::RenderedImage& b, int tolerance) {
  size_t differing = 0;
  for (size_t p = 0; p < a.rgba.size(); p += 4) {
    for (size_t c = 0; c < 3; ++c) {
      if (std::abs(int(a.rgba[p + c]) - int(b.rgba[p + c])) > tolerance) {
        ++differing;
        break;
      }
    }
  }
  return static_cast<double>(differing) / static_cast<double>(a.rgba.size() / 4);
}

FrameOptions at(double time, AnimationChoice animation = AnimationChoice::one(0)) {
  FrameOptions frame;
  frame.time = time;
  frame.previousTime = time;  // no object motion between frames: each frame is judged on its own
  frame.animation = animation;
  return frame;
}

}  // namespace

TEST(BuiltinMotion, AtTimeZeroTheFrameIsTheRestPose) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::withMotion()));
  const Camera camera = builtinSceneCamera(320, 180);
  for (const View& view : {View::Final, View::Ao}) {
    const test::RenderedImage playing = test::render(renderer, camera, RenderSettings(), view, at(0.0));
    const test::RenderedImage rest =
        test::render(renderer, camera, RenderSettings(), view, at(0.0, AnimationChoice::none()));
    EXPECT_EQ(playing.rgba, rest.rgba) << view.name;
  }
}

TEST(BuiltinMotion, ThePendulumAndTheLimbAreDrawnWhereTheCpuMirrorPutsThem) {
  const Scene scene = makeBuiltinScene(BuiltinSceneOptions::withMotion());
  const Camera camera = builtinSceneCamera(320, 180);
  RendererOptions gles2Minimum;
  gles2Minimum.simulateVertexLimits = VertexLimits::gles2Minimum();
  for (const auto& [name, options] : {std::pair<std::string, RendererOptions>("default", RendererOptions{}),
                                      std::pair<std::string, RendererOptions>("GLES 2 minimum", gles2Minimum)}) {
    Renderer gpu = test::makeRenderer(options);
    gpu.setScene(scene);
    for (double time : {1.0, 2.6}) {
      Renderer cpu = test::makeRenderer();
      cpu.setScene(posedScene(scene, evaluatePose(scene, time, PoseOptions{AnimationChoice::one(0), true})));
      const std::string what = name + " at " + std::to_string(static_cast<int>(time * 1000)) + " ms";
      for (const View& view : {View::Depth, View::Normals}) {
        const test::RenderedImage posed = test::render(gpu, camera, RenderSettings(), view, at(time));
        const test::RenderedImage baked = test::render(cpu, camera, RenderSettings(), view);
        // The same triangles through a different float order: a few edge pixels and one step may differ.
        EXPECT_LT(differingFraction(posed, baked, 2), 0.002) << what << ", view " << view.name;
      }
      // ... and they moved: the rest pose differs (the two objects cover a few per cent of the frame).
      const test::RenderedImage rest =
          test::render(gpu, camera, RenderSettings(), View::Depth, at(time, AnimationChoice::none()));
      const test::RenderedImage posed = test::render(gpu, camera, RenderSettings(), View::Depth, at(time));
      const double moved = differingFraction(rest, posed, 2);
      RecordProperty("moved_" + std::to_string(static_cast<int>(time * 10)), std::to_string(moved));
      EXPECT_GT(moved, 0.004) << what << ": not the rest pose";
    }
  }
}

// Mid-swing (the pendulum and both limb joints at their fastest at 2 s), with a still camera: motion vectors where the
// pendulum and the limb are, none on the room.
TEST(BuiltinMotion, OnlyThePendulumAndTheLimbHaveMotionVectors) {
  const Camera camera = builtinSceneCamera(320, 180);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::withMotion()));
  FrameOptions frame = at(2.0);
  frame.previousTime = 1.95;
  const test::RenderedImage depth = test::render(renderer, camera, RenderSettings(), View::Depth, frame);
  frame.retain = {"velocity"};
  test::render(renderer, camera, RenderSettings(), View::Final, frame);
  const std::vector<std::uint8_t> velocity = renderer.retained("velocity").readRgba();  // rows top to bottom
  // Where the moving objects are: the depth differs from the still room's.
  Renderer room = test::makeRenderer();
  room.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const test::RenderedImage roomDepth = test::render(room, camera, RenderSettings(), View::Depth);
  ASSERT_EQ(velocity.size(), depth.rgba.size());
  auto objectNear = [&](int x, int y) {  // within a pixel: edges rasterise either way
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int u = std::clamp(x + dx, 0, camera.width - 1), v = std::clamp(y + dy, 0, camera.height - 1);
        const size_t p = (static_cast<size_t>(v) * static_cast<size_t>(camera.width) + static_cast<size_t>(u)) * 4;
        if (depth.rgba[p] != roomDepth.rgba[p] || depth.rgba[p + 1] != roomDepth.rgba[p + 1]) return true;
      }
    return false;
  };
  int moving = 0, onRoom = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const size_t p = (static_cast<size_t>(y) * static_cast<size_t>(camera.width) + static_cast<size_t>(x)) * 4;
      if (VelocityPacking::velocityFromBytes(&velocity[p]) == glm::vec2(0.0f)) continue;
      ++moving;
      if (!objectNear(x, y)) ++onRoom;
    }
  RecordProperty("moving_pixels", std::to_string(moving));
  EXPECT_GT(moving, camera.width * camera.height / 250) << "pixels with motion";
  EXPECT_EQ(onRoom, 0) << "pixels of the room with motion";
}
