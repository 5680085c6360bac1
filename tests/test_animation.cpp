// Sampling glTF animations and posing scenes (scene/Animation.h) against values computed by hand: every
// interpolation (STEP, LINEAR with the shorter-arc slerp, CUBICSPLINE with tangents), clamping outside the keys, the
// looping timeline, a parent moving its child, linear blend skinning of a two-bone chain and morphing; then Debian's
// two moving samples, simple_skin and AnimatedMorphCube, through the loader, at times whose pose can be reasoned
// out from the files.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "TestSupport.h"
#include "base/Error.h"
#include "scene/Animation.h"
#include "scene/GltfLoader.h"

using namespace obscura;

namespace {

AnimationSampler makeSampler(std::vector<float> times, std::vector<float> values, int components,
                             Interpolation interpolation = Interpolation::Linear) {
  AnimationSampler sampler;
  sampler.times = std::move(times);
  sampler.values = std::move(values);
  sampler.components = components;
  sampler.interpolation = interpolation;
  return sampler;
}

void expectValues(const std::vector<float>& actual, const std::vector<float>& expected, const std::string& what,
                  float tolerance = 1e-5f) {
  ASSERT_EQ(actual.size(), expected.size()) << what;
  for (size_t i = 0; i < actual.size(); ++i)
    EXPECT_NEAR(actual[i], expected[i], tolerance) << what << ", [" << i << "]";
}

void expectNear(const glm::vec3& actual, const glm::vec3& expected, const std::string& what, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
  EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
  EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

// A sampled rotation (x, y, z, w) applied to a vector: q and -q give the same answer, as they should.
glm::vec3 rotate(const std::vector<float>& q, const glm::vec3& v) {
  return glm::quat(q[3], q[0], q[1], q[2]) * v;
}

// The quaternion (x, y, z, w) of `degrees` about +z.
std::vector<float> aboutZ(float degrees) {
  const float half = glm::radians(degrees) / 2.0f;
  return {0.0f, 0.0f, std::sin(half), std::cos(half)};
}

std::vector<float> concat(std::initializer_list<std::vector<float>> parts) {
  std::vector<float> out;
  for (const std::vector<float>& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

// A mesh of one triangle whose corners are `positions` (normals +z), for posing.
Mesh triangle(std::vector<glm::vec3> positions) {
  Mesh mesh;
  mesh.positions = std::move(positions);
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0, 0, 1));
  for (std::uint32_t i = 0; i < mesh.positions.size(); ++i) mesh.indices.push_back(i);
  return mesh;
}

int addNode(Scene& scene, const std::string& name, int parent, glm::vec3 translation = glm::vec3(0.0f)) {
  Node node;
  node.name = name;
  node.parent = parent;
  node.translation = translation;
  scene.nodes.push_back(node);
  return static_cast<int>(scene.nodes.size()) - 1;
}

}  // namespace

TEST(AnimationSampling, LinearInterpolatesAndClampsOutsideTheKeys) {
  const AnimationSampler s = makeSampler({1, 3}, {0, 0, 0, 4, -2, 8}, 3);
  expectValues(sampleAnimation(s, 2.0f, false), {2, -1, 4}, "halfway");
  expectValues(sampleAnimation(s, 1.5f, false), {1, -0.5f, 2}, "a quarter of the way");
  expectValues(sampleAnimation(s, 1.0f, false), {0, 0, 0}, "on the first key");
  expectValues(sampleAnimation(s, 3.0f, false), {4, -2, 8}, "on the last key");
  expectValues(sampleAnimation(s, 0.0f, false), {0, 0, 0}, "before the first key: the first value");
  expectValues(sampleAnimation(s, -5.0f, false), {0, 0, 0}, "long before: the first value");
  expectValues(sampleAnimation(s, 10.0f, false), {4, -2, 8}, "after the last key: the last value");
  const AnimationSampler single = makeSampler({0.5f}, {7, 8, 9}, 3);
  expectValues(sampleAnimation(single, 0.0f, false), {7, 8, 9}, "one key: its value before");
  expectValues(sampleAnimation(single, 9.0f, false), {7, 8, 9}, "one key: its value after");
}

TEST(AnimationSampling, StepHoldsEachKeyUntilTheNext) {
  // Two morph weights per key, as a weights channel of a two-target mesh would have.
  const AnimationSampler s = makeSampler({0, 1, 2}, {1, 10, 2, 20, 3, 30}, 2, Interpolation::Step);
  expectValues(sampleAnimation(s, 0.0f, false), {1, 10}, "t = 0");
  expectValues(sampleAnimation(s, 0.99f, false), {1, 10}, "just before key 1");
  expectValues(sampleAnimation(s, 1.0f, false), {2, 20}, "on key 1");
  expectValues(sampleAnimation(s, 1.5f, false), {2, 20}, "between keys 1 and 2");
  expectValues(sampleAnimation(s, 2.5f, false), {3, 30}, "after the last key");
  expectValues(sampleAnimation(s, -1.0f, false), {1, 10}, "before the first key");
}

TEST(AnimationSampling, LinearRotationsSlerpAlongTheShorterArc) {
  const glm::vec3 x(1, 0, 0);
  // Identity to 90 degrees about z: halfway is 45 degrees, at constant angular speed a quarter is 22.5.
  AnimationSampler s = makeSampler({0, 1}, concat({aboutZ(0), aboutZ(90)}), 4);
  expectValues(sampleAnimation(s, 0.5f, true), aboutZ(45), "halfway");
  expectValues(sampleAnimation(s, 0.25f, true), aboutZ(22.5f), "a quarter (slerp, not lerp)");

  // The same keys with the second negated (-q is the same rotation): a naive interpolation would turn 270 degrees
  // the long way round, through (0, 0, -0.38, 0.92)'s 135 degrees about -z at the middle; the shorter arc is 45
  // degrees about +z there.
  std::vector<float> negated = aboutZ(90);
  for (float& c : negated) c = -c;
  s = makeSampler({0, 1}, concat({aboutZ(0), negated}), 4);
  const float r = std::sqrt(0.5f);
  expectNear(rotate(sampleAnimation(s, 0.5f, true), x), glm::vec3(r, r, 0),
             "hemisphere flip: 45 degrees at the middle");
  expectNear(rotate(sampleAnimation(s, 0.25f, true), x), glm::vec3(std::cos(glm::radians(22.5f)),
                                                                   std::sin(glm::radians(22.5f)), 0),
             "hemisphere flip: 22.5 degrees at a quarter");
  expectNear(rotate(sampleAnimation(s, 1.0f, true), x), glm::vec3(0, 1, 0), "hemisphere flip: the last key");

  // q then -q: one rotation held still, not a full turn.
  std::vector<float> q = aboutZ(60), minusQ = q;
  for (float& c : minusQ) c = -c;
  s = makeSampler({0, 2}, concat({q, minusQ}), 4);
  for (float t : {0.0f, 0.5f, 1.0f, 1.5f, 2.0f})
    expectNear(rotate(sampleAnimation(s, t, true), x), glm::vec3(0.5f, std::sqrt(0.75f), 0),
               "q to -q at t = " + std::to_string(t));

  // Sampled rotations come out normalised, whatever the keys' lengths.
  s = makeSampler({0, 1}, {0, 0, 0, 2, 0, 0, 3, 0}, 4, Interpolation::Step);
  expectValues(sampleAnimation(s, 1.0f, true), {0, 0, 1, 0}, "a key of length 3, normalised");
}

TEST(AnimationSampling, CubicSplineFollowsTheHermiteCurveWithIntervalScaledTangents) {
  // Keys at 0 and 2 (interval 2). Key 0: in-tangent 0, value 1, out-tangent 3; key 1: in-tangent -1, value 5,
  // out-tangent 0. With u = t / 2 the spec's curve is
  //   p = (2u^3 - 3u^2 + 1) 1 + 2 (u^3 - 2u^2 + u) 3 + (-2u^3 + 3u^2) 5 + 2 (u^3 - u^2) (-1):
  //   u = 1/2: 0.5 + 0.75 + 2.5 + 0.25 = 4;  u = 1/4: 0.84375 + 0.84375 + 0.78125 + 0.09375 = 2.5625.
  const AnimationSampler s = makeSampler({0, 2}, {0, 1, 3, -1, 5, 0}, 1, Interpolation::CubicSpline);
  expectValues(sampleAnimation(s, 1.0f, false), {4.0f}, "u = 1/2");
  expectValues(sampleAnimation(s, 0.5f, false), {2.5625f}, "u = 1/4");
  expectValues(sampleAnimation(s, 0.0f, false), {1.0f}, "on key 0: its value, not a tangent");
  expectValues(sampleAnimation(s, 2.0f, false), {5.0f}, "on key 1");
  expectValues(sampleAnimation(s, -1.0f, false), {1.0f}, "clamped before");
  expectValues(sampleAnimation(s, 3.0f, false), {5.0f}, "clamped after: the value, not the out-tangent");

  // Three components, each its own curve: zero tangents give the smoothstep 3u^2 - 2u^3 between the values.
  const AnimationSampler smooth = makeSampler(
      {1, 2}, {0, 0, 0, 0, 10, 20, 0, 0, 0, 0, 0, 0, 4, 10, 20, 0, 0, 0}, 3, Interpolation::CubicSpline);
  const float h = 3 * 0.25f * 0.25f - 2 * 0.25f * 0.25f * 0.25f;  // u = 1/4: 0.15625
  expectValues(sampleAnimation(smooth, 1.25f, false), {4 * h, 10, 20}, "smoothstep in x, constant y and z");

  // A CUBICSPLINE rotation comes out normalised: between two keys with zero tangents the curve passes inside the
  // unit sphere.
  const AnimationSampler turn = makeSampler({0, 1}, concat({{0, 0, 0, 0}, aboutZ(0), {0, 0, 0, 0},
                                                             {0, 0, 0, 0}, aboutZ(90), {0, 0, 0, 0}}),
                                            4, Interpolation::CubicSpline);
  const std::vector<float> middle = sampleAnimation(turn, 0.5f, true);
  EXPECT_NEAR(middle[0] * middle[0] + middle[1] * middle[1] + middle[2] * middle[2] + middle[3] * middle[3], 1.0f,
              1e-5f);
  expectValues(middle, aboutZ(45), "symmetric keys: 45 degrees at the middle");
}

// A parent node translated and turned by an animation carries its child; the timeline loops at the duration.
TEST(AnimationPose, AParentsMotionMovesItsChildAndTheTimelineLoops) {
  Scene scene;
  const int parent = addNode(scene, "parent", -1);
  const int child = addNode(scene, "child", parent, glm::vec3(0, 1, 0));
  scene.meshes.push_back(triangle({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
  scene.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)), child, -1});
  Animation animation;
  animation.name = "slide and turn";
  animation.samplers.push_back(makeSampler({0, 2}, {0, 0, 0, 4, 0, 0}, 3));
  animation.samplers.push_back(makeSampler({0, 2}, concat({aboutZ(0), aboutZ(90)}), 4));
  animation.channels.push_back({0, parent, AnimationPath::Translation});
  animation.channels.push_back({1, parent, AnimationPath::Rotation});
  scene.animations.push_back(animation);
  ASSERT_FLOAT_EQ(scene.animations[0].duration(), 2.0f);

  auto childOrigin = [&](double time, PoseOptions options = {}) {
    const ScenePose pose = evaluatePose(scene, time, options);
    return glm::vec3(pose.instanceWorld[0] * glm::vec4(0, 0, 0, 1));
  };
  expectNear(childOrigin(0.0), glm::vec3(0, 1, 0), "t = 0: the rest pose");
  // t = 1: the parent at (2, 0, 0) turned 45 degrees, so the child's (0, 1, 0) lands at (2 - r, r, 0).
  const float r = std::sqrt(0.5f);
  expectNear(childOrigin(1.0), glm::vec3(2 - r, r, 0), "t = 1");
  // t = 2, the end: the parent at (4, 0, 0) turned 90 degrees, the child at (3, 0, 0).
  PoseOptions once;
  once.loop = false;
  expectNear(childOrigin(2.0, once), glm::vec3(3, 0, 0), "the end, not looping");
  expectNear(childOrigin(7.0, once), glm::vec3(3, 0, 0), "past the end, not looping: the last keys");
  expectNear(childOrigin(5.0), glm::vec3(2 - r, r, 0), "looping: t = 5 plays t = 1");
  expectNear(childOrigin(-1.0), glm::vec3(0, 1, 0), "before 0: the first keys");
  PoseOptions still;
  still.animation = AnimationChoice::none();
  expectNear(childOrigin(1.0, still), glm::vec3(0, 1, 0), "no animation chosen: the rest pose");
  // The child's own node world matrix is what places it.
  const ScenePose pose = evaluatePose(scene, 1.0);
  EXPECT_EQ(pose.nodeWorld[static_cast<size_t>(child)], pose.instanceWorld[0]);
}

// What may move (static batches keep the rest): a node some channel translates, turns or scales, and its
// descendants; not its parent, a sibling, nor a node whose morph weights alone are animated.
TEST(AnimationPose, MovingNodesAreTheAnimatedAndTheirDescendants) {
  Scene scene;
  const int root = addNode(scene, "root", -1);
  const int animated = addNode(scene, "animated", root);
  const int child = addNode(scene, "child", animated);
  const int grandchild = addNode(scene, "grandchild", child);
  const int sibling = addNode(scene, "sibling", root);
  const int morphed = addNode(scene, "morphed", root);
  Animation animation;
  animation.samplers.push_back(makeSampler({0, 1}, concat({aboutZ(0), aboutZ(90)}), 4));
  animation.samplers.push_back(makeSampler({0, 1}, {0, 1}, 1));
  animation.channels.push_back({0, animated, AnimationPath::Rotation});
  animation.channels.push_back({1, morphed, AnimationPath::Weights});
  scene.animations.push_back(animation);
  const std::vector<bool> moving = movingNodes(scene);
  ASSERT_EQ(moving.size(), scene.nodes.size());
  EXPECT_FALSE(moving[static_cast<size_t>(root)]);
  EXPECT_TRUE(moving[static_cast<size_t>(animated)]);
  EXPECT_TRUE(moving[static_cast<size_t>(child)]);
  EXPECT_TRUE(moving[static_cast<size_t>(grandchild)]);
  EXPECT_FALSE(moving[static_cast<size_t>(sibling)]);
  EXPECT_FALSE(moving[static_cast<size_t>(morphed)]);
  scene.animations.clear();
  EXPECT_EQ(movingNodes(scene), std::vector<bool>(scene.nodes.size(), false));
}

// Linear blend skinning of a two-bone chain: the hip at the origin, the knee one up; the knee turns 90 degrees about
// z over one second. Inverse bind matrices undo the joints' rest placement, so at rest nothing moves.
TEST(AnimationPose, SkinsATwoBoneChainAsComputedByHand) {
  Scene scene;
  const int meshNode = addNode(scene, "mesh", -1, glm::vec3(100, 0, 0));  // ignored for a skinned mesh
  const int hip = addNode(scene, "hip", -1);
  const int knee = addNode(scene, "knee", hip, glm::vec3(0, 1, 0));
  Skin skin;
  skin.joints = {hip, knee};
  skin.inverseBind = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0))};
  scene.skins.push_back(skin);
  Mesh mesh = triangle({{1, 0, 0}, {1, 1, 0}, {1, 2, 0}});
  mesh.joints = {{0, 0, 0, 0}, {0, 1, 0, 0}, {1, 0, 0, 0}};
  mesh.weights = {{1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}};
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, glm::mat4(1.0f), meshNode, 0});
  Animation bend;
  bend.samplers.push_back(makeSampler({0, 1}, concat({aboutZ(0), aboutZ(90)}), 4));
  bend.channels.push_back({0, knee, AnimationPath::Rotation});
  scene.animations.push_back(bend);

  const ScenePose rest = evaluatePose(scene, 0.0);
  EXPECT_EQ(rest.instanceWorld[0], glm::mat4(1.0f)) << "a skinned instance is placed by its joints alone";
  const PosedVertices atRest = posedMesh(scene.meshes[0], rest.skinJoints[0], rest.instanceWeights[0]);
  for (size_t v = 0; v < 3; ++v)
    expectNear(atRest.positions[v], mesh.positions[v], "rest, vertex " + std::to_string(v));

  // t = 1. The knee's joint matrix is T(0,1,0) R90 T(0,-1,0):
  //   (1, 2, 0), the knee's alone: (1, 1, 0) -> (-1, 1, 0) -> (-1, 2, 0);
  //   (1, 1, 0), half each: the hip leaves it at (1, 1, 0), the knee takes it to (0, 2, 0): (0.5, 1.5, 0);
  //   (1, 0, 0), the hip's alone: unmoved.
  PoseOptions once;  // t = 1 is the end: a looping timeline would wrap it to 0
  once.loop = false;
  const ScenePose bent = evaluatePose(scene, 1.0, once);
  const PosedVertices posed = posedMesh(scene.meshes[0], bent.skinJoints[0], bent.instanceWeights[0]);
  expectNear(posed.positions[0], glm::vec3(1, 0, 0), "the hip's vertex");
  expectNear(posed.positions[1], glm::vec3(0.5f, 1.5f, 0), "the shared vertex");
  expectNear(posed.positions[2], glm::vec3(-1, 2, 0), "the knee's vertex");
  // Normals turn with the joints: the knee's vertex's +z stays +z (a turn about z), renormalised.
  expectNear(posed.normals[2], glm::vec3(0, 0, 1), "the knee's normal");

  // posedScene bakes the same positions, in world space, under an identity instance matrix.
  const Scene still = posedScene(scene, bent);
  ASSERT_EQ(still.instances.size(), 1u);
  EXPECT_EQ(still.instances[0].world, glm::mat4(1.0f));
  EXPECT_FALSE(still.animated());
  const Mesh& baked = still.meshes[static_cast<size_t>(still.instances[0].mesh)];
  EXPECT_FALSE(baked.skinned());
  expectNear(baked.positions[2], glm::vec3(-1, 2, 0), "baked knee vertex");
}

TEST(AnimationPose, MorphWeightsDisplaceByTheirTargets) {
  Scene scene;
  const int node = addNode(scene, "morphed", -1, glm::vec3(10, 0, 0));
  scene.nodes[0].weights = {0.25f, 0.0f};
  Mesh mesh = triangle({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  MorphTarget up, right;
  up.positions = {{0, 0, 4}, {0, 0, 0}, {0, 0, 0}};
  right.positions = {{0, 0, 0}, {2, 0, 0}, {0, 0, 0}};
  right.normals = {{0, 0, 0}, {1, 0, -1}, {0, 0, 0}};
  mesh.morphTargets = {up, right};
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0)), node, -1});
  Animation animation;
  animation.samplers.push_back(makeSampler({0, 1}, {0, 0, 1, 0.5f}, 2));
  animation.channels.push_back({0, node, AnimationPath::Weights});
  scene.animations.push_back(animation);

  PoseOptions still;
  still.animation = AnimationChoice::none();
  const ScenePose rest = evaluatePose(scene, 0.0, still);
  expectValues(rest.instanceWeights[0], {0.25f, 0.0f}, "rest weights: the node's");
  // t = 0.5: weights (0.5, 0.25): vertex 0 up by 2, vertex 1 right by 0.5, its normal (0.25, 0, 0.75) normalised.
  const ScenePose pose = evaluatePose(scene, 0.5);
  expectValues(pose.instanceWeights[0], {0.5f, 0.25f}, "t = 0.5");
  const PosedVertices posed = posedMesh(scene.meshes[0], {}, pose.instanceWeights[0]);
  expectNear(posed.positions[0], glm::vec3(0, 0, 2), "vertex 0");
  expectNear(posed.positions[1], glm::vec3(1.5f, 0, 0), "vertex 1");
  expectNear(posed.normals[1], glm::normalize(glm::vec3(0.25f, 0, 0.75f)), "vertex 1's normal");
  // A morphed, unskinned instance stays in its node's space.
  const Scene baked = posedScene(scene, pose);
  expectNear(glm::vec3(baked.instances[0].world[3]), glm::vec3(10, 0, 0), "the node's place");
  expectNear(baked.meshes[static_cast<size_t>(baked.instances[0].mesh)].positions[0], glm::vec3(0, 0, 2), "baked");
}

// Debian's simple_skin (the glTF tutorial's): a strip of height 2 skinned to two joints, both at (0, 1, 0) with
// inverse bind matrices T(-0.5, -1, 0); weights blend from joint 0 at the bottom to joint 1 at the top, and the
// animation turns joint 1 about z (90 degrees at t = 1, back to rest at 2.5 and 3, -90 at 4).
TEST(AnimationPose, SimpleSkinBendsAsItsFileDescribes) {
  const Scene scene = loadGltfFile(test::assimpModels() + "/simple_skin/simple_skin.gltf");
  ASSERT_EQ(scene.instances.size(), 1u);
  const Mesh& mesh = scene.meshes[static_cast<size_t>(scene.instances[0].mesh)];
  auto posedAt = [&](double time) {
    const Scene still = posedScene(scene, evaluatePose(scene, time));
    return still.meshes[static_cast<size_t>(still.instances[0].mesh)].positions;
  };
  const std::vector<glm::vec3> rest = posedAt(0.0), bent = posedAt(1.0), back = posedAt(2.75);
  const std::vector<glm::vec3> other = posedAt(4.0);
  ASSERT_EQ(rest.size(), mesh.positions.size());
  int top = 0, middle = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec3 p = mesh.positions[v];
    const std::string what = "vertex " + std::to_string(v) + " at (" + std::to_string(p.x) + ", " +
                             std::to_string(p.y) + ")";
    // At rest both joint matrices are T(-0.5, 0, 0): the strip, moved half a unit left.
    expectNear(rest[v], p + glm::vec3(-0.5f, 0, 0), what + ", rest");
    expectNear(back[v], rest[v], what + ", t = 2.75 (keys at rest)");
    // At t = 1 joint 1 is T(0,1,0) R90 T(-0.5,-1,0): (x, y) -> (1 - y, x - 0.5); joint 0 leaves (x - 0.5, y).
    const float w1 = p.y / 2.0f;
    const glm::vec3 byJoint0(p.x - 0.5f, p.y, 0), byJoint1(1.0f - p.y, p.x - 0.5f + 1.0f, 0);
    expectNear(bent[v], (1 - w1) * byJoint0 + w1 * byJoint1, what + ", t = 1");
    // At t = 4 joint 1 turns -90 degrees: (x, y) -> (y - 1, 1.5 - x) under joint 1.
    const glm::vec3 byJoint1Back(p.y - 1.0f, 1.5f - p.x, 0);
    expectNear(other[v], (1 - w1) * byJoint0 + w1 * byJoint1Back, what + ", t = 4");
    if (p.y == 2.0f) ++top;
    if (p.y == 1.0f) ++middle;
  }
  EXPECT_GT(top, 0);
  EXPECT_GT(middle, 0);
  // The corners spelled out: the top right (1, 2) goes to (-1, 1.5); the middle right (1, 1), half each, to
  // (0.25, 1.25); the bottom left (0, 0) stays at (-0.5, 0).
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (mesh.positions[v] == glm::vec3(1, 2, 0)) expectNear(bent[v], glm::vec3(-1, 1.5f, 0), "top right");
    if (mesh.positions[v] == glm::vec3(1, 1, 0)) expectNear(bent[v], glm::vec3(0.25f, 1.25f, 0), "middle right");
    if (mesh.positions[v] == glm::vec3(0, 0, 0)) expectNear(bent[v], glm::vec3(-0.5f, 0, 0), "bottom left");
  }
}

// Debian's AnimatedMorphCube: a cube of side 0.02 scaled 100 and turned half a turn about (0, 1, -1), so local
// (x, y, z) lands at 100 (-x, -z, -y). Target "thin" lifts the bottom face (local y = -0.01) by 0.01893; target
// "angle" lifts its back edge (local z = -0.01) by 0.01989. The animation ("Square") reaches weights (1, 0) at
// t = 1.6 and (0, 1) at t = 3.4.
TEST(AnimationPose, AnimatedMorphCubeThinsThenTilts) {
  const Scene scene = loadGltfFile(test::assimpModels() +
                                   "/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
  auto worldPositions = [&](double time) {
    const Scene still = posedScene(scene, evaluatePose(scene, time));
    std::vector<glm::vec3> out;
    for (const glm::vec3& p : still.meshes[static_cast<size_t>(still.instances[0].mesh)].positions)
      out.push_back(glm::vec3(still.instances[0].world * glm::vec4(p, 1.0f)));
    return out;
  };
  auto zExtent = [](const std::vector<glm::vec3>& points) {
    float lo = 1e30f, hi = -1e30f;
    for (const glm::vec3& p : points) lo = std::min(lo, p.z), hi = std::max(hi, p.z);
    return hi - lo;
  };
  const std::vector<glm::vec3> rest = worldPositions(0.0), thin = worldPositions(1.6), tilted = worldPositions(3.4);
  EXPECT_NEAR(zExtent(rest), 2.0f, 1e-4f) << "a cube of side 2";
  // Thin: local y spans -0.01 + 0.01893 .. 0.01, i.e. 0.107 in world z.
  EXPECT_NEAR(zExtent(thin), 100.0f * (0.02f - 0.018932531f), 2e-3f);
  // Tilted: on the side whose local z is -0.01 (world y = +1) the bottom rose to 0.00989, so that side is 0.011
  // thick in world z; the other side (world y = -1) keeps its full 2.
  for (const glm::vec3& p : tilted) {
    if (p.y > 0.99f) {
      EXPECT_LE(p.z, -1.0f + 100.0f * (0.02f - 0.019890836f) + 1e-3f) << p.z;
    }
    if (p.y < -0.99f) {
      EXPECT_NEAR(std::abs(p.z), 1.0f, 1e-3f) << p.z;
    }
  }
  EXPECT_NEAR(zExtent(tilted), 2.0f, 1e-3f);
  // Between the keys, the weights are the sampler's, and the pose differs from the rest.
  const std::vector<glm::vec3> between = worldPositions(0.8);
  float moved = 0.0f;
  for (size_t v = 0; v < rest.size(); ++v) moved = std::max(moved, glm::length(between[v] - rest[v]));
  EXPECT_NEAR(moved, 100.0f * 0.5f * 0.018932531f, 2e-2f) << "weights (0.5, 0) at t = 0.8";
}
