// Motion vectors (effects/velocity/VelocityEffect.h): the packing on the GPU against its CPU mirror, a still scene
// gives zero, known camera and object motions give the analytic velocity within the packing's quantisation, and every
// way of drawing what moves (skinning paths, CPU deformation, every instance or only the moving ones) gives the same
// vectors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "encoding/VelocityPacking.h"
#include "gl/ShaderLibrary.h"
#include "scene/Animation.h"
#include "scene/Primitives.h"
#include "scene/SkinnedTube.h"

namespace obscura {
namespace {

namespace vp = VelocityPacking;

TEST(GpuVelocityPacking, TheShaderPacksLikeTheCpuMirrorAndDecodesWhatItPacks) {
  test::context();
  std::vector<glm::vec4> values = {{0, 0, 0, 0}, {1, -1, 0, 0}, {-1.5f, 2.0f, 0, 0}, {1e-6f, -1e-6f, 0, 0}};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uniform(-1.1f, 1.1f);
  while (values.size() < test::kPointSide * test::kPointSide) {
    const glm::vec2 v(uniform(rng), uniform(rng));
    // Skip values within a hair of a rounding boundary, where float evaluation order may legitimately differ.
    const glm::vec2 scaled = v * vp::kStepsPerUnit;
    if (std::abs(scaled.x - std::floor(scaled.x) - 0.5f) < 1e-2f) continue;
    if (std::abs(scaled.y - std::floor(scaled.y) - 0.5f) < 1e-2f) continue;
    values.emplace_back(v, 0.0f, 0.0f);
  }
  for (bool roundTrip : {false, true}) {
    // Packed, or packed, decoded and packed again: the decode must give back the same code.
    const std::string fragment = std::string(R"(
#include "lib/precision.glsl"
#include "lib/packing.glsl"
varying vec4 v_first;  // the velocity in xy (test::kTwoValuePointVertex)
void main() {
  vec4 texel = packVelocity(v_first.xy);
)") + (roundTrip ? "  texel = packVelocity(unpackVelocity(texel));\n" : "") + "  gl_FragColor = texel;\n}\n";
    const gl::Program program("pack velocities", ShaderLibrary::composeText(test::kTwoValuePointVertex, {}, {}),
                              ShaderLibrary::composeText(fragment, {}, {}));
    const std::vector<std::uint8_t> pixels = test::drawPoints(program, values);
    int mismatches = 0;
    for (size_t i = 0; i < values.size(); ++i) {
      const auto expected = vp::bytesFromVelocity(glm::vec2(values[i]));
      for (size_t c = 0; c < 4; ++c)
        if (pixels[i * 4 + c] != expected[c] && ++mismatches < 5)
          ADD_FAILURE() << "velocity (" << values[i].x << ", " << values[i].y << ") byte " << c << ": GPU "
                        << int(pixels[i * 4 + c]) << " CPU " << int(expected[c]) << (roundTrip ? " (round trip)" : "");
    }
    EXPECT_EQ(mismatches, 0);
  }
}

// The raw velocity target of the last frame (rows top to bottom), decoded.
std::vector<glm::vec2> readVelocity(Renderer& renderer) {
  const std::vector<std::uint8_t> bytes = renderer.retained("velocity").readRgba();
  std::vector<glm::vec2> out(bytes.size() / 4);
  for (size_t p = 0; p < out.size(); ++p) out[p] = vp::velocityFromBytes(&bytes[p * 4]);
  return out;
}

std::vector<glm::vec2> renderVelocity(Renderer& renderer, const Camera& camera, FrameOptions options) {
  options.retain = {"velocity"};
  test::render(renderer, camera, RenderSettings(), View::Final, options);
  return readVelocity(renderer);
}

// The analytic motion of the world point seen at pixel (x, y) (rows from the top) through `now`, on the plane
// z = planeZ, which moved by `worldMotion` since the previous frame seen through `before`.
struct Projection {
  glm::mat4 viewProjection;
  glm::mat4 inverse;
  static Projection of(const Camera& camera) {
    const glm::mat4 vp = camera.projection() * camera.view();
    return {vp, glm::inverse(vp)};
  }
};

std::optional<glm::vec3> pointOnPlane(const Projection& now, int x, int y, int width, int height, float planeZ) {
  const glm::vec2 ndc((static_cast<float>(x) + 0.5f) / static_cast<float>(width) * 2.0f - 1.0f,
                      1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(height) * 2.0f);
  const glm::vec4 nearPoint = now.inverse * glm::vec4(ndc, -1.0f, 1.0f);
  const glm::vec4 farPoint = now.inverse * glm::vec4(ndc, 1.0f, 1.0f);
  const glm::vec3 a = glm::vec3(nearPoint) / nearPoint.w, b = glm::vec3(farPoint) / farPoint.w;
  if (std::abs(b.z - a.z) < 1e-9f) return std::nullopt;
  const float t = (planeZ - a.z) / (b.z - a.z);
  if (t <= 0.0f) return std::nullopt;
  return a + t * (b - a);
}

glm::vec2 uvOf(const Projection& projection, const glm::vec3& p) {
  const glm::vec4 clip = projection.viewProjection * glm::vec4(p, 1.0f);
  return glm::vec2(clip) / clip.w * 0.5f;
}

// A wall (z = 0) and, in front of it, a box (front face at z = 1) on a node that a translation animation moves
// along +x at 1 m/s.
Scene wallAndSlidingBox() {
  Scene scene;
  scene.meshes.push_back(test::makeRectangle({-30, -30, 0}, {60, 0, 0}, {0, 60, 0}));
  scene.meshes.push_back(makeBox({-0.5f, -0.5f, 0.5f}, {0.5f, 0.5f, 1.0f}));
  scene.instances.push_back(Instance{0, glm::mat4(1.0f), -1, -1});
  test::addSlidingInstance(scene, 1, {-5, 0, 0}, {5, 0, 0}, 10.0f);
  return scene;
}

TEST(Velocity, AStillSceneAndAStillCameraGiveExactlyZero) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(wallAndSlidingBox());
  const Camera camera = test::makeCamera({0.3f, 0.2f, 6.0f}, {0.0f, 0.0f, 0.0f}, 96, 64);
  FrameOptions still;
  still.time = 5.0;  // the box is moving at 5 s, but the previous pose is the same instant
  for (int frame = 0; frame < 2; ++frame)
    for (const glm::vec2& v : renderVelocity(renderer, camera, still)) ASSERT_EQ(v, glm::vec2(0.0f));
}

// The worst difference between the velocity of a frame seen through `now` and the analytic motion of the wall's points
// (z = 0) between `before` and `now`, in uv units.
float worstCameraMotionError(const std::vector<glm::vec2>& velocity, const Camera& before, const Camera& now) {
  const int width = now.width, height = now.height;
  const Projection p = Projection::of(now), q = Projection::of(before);
  float worst = 0.0f;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto point = pointOnPlane(p, x, y, width, height, 0.0f);
      if (!point) return 1e30f;
      const glm::vec2 expected = uvOf(p, *point) - uvOf(q, *point);
      worst = std::max(worst, glm::length(velocity[static_cast<size_t>(y * width + x)] - expected));
    }
  return worst;
}

TEST(Velocity, ACameraPanGivesTheAnalyticMotion) {
  Renderer renderer = test::makeRenderer();
  Scene scene = wallAndSlidingBox();
  scene.instances.pop_back();  // the wall alone
  renderer.setScene(scene);
  const int width = 120, height = 80;
  Camera before = test::makeCamera({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, width, height);
  Camera now = test::makeCamera({0.25f, -0.1f, 5.2f}, {0.3f, 0.05f, 0.0f}, width, height);  // moves and turns
  renderVelocity(renderer, before, {});
  const std::vector<glm::vec2> velocity = renderVelocity(renderer, now, {});
  const Projection p = Projection::of(now), q = Projection::of(before);
  float worst = 0.0f;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto point = pointOnPlane(p, x, y, width, height, 0.0f);
      ASSERT_TRUE(point);
      const glm::vec2 expected = uvOf(p, *point) - uvOf(q, *point);
      worst = std::max(worst, glm::length(velocity[static_cast<size_t>(y * width + x)] - expected));
    }
  // The packing's step (1/32767 of the screen) and the 16-bit depth the motion is reconstructed from.
  EXPECT_LT(worst, 3.0f / vp::kStepsPerUnit) << "worst error, in uv units";
}

// An orthographic camera that pans, turns and zooms (ymag): every point of the wall moves as the two projections say.
TEST(Velocity, AnOrthographicCameraPanGivesTheAnalyticMotion) {
  Renderer renderer = test::makeRenderer();
  Scene scene = wallAndSlidingBox();
  scene.instances.pop_back();  // the wall alone
  renderer.setScene(scene);
  Camera before = test::makeCamera({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, 120, 80, 0.0f, 20.0f);
  before.orthographic = true;
  before.ymag = 2.0f;
  Camera now = before;
  now.eye = {0.25f, -0.1f, 5.2f};
  now.target = {0.3f, 0.05f, 0.0f};
  now.ymag = 2.1f;
  renderVelocity(renderer, before, {});
  const float worst = worstCameraMotionError(renderVelocity(renderer, now, {}), before, now);
  EXPECT_LT(worst, 3.0f / vp::kStepsPerUnit) << "worst error, in uv units";
}

// A camera of the scene on an animated node: one frame at T with the previous pose at T - 0.1 (the CLI's single
// frame: no previous frame, a previous time) sees the camera's motion between the two, for a perspective and an
// orthographic camera; with the previous time equal to T it sees none.
TEST(Velocity, AnAnimatedSceneCameraGivesTheAnalyticMotion) {
  for (bool orthographic : {false, true}) {
    Scene scene = wallAndSlidingBox();
    scene.instances.pop_back();  // the wall alone
    // The camera's node slides from (-1, 0.2, 6) to (1, 0.2, 6) over 10 s, looking down -z.
    scene.nodes.push_back(Node{});
    const int node = static_cast<int>(scene.nodes.size()) - 1;
    AnimationSampler sampler;
    sampler.times = {0.0f, 10.0f};
    sampler.values = {-1.0f, 0.2f, 6.0f, 1.0f, 0.2f, 6.0f};
    sampler.components = 3;
    scene.animations.front().channels.push_back(
        {static_cast<int>(scene.animations.front().samplers.size()), node, AnimationPath::Translation});
    scene.animations.front().samplers.push_back(sampler);
    SceneCamera sceneCamera;
    sceneCamera.orthographic = orthographic;
    sceneCamera.yfov = 0.8f;
    sceneCamera.ymag = 2.5f;
    sceneCamera.xmag = 2.5f * 1.5f;
    sceneCamera.znear = 0.5f;
    sceneCamera.zfar = 30.0f;
    sceneCamera.node = node;
    scene.cameras.push_back(sceneCamera);
    Renderer renderer = test::makeRenderer();
    renderer.setScene(scene);

    FrameOptions options;
    options.sceneCamera = 0;
    options.time = 5.0;
    options.previousTime = 4.9;  // 0.02 m to the left
    // The cameras the node puts there, made by hand: at x = 0 and -0.02, looking down -z.
    auto cameraAt = [&](float x) {
      Camera c = test::makeCamera({x, 0.2f, 6.0f}, {x, 0.2f, 0.0f}, 120, 80, 0.5f, 30.0f,
                                  glm::degrees(sceneCamera.yfov));
      c.orthographic = orthographic;
      c.ymag = sceneCamera.ymag;
      c.frameAspect = sceneCamera.frameAspect();
      return c;
    };
    const Camera placeholder = test::makeCamera({0, 0, 1}, {0, 0, 0}, 120, 80);  // only its size counts
    const std::vector<glm::vec2> velocity = renderVelocity(renderer, placeholder, options);
    const float worst = worstCameraMotionError(velocity, cameraAt(-0.02f), cameraAt(0.0f));
    EXPECT_LT(worst, 3.0f / vp::kStepsPerUnit) << (orthographic ? "orthographic" : "perspective");
    // The motion is there to see: 0.02 m of a view about 5 m wide is 1/250 of the screen.
    EXPECT_GT(std::abs(velocity[80 * 60 + 40].x), 0.002f);
    const FrameCamera frame = renderer.lastFrame().camera;
    EXPECT_NEAR(glm::inverse(frame.view)[3].x, 0.0f, 1e-5f) << "the camera is where the node is at 5 s";

    options.previousTime = 5.0;
    renderer.setScene(scene);  // no history
    for (const glm::vec2& v : renderVelocity(renderer, placeholder, options)) ASSERT_EQ(v, glm::vec2(0.0f));
  }
}

TEST(Velocity, AMovingObjectGivesTheAnalyticMotionAndItsBackgroundNone) {
  for (bool everything : {false, true}) {
    RendererOptions options;
    options.velocityDrawsEverything = everything;
    Renderer renderer = test::makeRenderer(options);
    renderer.setScene(wallAndSlidingBox());
    const int width = 120, height = 80;
    const Camera camera = test::makeCamera({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, width, height);
    FrameOptions frame;
    frame.time = 5.0;          // the box at x = 0
    frame.previousTime = 4.8;  // 0.2 m to the left before
    const std::vector<glm::vec2> velocity = renderVelocity(renderer, camera, frame);
    const Projection p = Projection::of(camera);
    int onBox = 0, onWall = 0;
    float worstBox = 0.0f, worstWall = 0.0f;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const glm::vec2 v = velocity[static_cast<size_t>(y * width + x)];
        const auto front = pointOnPlane(p, x, y, width, height, 1.0f);
        // Inside the front face with a margin (edges rasterise either way), or clear of where the box is or was.
        if (std::abs(front->x) < 0.45f && std::abs(front->y) < 0.45f) {
          const glm::vec2 expected = uvOf(p, *front) - uvOf(p, *front - glm::vec3(0.2f, 0.0f, 0.0f));
          worstBox = std::max(worstBox, glm::length(v - expected));
          ++onBox;
        } else if (std::abs(front->x) > 1.0f || std::abs(front->y) > 0.7f) {
          worstWall = std::max(worstWall, glm::length(v));
          ++onWall;
        }
      }
    ASSERT_GT(onBox, 200);
    ASSERT_GT(onWall, 2000);
    EXPECT_LT(worstBox, 2.0f / vp::kStepsPerUnit) << (everything ? "drawing everything" : "drawing what moves");
    EXPECT_EQ(worstWall, 0.0f) << "the wall does not move";
  }
}

// A tube on a chain of three joints, bending and sliding (scene/SkinnedTube.h).
Scene bendingChain() {
  Scene scene;
  SkinnedTubeShape shape;
  shape.height = 3.0f;
  shape.rings = 24;
  addSkinnedTube(scene, shape, glm::vec3(0.0f));
  return scene;
}

TEST(Velocity, EverySkinningPathGivesTheSameMotion) {
  const Camera camera = test::makeCamera({0.5f, 1.5f, 7.0f}, {0.0f, 1.5f, 0.0f}, 96, 96);
  FrameOptions frame;
  frame.time = 0.6;
  frame.previousTime = 0.5;
  std::vector<std::vector<glm::vec2>> results;
  for (SkinningPath path : {SkinningPath::Cpu, SkinningPath::Uniforms, SkinningPath::Texture}) {
    RendererOptions options;
    options.skinning = path;
    Renderer renderer = test::makeRenderer(options);
    renderer.setScene(bendingChain());
    results.push_back(renderVelocity(renderer, camera, frame));
  }
  int moving = 0;
  for (const glm::vec2& v : results[0]) moving += glm::length(v) > 1e-3f;
  EXPECT_GT(moving, 300) << "the chain moves";
  for (size_t r = 1; r < results.size(); ++r) {
    int differing = 0;
    for (size_t p = 0; p < results[0].size(); ++p) differing += glm::length(results[r][p] - results[0][p]) > 3e-4f;
    // Silhouette pixels may rasterise differently through another float order.
    EXPECT_LT(differing, moving / 50) << "path " << r << " against the CPU's";
  }
}

}  // namespace
}  // namespace obscura
