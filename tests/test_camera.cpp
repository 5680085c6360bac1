// Cameras on the CPU: the orthographic projection and its JSON, the frame's aspect ratio fitted into any output, the
// reconstruction's mirror against the projection matrices, the jitter, and the scene's cameras posed by their nodes
// and chosen by name or index.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "base/Error.h"
#include "frame/FrameContext.h"
#include "scene/Animation.h"
#include "scene/Camera.h"

using namespace obscura;

namespace {

std::string refusal(const std::string& json) {
  try {
    Camera::fromJson(json, "cam.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The uv (y up) where the projection puts view-space point p.
glm::vec2 projectedUv(const glm::mat4& projection, const glm::vec3& p) {
  const glm::vec4 clip = projection * glm::vec4(p, 1.0f);
  return glm::vec2(clip) / clip.w * 0.5f + 0.5f;
}

Camera orthographic(float ymag) {
  Camera camera;
  camera.eye = {1.0f, 2.0f, 9.0f};
  camera.target = {0.0f, 0.5f, 0.0f};
  camera.orthographic = true;
  camera.ymag = ymag;
  camera.near = 0.0f;
  camera.far = 30.0f;
  return camera;
}

}  // namespace

TEST(Camera, OrthographicJsonRoundTripsAndIsChecked) {
  const Camera camera =
      Camera::fromJson(R"({"eye":[0,5,10],"target":[0,0,0],"type":"orthographic","ymag":3,"xmag":6,"near":0,)"
                       R"("far":40,"width":640,"height":360})",
                       "cam.json");
  EXPECT_TRUE(camera.orthographic);
  EXPECT_FLOAT_EQ(camera.ymag, 3.0f);
  EXPECT_FLOAT_EQ(camera.frameAspect, 2.0f);
  EXPECT_FLOAT_EQ(camera.near, 0.0f);
  const Camera again = Camera::fromJson(camera.toJson(), "again");
  EXPECT_TRUE(again.orthographic);
  EXPECT_FLOAT_EQ(again.ymag, 3.0f);
  EXPECT_FLOAT_EQ(again.frameAspect, 2.0f);
  EXPECT_EQ(again.toJson(), camera.toJson());
  const Camera perspective = Camera::fromJson(R"({"eye":[0,0,5],"target":[0,0,0],"aspect_ratio":1.5})", "p.json");
  EXPECT_FALSE(perspective.orthographic);
  EXPECT_FLOAT_EQ(Camera::fromJson(perspective.toJson(), "p").frameAspect, 1.5f);

  EXPECT_EQ(refusal(R"({"eye":[0,0,5],"target":[0,0,0],"type":"orthographic"})"),
            "cam.json: ymag: missing (an orthographic camera's half height)");
  EXPECT_EQ(refusal(R"({"eye":[0,0,5],"target":[0,0,0],"type":"fisheye"})"),
            "cam.json: type: expected \"perspective\" or \"orthographic\"");
  EXPECT_EQ(refusal(R"({"eye":[0,0,5],"target":[0,0,0],"ymag":2})"),
            "cam.json: ymag: only an orthographic camera has it");
  EXPECT_EQ(refusal(R"({"eye":[0,0,5],"target":[0,0,0],"type":"orthographic","ymag":0})"),
            "cam.json: ymag: must be in 0 .. 1e9 (the view's half height)");
  EXPECT_EQ(refusal(R"({"eye":[0,0,5],"target":[0,0,0],"near":0})"), "cam.json: near: must be > 0");
}

// A frame that names its aspect ratio stays whole in any output: wider outputs show more at the sides, narrower ones
// more above and below; the output's aspect is the projection's either way (nothing is stretched).
TEST(Camera, TheFramesAspectRatioFitsIntoAnyOutput) {
  Camera camera = orthographic(2.0f);
  camera.frameAspect = 1.5f;  // a frame 6 x 4 m
  EXPECT_EQ(camera.halfExtent(2.0f), glm::vec2(4.0f, 2.0f)) << "wider: the height kept";
  EXPECT_EQ(camera.halfExtent(1.5f), glm::vec2(3.0f, 2.0f));
  const glm::vec2 tall = camera.halfExtent(0.75f);
  EXPECT_FLOAT_EQ(tall.x, 3.0f) << "narrower: the width kept";
  EXPECT_FLOAT_EQ(tall.y, 4.0f);
  camera.frameAspect = 0.0f;
  EXPECT_EQ(camera.halfExtent(0.75f), glm::vec2(1.5f, 2.0f)) << "no frame: the height kept";

  Camera perspective;
  perspective.fovyDegrees = 60.0f;
  perspective.frameAspect = 2.0f;
  const float t = std::tan(glm::radians(30.0f));
  EXPECT_FLOAT_EQ(perspective.halfExtent(3.0f).y, t);
  EXPECT_FLOAT_EQ(perspective.halfExtent(1.0f).x, 2.0f * t);
  // The projection agrees: the frame's corner direction lands on the output's edge.
  const glm::mat4 p = perspective.projection(1.0f);
  EXPECT_NEAR(projectedUv(p, glm::vec3(2.0f * t, 0.0f, -1.0f)).x, 1.0f, 1e-5f);
  EXPECT_NEAR(projectedUv(perspective.projection(3.0f), glm::vec3(0.0f, t, -1.0f)).y, 1.0f, 1e-5f);
}

// The reconstruction's mirror inverts the projection: a view-space point projected by the camera's matrix lands at
// the uv from which viewPosition rebuilds it (its linear depth given), perspective and orthographic alike.
TEST(Camera, TheReconstructionInvertsTheProjection) {
  Camera perspective;
  perspective.near = 0.2f;
  perspective.far = 40.0f;
  for (const Camera& camera : {perspective, orthographic(2.5f)}) {
    const FrameCamera frame = FrameCamera::from(camera, 160, 90);
    EXPECT_EQ(frame.reconstruction.perspective, !camera.orthographic);
    for (const glm::vec3& p : {glm::vec3(0.3f, -0.4f, -3.0f), glm::vec3(-1.9f, 1.1f, -12.0f),
                               glm::vec3(2.0f, 0.7f, -25.0f)}) {
      const glm::vec2 uv = projectedUv(frame.projection, p);
      const float depth = (-p.z - camera.near) / (camera.far - camera.near);
      const glm::vec3 rebuilt = frame.reconstruction.viewPosition(uv, depth);
      EXPECT_NEAR(glm::length(rebuilt - p), 0.0f, 1e-4f) << (camera.orthographic ? "orthographic" : "perspective");
      const glm::vec2 back = frame.reconstruction.uvOf(p);
      EXPECT_NEAR(glm::length(back - uv), 0.0f, 1e-6f);
      // The eye's ray through p: from the eye, or straight down the axis from the eye's plane.
      const glm::vec3 direction = frame.reconstruction.eyeRayDirection(p);
      const glm::vec3 origin = frame.reconstruction.eyeRayOrigin(p);
      EXPECT_NEAR(glm::length(glm::cross(p - origin, direction)), 0.0f, 1e-5f);
      if (camera.orthographic) {
        EXPECT_EQ(direction, glm::vec3(0.0f, 0.0f, -1.0f));
      }
    }
  }
}

// In orthographic projection a metre is the same number of pixels at every depth; in perspective it shrinks with
// depth. The AO's projected radius (SaoKernel::diskRadiusPixels) and DoF's reference rely on it.
TEST(Camera, PixelsPerMetreAreTheSameAtEveryDepthOnlyInOrthographicProjection) {
  const FrameCamera ortho = FrameCamera::from(orthographic(2.0f), 200, 100);
  EXPECT_FLOAT_EQ(ortho.pixelsPerMetre(100, 1.0f), 25.0f);
  EXPECT_FLOAT_EQ(ortho.pixelsPerMetre(100, 17.0f), 25.0f);
  Camera camera;
  camera.fovyDegrees = 90.0f;
  const FrameCamera perspective = FrameCamera::from(camera, 200, 100);
  EXPECT_NEAR(perspective.pixelsPerMetre(100, 1.0f), 50.0f, 1e-4f);
  EXPECT_NEAR(perspective.pixelsPerMetre(100, 2.0f), 25.0f, 1e-4f);
}

// The jitter moves every point by the same sub-pixel offset, under either projection; the shear of the orthographic
// aperture reference moves a point by its depth times the shear.
TEST(Camera, TheJitterAndTheShearMoveThePointsAsSaid) {
  Camera perspective;
  for (const Camera& camera : {perspective, orthographic(2.0f)}) {
    const FrameCamera plain = FrameCamera::from(camera, 200, 100);
    const FrameCamera jittered = FrameCamera::from(camera, 200, 100, glm::vec2(0.25f, -0.5f));
    for (const glm::vec3& p : {glm::vec3(0.1f, 0.2f, -2.0f), glm::vec3(-0.5f, 0.3f, -20.0f)}) {
      const glm::vec2 moved = (projectedUv(jittered.projection, p) - projectedUv(plain.projection, p)) *
                              glm::vec2(200.0f, 100.0f);
      EXPECT_NEAR(moved.x, 0.25f, 1e-3f);
      EXPECT_NEAR(moved.y, -0.5f, 1e-3f);
    }
    EXPECT_EQ(jittered.unjitteredProjection, plain.projection);
  }
  const FrameCamera plain = FrameCamera::from(orthographic(2.0f), 200, 100);
  const FrameCamera sheared = FrameCamera::from(orthographic(2.0f), 200, 100, glm::vec2(-3.0f, 0.0f),
                                                glm::vec2(0.5f, 0.25f));
  for (float depth : {2.0f, 6.0f, 20.0f}) {
    const glm::vec3 p(0.3f, -0.2f, -depth);
    const glm::vec2 moved = (projectedUv(sheared.projection, p) - projectedUv(plain.projection, p)) *
                            glm::vec2(200.0f, 100.0f);
    EXPECT_NEAR(moved.x, -3.0f + 0.5f * depth, 1e-3f);
    EXPECT_NEAR(moved.y, 0.25f * depth, 1e-3f);
  }
}

// Switching projections keeps the view at the target: the orthographic half height is the perspective view's there.
TEST(Camera, SwitchingProjectionKeepsTheViewAtTheTarget) {
  Camera camera;
  camera.eye = {0.0f, 0.0f, 8.0f};
  camera.target = {0.0f, 0.0f, 0.0f};
  camera.fovyDegrees = 60.0f;
  const Camera ortho = camera.asOrthographic();
  EXPECT_TRUE(ortho.orthographic);
  EXPECT_NEAR(ortho.ymag, 8.0f * std::tan(glm::radians(30.0f)), 1e-5f);
  EXPECT_NEAR(ortho.halfHeightAt(123.0f, 1.0f), camera.halfHeightAt(8.0f, 1.0f), 1e-5f);
  Camera zoomed = ortho;
  zoomed.ymag *= 2.0f;
  const Camera back = zoomed.asPerspective();
  EXPECT_FALSE(back.orthographic);
  EXPECT_NEAR(glm::length(back.eye - back.target), 16.0f, 1e-4f) << "the perspective camera steps back";
  EXPECT_EQ(back.target, camera.target);
}

// A scene camera where its node's pose puts it: at the node's origin, looking down its -z, its projection the file's,
// a far plane fitted to the scene where the file gives none.
TEST(Camera, SceneCamerasArePlacedByTheirNodesPose) {
  Scene scene;
  scene.nodes.push_back(Node{});
  scene.nodes[0].name = "Dolly";
  AnimationSampler sampler;
  sampler.times = {0.0f, 2.0f};
  sampler.values = {0.0f, 1.0f, 10.0f, 4.0f, 1.0f, 10.0f};
  sampler.components = 3;
  scene.animations.push_back(Animation{"move", {sampler}, {{0, 0, AnimationPath::Translation}}});
  SceneCamera dolly;
  dolly.name = "lens";
  dolly.nodeName = "Dolly";
  dolly.yfov = glm::radians(40.0f);
  dolly.znear = 0.5f;
  dolly.node = 0;
  scene.cameras.push_back(dolly);
  SceneCamera plan;
  plan.orthographic = true;
  plan.xmag = 8.0f;
  plan.ymag = 4.0f;
  plan.znear = 0.0f;
  plan.zfar = 20.0f;
  plan.world = glm::translate(glm::mat4(1.0f), glm::vec3(0, 10, 0)) *
               glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1, 0, 0)) *
               glm::scale(glm::mat4(1.0f), glm::vec3(3.0f));  // its scale is ignored
  scene.cameras.push_back(plan);

  Bounds bounds;
  bounds.add({-2, 0, -2});
  bounds.add({2, 2, 2});
  const Camera atOne = sceneCameraAt(scene, 0, evaluatePose(scene, 1.0), bounds, 640, 480);
  EXPECT_NEAR(glm::length(atOne.eye - glm::vec3(2, 1, 10)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(glm::normalize(atOne.target - atOne.eye) - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
  EXPECT_NEAR(atOne.fovyDegrees, 40.0f, 1e-4f);
  EXPECT_FALSE(atOne.orthographic);
  // The planes hug the bounding sphere (radius 3, 1.05 times) within the file's: none given, so both are the sphere's.
  const float distance = glm::length(atOne.eye - bounds.center());
  EXPECT_NEAR(atOne.near, distance - 3.15f, 1e-4f);
  EXPECT_NEAR(atOne.far, distance + 3.15f, 1e-4f) << "an infinite far plane is fitted";
  EXPECT_NO_THROW(atOne.validate("scene camera"));

  const Camera top = sceneCameraAt(scene, 1, evaluatePose(scene, 0.0), bounds, 640, 480);
  EXPECT_TRUE(top.orthographic);
  EXPECT_FLOAT_EQ(top.ymag, 4.0f);
  EXPECT_NEAR(top.near, 9.0f - 3.15f, 1e-4f);
  EXPECT_NEAR(top.far, 9.0f + 3.15f, 1e-4f) << "within the file's 20";
  Scene closeUp;
  closeUp.cameras = {plan};
  closeUp.cameras[0].zfar = 10.0f;
  EXPECT_FLOAT_EQ(sceneCameraAt(closeUp, 0, ScenePose{}, bounds, 64, 64).far, 10.0f)
      << "the file's far plane, where it is nearer";
  EXPECT_FLOAT_EQ(top.frameAspect, 2.0f);
  EXPECT_NEAR(glm::length(glm::normalize(top.target - top.eye) - glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(glm::normalize(top.up) - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
  EXPECT_EQ(heightForWidth(plan, 1000), 500);
  EXPECT_EQ(heightForWidth(dolly, 1280), 720) << "no frame: 16:9";

  EXPECT_EQ(parseSceneCamera(scene, "Dolly"), 0);
  EXPECT_EQ(parseSceneCamera(scene, "lens"), 0);
  EXPECT_EQ(parseSceneCamera(scene, "1"), 1);
  try {
    parseSceneCamera(scene, "side");
    ADD_FAILURE() << "no camera named side";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "camera node 'side' is not one of the scene's cameras: 0 'Dolly', 1 'camera 1'");
  }
  EXPECT_THROW(parseSceneCamera(Scene(), "0"), InputError);
}
