// CPU tests of the built-in scene's two variants (scene/BuiltinScene.h): the still room is the room as it was, and
// what moves (a pendulum on a two-node hierarchy, a limb skinned to three bones, one looping animation) is well
// formed, rests at time 0, loops, moves, and passes through nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_access.hpp>

#include "scene/Animation.h"
#include "scene/BuiltinScene.h"

using namespace obscura;

namespace {

int nodeNamed(const Scene& scene, const std::string& name) {
  for (size_t n = 0; n < scene.nodes.size(); ++n)
    if (scene.nodes[n].name == name) return static_cast<int>(n);
  ADD_FAILURE() << "no node '" << name << "'";
  return 0;
}

// The instance of the skinned limb (the scene's one skinned instance).
const Instance& limbInstance(const Scene& scene) {
  const auto skinned = std::find_if(scene.instances.begin(), scene.instances.end(),
                                    [](const Instance& i) { return i.skin >= 0; });
  EXPECT_NE(skinned, scene.instances.end());
  return *skinned;
}

double largestDifference(const glm::mat4& a, const glm::mat4& b) {
  double largest = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) largest = std::max(largest, double(std::abs(a[c][r] - b[c][r])));
  return largest;
}

PoseOptions playing(const Scene& scene, bool loop = true) {
  PoseOptions options;
  options.animation = parseAnimationChoice(scene, kBuiltinMotionName);
  options.loop = loop;
  return options;
}

// The angle (degrees) of a rotation about z, from a node's local matrix.
double zDegrees(const glm::mat4& local) { return glm::degrees(std::atan2(double(local[0][1]), double(local[0][0]))); }

}  // namespace

// The room the AO figures were measured on (the accuracy guard, the tuned defaults, the golden images, the
// benchmarks): the counts and bounds it had before anything moved.
TEST(BuiltinScene, TheStillRoomIsTheRoomAsItWas) {
  const Scene still = makeBuiltinScene(BuiltinSceneOptions::still());
  EXPECT_EQ(still.meshes.size(), 23u);
  EXPECT_EQ(still.instances.size(), 28u);
  EXPECT_EQ(still.materials.size(), 7u);
  EXPECT_EQ(still.triangleCount(), 10200u);
  const Bounds bounds = still.worldBounds();
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(bounds.min[axis], glm::vec3(-6.2f, -0.2f, -5.2f)[axis], 1e-6f) << "axis " << axis;
    EXPECT_NEAR(bounds.max[axis], glm::vec3(6.0f, 4.1f, 5.0f)[axis], 1e-6f) << "axis " << axis;
  }
  EXPECT_TRUE(still.nodes.empty());
  EXPECT_FALSE(still.animated());
  EXPECT_EQ(still.designedAoRadius, 1.0f);
  // The default is the moving scene: motion can be seen without a file.
  EXPECT_TRUE(makeBuiltinScene().animated());
}

// The moving scene begins with the still room, unchanged, and keeps within its bounds.
TEST(BuiltinScene, TheMovingSceneAddsToTheStillRoom) {
  const Scene still = makeBuiltinScene(BuiltinSceneOptions::still());
  const Scene moving = makeBuiltinScene(BuiltinSceneOptions::withMotion());
  ASSERT_GT(moving.meshes.size(), still.meshes.size());
  ASSERT_GT(moving.instances.size(), still.instances.size());
  for (size_t m = 0; m < still.meshes.size(); ++m) {
    EXPECT_EQ(moving.meshes[m].positions, still.meshes[m].positions) << "mesh " << m;
    EXPECT_EQ(moving.meshes[m].indices, still.meshes[m].indices) << "mesh " << m;
    EXPECT_EQ(moving.meshes[m].material, still.meshes[m].material) << "mesh " << m;
  }
  for (size_t i = 0; i < still.instances.size(); ++i) {
    EXPECT_EQ(moving.instances[i].mesh, still.instances[i].mesh) << "instance " << i;
    EXPECT_EQ(moving.instances[i].world, still.instances[i].world) << "instance " << i;
    EXPECT_EQ(moving.instances[i].node, -1) << "the room is fixed";
    EXPECT_EQ(moving.instances[i].skin, -1);
  }
  for (size_t m = 0; m < still.materials.size(); ++m)
    EXPECT_EQ(moving.materials[m].baseColorFactor, still.materials[m].baseColorFactor) << "material " << m;
  EXPECT_TRUE(moving.animated());
  EXPECT_EQ(moving.designedAoRadius, 1.0f);
  const Bounds a = moving.worldBounds(), b = still.worldBounds();
  EXPECT_EQ(a.min, b.min);
  EXPECT_EQ(a.max, b.max);
}

TEST(BuiltinScene, TheHierarchyTheSkinAndTheAnimationAreWellFormed) {
  const Scene scene = makeBuiltinScene(BuiltinSceneOptions::withMotion());
  const ScenePose rest = evaluatePose(scene, 0.0, {AnimationChoice::none(), true});
  for (size_t n = 0; n < scene.nodes.size(); ++n) EXPECT_LT(scene.nodes[n].parent, static_cast<int>(n));
  EXPECT_GE(scene.nodes[static_cast<size_t>(nodeNamed(scene, "pendulum bob"))].parent, 0) << "a child node";
  // Rigid instances on nodes sit where their node is at rest; rigid meshes carry no joints.
  for (const Instance& instance : scene.instances) {
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    if (instance.skin < 0) {
      EXPECT_FALSE(mesh.skinned());
    }
    if (instance.node >= 0) {
      EXPECT_LE(largestDifference(instance.world, rest.nodeWorld[static_cast<size_t>(instance.node)]), 1e-6);
    }
  }

  ASSERT_EQ(scene.skins.size(), 1u);
  const Skin& skin = scene.skins[0];
  ASSERT_EQ(skin.joints.size(), 3u);
  ASSERT_EQ(skin.inverseBind.size(), skin.joints.size());
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    ASSERT_GE(skin.joints[j], 0);
    ASSERT_LT(skin.joints[j], static_cast<int>(scene.nodes.size()));
    if (j > 0) {
      EXPECT_EQ(scene.nodes[static_cast<size_t>(skin.joints[j])].parent, skin.joints[j - 1]) << "a chain";
    }
    // The inverse bind matrix undoes the joint's rest world matrix: at rest every joint matrix is the identity.
    EXPECT_LE(largestDifference(skin.inverseBind[j] * rest.nodeWorld[static_cast<size_t>(skin.joints[j])],
                                glm::mat4(1.0f)),
              1e-6)
        << "joint " << j;
  }

  const Instance& limb = limbInstance(scene);
  EXPECT_EQ(limb.world, glm::mat4(1.0f)) << "its joints place it";
  const Mesh& mesh = scene.meshes[static_cast<size_t>(limb.mesh)];
  ASSERT_EQ(mesh.joints.size(), mesh.positions.size());
  ASSERT_EQ(mesh.weights.size(), mesh.positions.size());
  int blended = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec4 w = mesh.weights[v];
    for (int k = 0; k < 4; ++k) {
      EXPECT_GE(w[k], 0.0f);
      if (w[k] > 0.0f) {
        EXPECT_LT(mesh.joints[v][k], skin.joints.size());
      }
    }
    EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-6f) << "vertex " << v;
    blended += std::max({w.x, w.y, w.z}) < 0.99f;
  }
  EXPECT_GT(blended, 64) << "rings across each joint blend two bones (a smooth bend, not a kink)";

  ASSERT_EQ(scene.animations.size(), 1u);
  const Animation& motion = scene.animations[0];
  EXPECT_EQ(motion.name, kBuiltinMotionName);
  EXPECT_FLOAT_EQ(motion.duration(), kBuiltinMotionSeconds);
  bool cubic = false;
  for (const AnimationChannel& channel : motion.channels) {
    ASSERT_GE(channel.node, 0);
    ASSERT_LT(channel.node, static_cast<int>(scene.nodes.size()));
    ASSERT_LT(channel.sampler, static_cast<int>(motion.samplers.size()));
    const AnimationSampler& s = motion.samplers[static_cast<size_t>(channel.sampler)];
    EXPECT_EQ(channel.path, AnimationPath::Rotation);
    EXPECT_EQ(s.components, 4);
    EXPECT_EQ(s.times.front(), 0.0f);
    EXPECT_EQ(s.times.back(), kBuiltinMotionSeconds);
    for (size_t k = 1; k < s.times.size(); ++k) EXPECT_LT(s.times[k - 1], s.times[k]);
    const size_t perKey = s.interpolation == Interpolation::CubicSpline ? 12 : 4;
    ASSERT_EQ(s.values.size(), s.times.size() * perKey);
    cubic |= s.interpolation == Interpolation::CubicSpline;
  }
  EXPECT_TRUE(cubic) << "one channel is a CUBICSPLINE";
}

// The first keys are the rest pose, bit for bit: at time 0 the moving scene is what a still render of it shows; and
// the last keys are the first, so the loop closes without a jump.
TEST(BuiltinScene, TheMotionRestsAtTimeZeroAndLoops) {
  const Scene scene = makeBuiltinScene(BuiltinSceneOptions::withMotion());
  const ScenePose rest = evaluatePose(scene, 0.0, {AnimationChoice::none(), true});
  const ScenePose start = evaluatePose(scene, 0.0, playing(scene));
  EXPECT_EQ(start.nodeWorld, rest.nodeWorld);
  EXPECT_EQ(start.skinJoints, rest.skinJoints);
  EXPECT_EQ(start.instanceWorld, rest.instanceWorld);
  // The last keys themselves (no wrap), and the wrap.
  EXPECT_EQ(evaluatePose(scene, kBuiltinMotionSeconds, playing(scene, false)).nodeWorld, start.nodeWorld);
  EXPECT_EQ(evaluatePose(scene, kBuiltinMotionSeconds, playing(scene)).nodeWorld, start.nodeWorld);
  // Just before and just after the seam: close to each other (a smooth loop, not only an equal one).
  const ScenePose before = evaluatePose(scene, kBuiltinMotionSeconds - 0.002, playing(scene));
  const ScenePose after = evaluatePose(scene, 0.002, playing(scene));
  for (size_t n = 0; n < scene.nodes.size(); ++n)
    EXPECT_LE(largestDifference(before.nodeWorld[n], after.nodeWorld[n]), 0.02) << scene.nodes[n].name;
  // The limb modelled in place: at rest its joint matrices are the identity, so the posed mesh is the mesh.
  for (const glm::mat4& joint : rest.skinJoints[0]) EXPECT_LE(largestDifference(joint, glm::mat4(1.0f)), 1e-6);
  const Instance& limb = limbInstance(scene);
  const Mesh& mesh = scene.meshes[static_cast<size_t>(limb.mesh)];
  const PosedVertices posed = posedMesh(mesh, rest.skinJoints[0], {});
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    ASSERT_LE(glm::length(posed.positions[v] - mesh.positions[v]), 1e-5f) << "vertex " << v;
}

// Two times a half period apart: the pendulum's bob and the limb are elsewhere, the room is where it was.
TEST(BuiltinScene, ThePendulumAndTheLimbMoveAndTheRoomDoesNot) {
  const Scene still = makeBuiltinScene(BuiltinSceneOptions::still());
  const Scene scene = makeBuiltinScene(BuiltinSceneOptions::withMotion());
  const int pivot = nodeNamed(scene, "pendulum pivot"), bob = nodeNamed(scene, "pendulum bob");
  const float length = -scene.nodes[static_cast<size_t>(bob)].translation.y;
  const ScenePose a = evaluatePose(scene, 1.0, playing(scene));  // a quarter period: the swings at +amplitude
  const ScenePose b = evaluatePose(scene, 3.0, playing(scene));  // three quarters: at -amplitude
  for (size_t i = 0; i < still.instances.size(); ++i) {
    EXPECT_EQ(a.instanceWorld[i], still.instances[i].world) << "instance " << i;
    EXPECT_EQ(b.instanceWorld[i], still.instances[i].world) << "instance " << i;
  }
  // The bob follows its parent, the pivot, 15 degrees either side of straight down.
  const glm::vec3 pivotAt = scene.nodes[static_cast<size_t>(pivot)].translation;
  const glm::vec3 bobA(glm::column(a.nodeWorld[static_cast<size_t>(bob)], 3));
  const glm::vec3 bobB(glm::column(b.nodeWorld[static_cast<size_t>(bob)], 3));
  const float reach = length * std::sin(glm::radians(15.0f));
  EXPECT_NEAR(bobA.x, pivotAt.x + reach, 1e-4f);
  EXPECT_NEAR(bobB.x, pivotAt.x - reach, 1e-4f);
  EXPECT_NEAR(bobA.y, pivotAt.y - length * std::cos(glm::radians(15.0f)), 1e-4f);

  // The limb: its rounded end moves far, its foot on the plinth not at all.
  const Instance& limb = limbInstance(scene);
  const Mesh& mesh = scene.meshes[static_cast<size_t>(limb.mesh)];
  const PosedVertices posedA = posedMesh(mesh, a.skinJoints[0], {}), posedB = posedMesh(mesh, b.skinJoints[0], {});
  const size_t top = static_cast<size_t>(
      std::max_element(mesh.positions.begin(), mesh.positions.end(),
                       [](const glm::vec3& p, const glm::vec3& q) { return p.y < q.y; }) -
      mesh.positions.begin());
  EXPECT_GT(glm::length(posedA.positions[top] - mesh.positions[top]), 0.3f);
  EXPECT_GT(glm::length(posedA.positions[top] - posedB.positions[top]), 0.5f);
  const float footY = mesh.positions[0].y;  // the lowest ring, standing on the plinth
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (mesh.positions[v].y != footY) continue;
    EXPECT_LE(glm::length(posedA.positions[v] - mesh.positions[v]), 1e-5f) << "vertex " << v;
    EXPECT_LE(glm::length(posedB.positions[v] - mesh.positions[v]), 1e-5f) << "vertex " << v;
  }
}

// The tip joint's CUBICSPLINE keys (every half second, with the sine's own derivative as tangents) follow
// 40 degrees * sin(4 pi t / 4 s) between the keys, where straight lines between them would be 8 degrees off.
TEST(BuiltinScene, TheCubicSplineFollowsTheSineBetweenItsKeys) {
  const Scene scene = makeBuiltinScene(BuiltinSceneOptions::withMotion());
  const size_t middle = static_cast<size_t>(nodeNamed(scene, "limb middle"));
  const size_t tip = static_cast<size_t>(nodeNamed(scene, "limb tip"));
  for (double t : {0.25, 0.6, 1.3, 2.75, 3.9}) {
    const ScenePose pose = evaluatePose(scene, t, playing(scene));
    const glm::mat4 local = glm::inverse(pose.nodeWorld[middle]) * pose.nodeWorld[tip];
    const double expected = 40.0 * std::sin(2.0 * 2.0 * glm::pi<double>() * t / kBuiltinMotionSeconds);
    EXPECT_NEAR(zDegrees(local), expected, 1.0) << "at " << t << " s";
  }
}

// Over the whole loop the limb stays above the plinth it stands on and the bob clears the floor and the piers.
TEST(BuiltinScene, NothingPassesThroughTheRoom) {
  const Scene scene = makeBuiltinScene(BuiltinSceneOptions::withMotion());
  const Instance& limb = limbInstance(scene);
  const Mesh& mesh = scene.meshes[static_cast<size_t>(limb.mesh)];
  const float footY = mesh.positions[0].y;
  const size_t bob = static_cast<size_t>(nodeNamed(scene, "pendulum bob"));
  const size_t ball = static_cast<size_t>(
      std::find_if(scene.instances.begin(), scene.instances.end(),
                   [&](const Instance& i) { return i.node == static_cast<int>(bob); }) -
      scene.instances.begin());
  ASSERT_LT(ball, scene.instances.size());
  const Mesh& ballMesh = scene.meshes[static_cast<size_t>(scene.instances[ball].mesh)];
  for (int step = 0; step <= 80; ++step) {
    const double t = double(kBuiltinMotionSeconds) * step / 80.0;
    const ScenePose pose = evaluatePose(scene, t, playing(scene));
    const PosedVertices posed = posedMesh(mesh, pose.skinJoints[0], {});
    float lowest = 1e30f;
    for (const glm::vec3& p : posed.positions) lowest = std::min(lowest, p.y);
    EXPECT_GE(lowest, footY - 1e-4f) << "the limb at " << t << " s";
    float bobLowest = 1e30f, bobWidest = 0.0f;
    for (const glm::vec3& p : ballMesh.positions) {
      const glm::vec3 world(pose.instanceWorld[ball] * glm::vec4(p, 1.0f));
      bobLowest = std::min(bobLowest, world.y);
      bobWidest = std::max(bobWidest, std::abs(world.x));
    }
    EXPECT_GT(bobLowest, 0.04f) << "the bob above the floor at " << t << " s";
    EXPECT_LT(bobWidest, 1.25f) << "the bob inside the arch's opening (piers from |x| = 1.3 m) at " << t << " s";
  }
}
