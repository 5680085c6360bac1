#pragma once
// Sampling glTF animations and posing a scene: which animation plays (AnimationChoice), every node's local and world
// transform, every skin's joint matrices and every node's morph weights at a time (ScenePose), and the CPU mirror of
// skinning and morphing (posedMesh, posedScene) that the CPU fallback, the reference tracer and the tests use.
//
// Timeline rules (glTF 2.0, "Animations"): a time before a sampler's first key takes the first key's value, after
// its last key the last key's; with `loop`, the timeline wraps at the chosen animations' duration. LINEAR rotations
// are slerped along the shorter arc; CUBICSPLINE is the Hermite spline of the spec with tangents scaled by the key
// interval, and its rotations are normalised afterwards.
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>

#include "scene/Scene.h"

namespace obscura {

// Which animations drive the pose: none (the rest pose: the still scene), one by index, or all together.
struct AnimationChoice {
  enum class Kind { None, One, All } kind = Kind::One;
  int index = 0;  // Kind::One: index into Scene::animations (a scene without animations poses at rest)

  static AnimationChoice none() { return {Kind::None, 0}; }
  static AnimationChoice one(int index) { return {Kind::One, index}; }
  static AnimationChoice all() { return {Kind::All, 0}; }
  bool operator==(const AnimationChoice& o) const { return kind == o.kind && index == o.index; }
};

// "none", "all", an index ("0") or an animation's name. Throws InputError listing the scene's animations.
AnimationChoice parseAnimationChoice(const Scene& scene, const std::string& text);
// The inverse: "none", "all", or the animation's name (its index where it has none or shares it).
std::string animationChoiceName(const Scene& scene, const AnimationChoice& choice);
// The timeline's length in seconds for the choice (the longest chosen animation; 0 when nothing plays).
double animationDuration(const Scene& scene, const AnimationChoice& choice);

// One sampler's value at time t (clamped to its keys), `components` floats; rotations come out normalised.
std::vector<float> sampleAnimation(const AnimationSampler& sampler, float t, bool rotation);

struct ScenePose {
  std::vector<glm::mat4> nodeWorld;               // per node
  std::vector<std::vector<float>> nodeWeights;    // per node: its morph weights (the rest weights where unanimated)
  // Per skin, per joint: world(joint) * inverseBind(joint), which takes a bind-pose vertex to world space.
  std::vector<std::vector<glm::mat4>> skinJoints;
  // Per scene instance: its world matrix (identity for a skinned instance, whose joints place it) and its morph
  // weights (empty for a mesh without targets).
  std::vector<glm::mat4> instanceWorld;
  std::vector<std::vector<float>> instanceWeights;
};

struct PoseOptions {
  AnimationChoice animation;
  bool loop = true;
};

// The pose at `time` seconds. A scene without nodes gives each instance its fixed world matrix.
ScenePose evaluatePose(const Scene& scene, double time, const PoseOptions& options = {});

// Per node: whether some animation's translation, rotation or scale channel moves it or one of its ancestors (its
// world matrix may then differ from its rest one in some pose; morph weights do not move a node).
std::vector<bool> movingNodes(const Scene& scene);

// The CPU mirror of the vertex stage's skinning and morphing: a mesh's positions and normals (normals renormalised)
// in its instance's posed space, i.e. world space for a skinned mesh (then apply no instance matrix) and the mesh's
// local space otherwise. `joints` is the skin's ScenePose::skinJoints entry (ignored for an unskinned mesh).
struct PosedVertices {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec4> tangents;  // empty where the mesh has none; w turned by a mirroring joint
};
PosedVertices posedMesh(const Mesh& mesh, const std::vector<glm::mat4>& joints, const std::vector<float>& weights);

// A still scene of the pose: skinned and morphed meshes baked, every instance at its posed world matrix, no nodes,
// skins or animations (for the reference tracer, bounds and tests).
Scene posedScene(const Scene& scene, const ScenePose& pose);

}  // namespace obscura
