// The default AO radius (scene/SceneScale.h): 5 % of the scene's bounding-sphere diameter to two significant figures,
// the built-in scene's own 1 m, scaling with the scene; and how a viewer's state applies it when scenes change
// (ViewerState::sceneLoaded, radiusGiven, toQuery).
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "TestSupport.h"
#include "apps/SceneInput.h"
#include "platform/ViewerState.h"
#include "renderer/RenderSettings.h"
#include "scene/Animation.h"
#include "scene/BuiltinScene.h"
#include "scene/GltfLoader.h"
#include "scene/SceneScale.h"

using namespace obscura;

namespace {

std::string enginePath() { return test::assimpModels() + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"; }

Bounds box(const glm::vec3& min, const glm::vec3& max) {
  Bounds b;
  b.add(min);
  b.add(max);
  return b;
}

}  // namespace

TEST(DefaultAoRadius, RoundsToTwoSignificantFigures) {
  EXPECT_FLOAT_EQ(roundToTwoSignificantFigures(41.8025f), 42.0f);
  EXPECT_FLOAT_EQ(roundToTwoSignificantFigures(0.418025f), 0.42f);
  EXPECT_FLOAT_EQ(roundToTwoSignificantFigures(1234.0f), 1200.0f);
  EXPECT_FLOAT_EQ(roundToTwoSignificantFigures(99.6f), 100.0f);
  EXPECT_FLOAT_EQ(roundToTwoSignificantFigures(0.01234f), 0.012f);
  EXPECT_FLOAT_EQ(roundToTwoSignificantFigures(7.0f), 7.0f);
  EXPECT_EQ(roundToTwoSignificantFigures(0.0f), 0.0f);
  // As the page, the URL and the title bar show it.
  EXPECT_EQ(formatShortest(roundToTwoSignificantFigures(0.418025f)), "0.42");
  EXPECT_EQ(formatShortest(roundToTwoSignificantFigures(41.8025f)), "42");
}

TEST(DefaultAoRadius, IsFivePercentOfTheBoundingSphereDiameter) {
  // A 3 x 4 x 12 box: diagonal (the bounding sphere's diameter) 13, 5 % of it 0.65.
  EXPECT_FLOAT_EQ(suggestedAoRadius(box({0, 0, 0}, {3, 4, 12})), 0.65f);
  EXPECT_FLOAT_EQ(suggestedAoRadius(box({-300, -400, -1200}, {0, 0, 0})), 65.0f);
  // Nothing to measure: 1. Out of the parameter's range: clamped to it.
  EXPECT_EQ(suggestedAoRadius(Bounds{}), 1.0f);
  EXPECT_EQ(suggestedAoRadius(box({1, 2, 3}, {1, 2, 3})), 1.0f);
  EXPECT_EQ(suggestedAoRadius(box({0, 0, 0}, {1e-7f, 0, 0})), kMinAoRadius);
  EXPECT_EQ(suggestedAoRadius(box({-1e10f, 0, 0}, {1e10f, 0, 0})), kMaxAoRadius);
  // The clamp is the ao.radius parameter's range.
  const ParameterInfo* radius = RenderSettings::find("ao.radius");
  ASSERT_NE(radius, nullptr);
  EXPECT_FLOAT_EQ(static_cast<float>(radius->min), kMinAoRadius);
  EXPECT_FLOAT_EQ(static_cast<float>(radius->max), kMaxAoRadius);
}

TEST(DefaultAoRadius, TheBuiltinSceneKeepsItsMetreAndScalesWithIt) {
  const Scene builtin = makeBuiltinScene();
  EXPECT_EQ(defaultAoRadius(builtin), 1.0f);
  EXPECT_NE(suggestedAoRadius(builtin.worldBounds()), 1.0f) << "the special case is needed: the rule alone differs";
  std::printf("built-in scene: the rule alone would give %s (diameter %g)\n",
              formatShortest(suggestedAoRadius(builtin.worldBounds())).c_str(), 2.0 * builtin.worldBounds().radius());
  Scene scaled = makeBuiltinScene();
  scaleScene(scaled, 100.0f);
  EXPECT_FLOAT_EQ(defaultAoRadius(scaled), 100.0f);
  EXPECT_NE(defaultAoRadiusReason(builtin).find("built-in scene"), std::string::npos) << defaultAoRadiusReason(builtin);
}

TEST(DefaultAoRadius, TheEngineInCentimetresGets42AndScalesWithTheScene) {
  const Scene engine = loadGltfFile(enginePath());
  // Its bounds' diagonal is 836.05 cm (docs/benchmarks.md: 41.8025 = 5 %), so 42 to two significant figures.
  EXPECT_NEAR(2.0f * engine.worldBounds().radius(), 836.05f, 0.01f);
  EXPECT_EQ(defaultAoRadius(engine), 42.0f);
  EXPECT_NE(defaultAoRadiusReason(engine).find("5 % of the scene's bounding-sphere diameter, 836.05"),
            std::string::npos)
      << defaultAoRadiusReason(engine);
  // --scene-scale composes: the rule reads the scaled scene.
  for (const float scale : {0.01f, 100.0f}) {
    Scene scaled = engine;
    scaleScene(scaled, scale);
    EXPECT_FLOAT_EQ(defaultAoRadius(scaled), 42.0f * scale) << scale;
  }
}

TEST(DefaultAoRadius, EachSceneLoadedGetsItsOwnUnlessAStateTextGaveOne) {
  ViewerState state;
  EXPECT_EQ(state.settings.ao().radius, 1.0f);
  EXPECT_EQ(state.toQuery().find("radius"), std::string::npos);

  // A scene loaded: its radius, which the state text leaves out as the scene's default.
  state.sceneLoaded(42.0f);
  EXPECT_EQ(state.settings.ao().radius, 42.0f);
  EXPECT_EQ(state.toQuery().find("radius"), std::string::npos) << state.toQuery();
  // Changed by a control or a key: written, but not kept once another scene is loaded.
  state.settings.set("ao.radius", "60");
  EXPECT_NE(state.toQuery().find("ao.radius=60"), std::string::npos) << state.toQuery();
  state.sceneLoaded(0.42f);
  EXPECT_EQ(state.settings.ao().radius, 0.42f);
  EXPECT_FALSE(state.radiusGiven);

  // Given by a state text (a URL, --state), under either name: kept across scenes, and written even where it equals
  // the scene's default, so that the text keeps giving it.
  for (const char* query : {"radius=3", "ao.radius=3"}) {
    ViewerState linked;
    linked.applyQuery(query);
    EXPECT_TRUE(linked.radiusGiven) << query;
    linked.sceneLoaded(42.0f);
    EXPECT_EQ(linked.settings.ao().radius, 3.0f) << query;
    linked.sceneLoaded(3.0f);
    EXPECT_NE(linked.toQuery().find("ao.radius=3&"), std::string::npos) << linked.toQuery();
  }
  // A text without a radius leaves it to the scene.
  ViewerState other;
  other.applyQuery("view=ao&ao.samples=16");
  EXPECT_FALSE(other.radiusGiven);
  // A refused text changes nothing, radiusGiven included.
  EXPECT_THROW(other.applyQuery("radius=2&view=sideways"), InputError);
  EXPECT_FALSE(other.radiusGiven);
}

// --scene-scale on a scene placed by its node hierarchy: posed at any time, every instance (rigid below an animated
// root, or skinned by joints below it) lands where the unscaled pose times the scale puts it; a sampler the root
// shares with a child's channel moves the child as before.
TEST(SceneScale, ScalesAPosedSceneLikeItsRestPose) {
  Scene scene;
  Mesh triangle;
  triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangle.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  triangle.indices = {0, 1, 2};
  scene.meshes.push_back(triangle);
  Mesh skinned = triangle;
  skinned.joints.assign(3, glm::u16vec4(0, 1, 0, 0));
  skinned.weights.assign(3, glm::vec4(0.5f, 0.5f, 0.0f, 0.0f));
  scene.meshes.push_back(skinned);
  Node root, child;
  root.translation = {1, 2, 3};
  root.rotation = glm::angleAxis(0.5f, glm::normalize(glm::vec3(1, 1, 0)));
  root.scale = glm::vec3(2.0f);
  child.parent = 0;
  child.translation = {0, 1, 0};
  scene.nodes = {root, child};
  Skin skin;
  skin.joints = {0, 1};
  skin.inverseBind = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0))};
  scene.skins.push_back(skin);
  Instance rigid, deformed;
  rigid.node = 1;
  deformed.mesh = 1;
  deformed.node = 1;
  deformed.skin = 0;
  scene.instances = {rigid, deformed};
  Animation move;
  AnimationSampler shared;  // translations, used by the root and by the child
  shared.times = {0.0f, 1.0f};
  shared.components = 3;
  shared.values = {0, 0, 0, 4, 0, -2};
  AnimationSampler grow;
  grow.times = {0.0f, 1.0f};
  grow.components = 3;
  grow.interpolation = Interpolation::Step;
  grow.values = {1, 1, 1, 3, 3, 3};
  move.samplers = {shared, grow};
  move.channels = {{0, 0, AnimationPath::Translation}, {0, 1, AnimationPath::Translation},
                   {1, 0, AnimationPath::Scale}};
  scene.animations.push_back(move);

  const float s = 0.01f;
  Scene scaled = scene;
  scaleScene(scaled, s);
  const glm::mat4 scaling = glm::scale(glm::mat4(1.0f), glm::vec3(s));
  for (double time : {0.0, 0.3, 1.0}) {
    const Scene a = posedScene(scene, evaluatePose(scene, time)), b = posedScene(scaled, evaluatePose(scaled, time));
    ASSERT_EQ(a.instances.size(), b.instances.size());
    for (size_t i = 0; i < a.instances.size(); ++i) {
      const Mesh &ma = a.meshes[static_cast<size_t>(a.instances[i].mesh)],
                 &mb = b.meshes[static_cast<size_t>(b.instances[i].mesh)];
      for (size_t v = 0; v < ma.positions.size(); ++v) {
        const glm::vec3 expected = glm::vec3(scaling * a.instances[i].world * glm::vec4(ma.positions[v], 1.0f));
        const glm::vec3 got = glm::vec3(b.instances[i].world * glm::vec4(mb.positions[v], 1.0f));
        EXPECT_LT(glm::length(got - expected), 1e-5f) << "instance " << i << " vertex " << v << " at " << time;
      }
    }
  }
  EXPECT_EQ(scaled.animations[0].samplers.size(), 3u) << "the shared sampler was copied for the root";
  EXPECT_EQ(scaled.animations[0].samplers[0].values, shared.values) << "and the child's kept";
}
