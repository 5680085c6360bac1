// The viewers' shared state text (the web page's URL, obscura-view --state) and camera controls. No GL needed.
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "base/Error.h"
#include "platform/CameraControls.h"
#include "platform/ViewerState.h"
#include "scene/BuiltinScene.h"

using namespace obscura;

namespace {
bool sameCamera(const Camera& a, const Camera& b) {
  return a.eye == b.eye && a.target == b.target && a.up == b.up && a.fovyDegrees == b.fovyDegrees &&
         a.near == b.near && a.far == b.far;
}
}  // namespace

TEST(ViewerState, RoundTripsThroughQueryTextExactly) {
  ViewerState changed;
  changed.camera = builtinSceneCamera();
  changed.setViewMode("split");
  changed.view.compare = "fxaa";
  changed.settings.set("radius", "2.5");
  changed.settings.set("preset", "high");
  changed.settings.set("blur", "off");
  changed.camera.eye = glm::vec3(1.0f / 3.0f, 2.7182817f, -6.1f);
  changed.camera.fovyDegrees = 47.5f;
  changed.camera.near = 30.0f;
  changed.camera.far = 2.5e7f;  // exponent form with a '+', which must survive URL decoding
  for (const ViewerState& original : {ViewerState{}, changed}) {
    ViewerState copy;
    EXPECT_TRUE(copy.applyQuery(original.toQuery()));
    EXPECT_EQ(copy.toQuery(), original.toQuery());
    EXPECT_TRUE(sameCamera(copy.camera, original.camera)) << copy.toQuery();
    EXPECT_EQ(copy.viewMode(), original.viewMode());
    EXPECT_EQ(copy.view.compare, original.view.compare);
    for (const ParameterInfo& p : RenderSettings::parameters())
      EXPECT_EQ(copy.settings.get(p.name), original.settings.get(p.name)) << p.name;
  }
  // Written under the full names, the frame's preset first; read back under the old names too (aliases).
  const std::string text = changed.toQuery();
  EXPECT_EQ(text.rfind("view=split&compare=fxaa&preset=high&ao.radius=2.5&", 0), 0u) << text;
  EXPECT_EQ(text.find("bias="), std::string::npos) << "defaults are left out: " << text;
  ViewerState old;
  old.applyQuery("view=split&compare=fxaa&preset=high&radius=2.5&blur=off");
  EXPECT_EQ(old.toQuery().substr(0, text.find("&eye=")), text.substr(0, text.find("&eye=")));
}

// A preset whose values were then changed still travels with the text: it selects the fitted estimator parameters
// ("auto"), so dropping it would reopen the link with medium's bias, intensity and contrast.
TEST(ViewerState, ATweakedPresetRoundTripsWithItsFittedEstimator) {
  for (const char* preset : {"low", "high", "ultra"}) {
    ViewerState original;
    original.settings.set("preset", preset);
    original.settings.set("samples", "9");
    original.settings.set("blur-radius", "2");
    original.settings.set("radius", "0.5");
    ASSERT_EQ(original.settings.get("preset"), "") << "the values no longer match the preset";
    ViewerState copy;
    copy.applyQuery(original.toQuery());
    EXPECT_EQ(copy.settings.ao().preset, original.settings.ao().preset) << original.toQuery();
    for (const ParameterInfo& p : RenderSettings::parameters())
      EXPECT_EQ(copy.settings.get(p.name), original.settings.get(p.name)) << p.name << " in " << original.toQuery();
    const EstimatorParameters a = original.settings.ao().estimatorAt(), b = copy.settings.ao().estimatorAt();
    EXPECT_EQ(a.intensity, b.intensity) << original.toQuery();
    EXPECT_EQ(a.bias, b.bias);
    EXPECT_EQ(a.contrast, b.contrast);
    EXPECT_NE(a.intensity, AoSettings{}.estimatorAt().intensity) << "the test needs a preset whose fit differs";
  }
  // A value that differs from the defaults but equals the preset's own is left out.
  ViewerState low;
  low.settings.set("preset", "low");
  EXPECT_EQ(low.toQuery().find("samples="), std::string::npos) << low.toQuery();
  EXPECT_NE(low.toQuery().find("preset=low"), std::string::npos) << low.toQuery();
}

TEST(ViewerState, AcceptsKeysInAnyOrderAndEncodedText) {
  ViewerState state;
  // "turns" before "samples" in the text: parameters apply in table order, so 5 is checked against 32 samples.
  EXPECT_FALSE(state.applyQuery("?turns=5&samples=32&view=ao-raw"));
  EXPECT_EQ(state.settings.ao().samples, 32);
  EXPECT_EQ(state.settings.ao().spiralTurns, 5);
  EXPECT_EQ(state.viewMode(), "ao-raw");
  EXPECT_TRUE(state.applyQuery("eye=1%2C2%2C3&target=0,0,0&view=split"));
  EXPECT_EQ(state.camera.eye, glm::vec3(1, 2, 3));
  EXPECT_EQ(state.view, View::Split);
  // Full names and old names mix; every effect's parameters are keys.
  EXPECT_FALSE(state.applyQuery("ao.turns=3&samples=8&tonemap.operator=aces&fxaa=off&view=scene-color"));
  EXPECT_EQ(state.settings.ao().samples, 8);
  EXPECT_EQ(state.settings.get("tonemap.operator"), "aces");
  EXPECT_EQ(state.settings.get("fxaa"), "off");
  EXPECT_EQ(state.viewMode(), "scene-color");
}

TEST(ViewerState, RefusesBadTextAndKeepsTheState) {
  const std::pair<const char*, const char*> cases[] = {
      {"colour=red", "unknown key 'colour'"},
      {"radius=0", "state: radius: 0 is out of range"},
      {"view=wireframe", "state: view: expected final, split, normals, normals-from-depth, depth, mask, "},
      {"eye=1,2", "eye: expected x,y,z"},
      {"eye=1,2,x", "eye: expected a number"},
      {"eye=0,0,0&target=0,0,0", "target: must differ from eye"},
      {"near=5&far=1", "far: must be greater than near"},
      {"radius=2&radius=3", "radius is given twice"},
      {"radius=2&ao.radius=3", "ao.radius is given twice (also as radius)"},
      {"tonemap.operator=filmic", "state: tonemap.operator: expected linear, reinhard, aces, neutral or agx"},
      {"radius", "'radius' has no value"},
      {"view=split&compare=ao.radius", "state: compare: expected a switch, one of ao, "},
      {"compare=preset", "state: compare: expected a switch"},
  };
  ViewerState state;
  const std::string before = state.toQuery();
  for (const auto& [text, expect] : cases) {
    try {
      state.applyQuery(text);
      ADD_FAILURE() << text << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << text << ": " << e.what();
    }
    EXPECT_EQ(state.toQuery(), before) << text;
  }
}

// The cameras in the state text: an orthographic free camera (projection=orthographic&ymag=), a scene camera looked
// through (camera=, by its name where that finds it again, else its index), each coming back exactly; a text that
// describes the free camera without them is a perspective free camera; a camera the scene lacks is refused.
TEST(ViewerState, CamerasRoundTripThroughQueryText) {
  ViewerState state;
  state.camera = builtinSceneCamera().asOrthographic();
  state.camera.ymag = 3.25f;
  SceneCamera front, unnamed;
  front.nodeName = "Front";
  state.sceneCameras = {front, unnamed};
  EXPECT_EQ(state.cameraChoice(), "free");
  const std::string orthographic = state.toQuery();
  EXPECT_NE(orthographic.find("&projection=orthographic&ymag=3.25"), std::string::npos) << orthographic;
  EXPECT_EQ(orthographic.find("camera="), std::string::npos) << "the free camera is the default";
  for (const char* choice : {"Front", "1"}) {
    ViewerState through = state;
    through.setCameraChoice(choice);
    const std::string text = through.toQuery();
    EXPECT_NE(text.find(std::string("&camera=") + choice), std::string::npos) << text;
    ViewerState copy;
    copy.sceneCameras = state.sceneCameras;
    EXPECT_TRUE(copy.applyQuery(text));
    EXPECT_EQ(copy.toQuery(), text);
    EXPECT_EQ(copy.sceneCamera, through.sceneCamera);
    EXPECT_TRUE(copy.camera.orthographic);
    EXPECT_EQ(copy.camera.ymag, 3.25f);
  }
  // Back to a perspective free camera by text that names neither: as toQuery writes it.
  ViewerState perspective = state;
  perspective.setCameraChoice("Front");
  perspective.applyQuery(ViewerState{}.toQuery());
  EXPECT_FALSE(perspective.camera.orthographic);
  EXPECT_EQ(perspective.sceneCamera, -1);
  // camera= alone chooses the camera and leaves the free one as it was.
  ViewerState chosen = state;
  chosen.applyQuery("camera=Front");
  EXPECT_EQ(chosen.sceneCamera, 0);
  EXPECT_TRUE(chosen.camera.orthographic);

  const std::pair<const char*, const char*> refused[] = {
      {"camera=Top", "state: camera 'Top' is not one of the scene's cameras: 0 'Front', 1 'camera 1'"},
      {"projection=fisheye", "state: projection: expected perspective or orthographic, got 'fisheye'"},
      {"projection=orthographic&ymag=0", "state: ymag: must be in 0 .. 1e9"},
  };
  for (const auto& [text, expect] : refused) {
    ViewerState copy = state;
    try {
      copy.applyQuery(text);
      ADD_FAILURE() << text << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << text << ": " << e.what();
    }
    EXPECT_EQ(copy.toQuery(), state.toQuery()) << text;
  }
  ViewerState none;
  EXPECT_THROW(none.applyQuery("camera=0"), InputError) << "a scene without cameras of its own";
}

TEST(CameraControls, OrbitTurnsAboutTheTargetLikeGrabbingTheScene) {
  const Camera start = builtinSceneCamera(320, 180);
  const float distance = glm::length(start.eye - start.target);
  const glm::vec3 right = glm::normalize(glm::cross(start.target - start.eye, start.up));

  Camera camera = start;
  orbitCamera(camera, 10.0f, 0.0f, 180);
  EXPECT_NEAR(glm::length(camera.eye - camera.target), distance, 1e-4f * distance);
  EXPECT_LT(glm::dot(camera.eye - start.eye, right), 0.0f) << "dragging right carries the eye left";
  EXPECT_NEAR(camera.eye.y, start.eye.y, 1e-4f) << "a horizontal drag turns about the up axis";

  camera = start;
  orbitCamera(camera, 0.0f, 10.0f, 180);
  EXPECT_GT(camera.eye.y, start.eye.y) << "dragging down lifts the eye";
  EXPECT_NEAR(glm::length(camera.eye - camera.target), distance, 1e-4f * distance);

  // A drag across the full height turns half a turn about up; a huge vertical drag stops short of the pole.
  camera = start;
  orbitCamera(camera, 180.0f, 0.0f, 180);
  const glm::vec2 before(start.eye.x - start.target.x, start.eye.z - start.target.z);
  const glm::vec2 after(camera.eye.x - camera.target.x, camera.eye.z - camera.target.z);
  EXPECT_NEAR(glm::dot(glm::normalize(before), glm::normalize(after)), -1.0f, 1e-4f);
  orbitCamera(camera, 0.0f, 1e5f, 180);
  const float fromUp = std::acos(glm::dot(glm::normalize(camera.eye - camera.target), glm::vec3(0, 1, 0)));
  EXPECT_NEAR(fromUp, 0.05f, 1e-3f);
  EXPECT_NO_THROW(camera.validate("orbited camera"));
}

TEST(CameraControls, PanKeepsTheTargetUnderTheCursorAndZoomScalesTheDistance) {
  const Camera start = builtinSceneCamera(320, 180);
  const float distance = glm::length(start.eye - start.target);
  Camera camera = start;
  panCamera(camera, 0.0f, 180.0f, 180);  // a full-height drag moves the view by its height at the target's depth
  const float viewHeight = 2.0f * distance * std::tan(start.fovyRadians() * 0.5f);
  EXPECT_NEAR(glm::length(camera.target - start.target), viewHeight, 1e-3f * viewHeight);
  EXPECT_LT(glm::length((camera.eye - start.eye) - (camera.target - start.target)), 1e-5f)
      << "eye and target move together";

  camera = start;
  zoomCamera(camera, 0.5f, 10.0f);
  EXPECT_NEAR(glm::length(camera.eye - camera.target), 0.5f * distance, 1e-4f * distance);
  zoomCamera(camera, 1e-9f, 10.0f);
  EXPECT_NEAR(glm::length(camera.eye - camera.target), 10.0f * 1e-3f, 1e-6f) << "clamped near the target";
  EXPECT_NO_THROW(camera.validate("zoomed camera"));

  // Orthographic: a pan moves the view by its height, and a zoom scales the view's size with the eye's distance.
  camera = start.asOrthographic();
  panCamera(camera, 0.0f, 180.0f, 180);
  EXPECT_NEAR(glm::length(camera.target - start.target), 2.0f * start.asOrthographic().ymag, 1e-3f * viewHeight);
  camera = start.asOrthographic();
  zoomCamera(camera, 0.5f, 10.0f);
  EXPECT_NEAR(camera.ymag, 0.5f * start.asOrthographic().ymag, 1e-5f);
  EXPECT_NEAR(camera.asPerspective().halfHeightAt(glm::length(camera.eye - camera.target), 1.0f), camera.ymag, 1e-4f)
      << "back to perspective, the same view at the target";
}

TEST(CameraControls, FitDepthRangeHugsTheSceneWithBoundedRatio) {
  Bounds bounds;
  bounds.add(glm::vec3(-1.0f));
  bounds.add(glm::vec3(1.0f));
  Camera camera = builtinSceneCamera();
  camera.target = glm::vec3(0.0f);
  camera.eye = glm::vec3(0.0f, 0.0f, 10.0f);
  fitDepthRange(camera, bounds);
  EXPECT_LE(camera.near, 10.0f - bounds.radius());
  EXPECT_GE(camera.far, 10.0f + bounds.radius());
  EXPECT_GT(camera.near, 10.0f - 1.1f * bounds.radius());
  camera.eye = glm::vec3(0.1f, 0.0f, 0.0f);  // inside the bounds: near is limited by the depth ratio
  fitDepthRange(camera, bounds);
  EXPECT_FLOAT_EQ(camera.far / camera.near, kMaxDepthRatio);
}
