#include "scene/Animation.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "base/Error.h"

namespace obscura {
namespace {

bool isIndex(const std::string& text) {
  return !text.empty() && text.size() < 10 && std::all_of(text.begin(), text.end(), [](char c) {
    return c >= '0' && c <= '9';
  });
}

std::string animationList(const Scene& scene) {
  if (scene.animations.empty()) return "the scene has no animations (choices: none, all)";
  std::string list = "choices: none, all";
  for (size_t i = 0; i < scene.animations.size(); ++i) {
    list += ", " + std::to_string(i);
    if (!scene.animations[i].name.empty()) list += " '" + scene.animations[i].name + "'";
  }
  return list;
}

// Key k's value: CUBICSPLINE keys store (in-tangent, value, out-tangent), glTF 2.0 "Animations", "Interpolation".
const float* keyValue(const AnimationSampler& s, size_t key) {
  const size_t c = static_cast<size_t>(s.components);
  return s.values.data() + (s.interpolation == Interpolation::CubicSpline ? (3 * key + 1) * c : key * c);
}

}  // namespace

AnimationChoice parseAnimationChoice(const Scene& scene, const std::string& text) {
  if (text == "none") return AnimationChoice::none();
  if (text == "all") return AnimationChoice::all();
  if (isIndex(text)) {
    const long index = std::stol(text);
    if (index < static_cast<long>(scene.animations.size())) return AnimationChoice::one(static_cast<int>(index));
    throw InputError("animation " + text + " is not in the scene; " + animationList(scene));
  }
  for (size_t i = 0; i < scene.animations.size(); ++i)
    if (scene.animations[i].name == text) return AnimationChoice::one(static_cast<int>(i));
  throw InputError("animation '" + text + "' is not in the scene; " + animationList(scene));
}

std::string animationChoiceName(const Scene& scene, const AnimationChoice& choice) {
  switch (choice.kind) {
    case AnimationChoice::Kind::None: return "none";
    case AnimationChoice::Kind::All: return "all";
    case AnimationChoice::Kind::One: break;
  }
  if (choice.index < 0 || static_cast<size_t>(choice.index) >= scene.animations.size())
    return std::to_string(choice.index);
  const std::string& name = scene.animations[static_cast<size_t>(choice.index)].name;
  const bool unique = !name.empty() && !isIndex(name) && name != "none" && name != "all" &&
                      std::count_if(scene.animations.begin(), scene.animations.end(),
                                    [&](const Animation& a) { return a.name == name; }) == 1;
  return unique ? name : std::to_string(choice.index);
}

double animationDuration(const Scene& scene, const AnimationChoice& choice) {
  switch (choice.kind) {
    case AnimationChoice::Kind::None: return 0.0;
    case AnimationChoice::Kind::One:
      return choice.index >= 0 && static_cast<size_t>(choice.index) < scene.animations.size()
                 ? scene.animations[static_cast<size_t>(choice.index)].duration()
                 : 0.0;
    case AnimationChoice::Kind::All: break;
  }
  double longest = 0.0;
  for (const Animation& animation : scene.animations) longest = std::max(longest, double(animation.duration()));
  return longest;
}

std::vector<float> sampleAnimation(const AnimationSampler& s, float t, bool rotation) {
  const size_t c = static_cast<size_t>(s.components);
  const size_t keys = s.times.size();
  std::vector<float> out(c);
  auto copyKey = [&](size_t key) {
    const float* v = keyValue(s, key);
    std::copy(v, v + c, out.begin());
  };
  // Clamp outside the keys (glTF 2.0: "before the first key, the first value; after the last, the last"); a time
  // that is not a number is taken as the first key's.
  if (keys == 1 || !(t > s.times.front())) {
    copyKey(0);
  } else if (t >= s.times.back()) {
    copyKey(keys - 1);
  } else {
    const size_t k1 = static_cast<size_t>(std::upper_bound(s.times.begin(), s.times.end(), t) - s.times.begin());
    const size_t k0 = k1 - 1;
    const float t0 = s.times[k0], interval = s.times[k1] - t0;
    const float u = (t - t0) / interval;
    const float* a = keyValue(s, k0);
    const float* b = keyValue(s, k1);
    switch (s.interpolation) {
      case Interpolation::Step: copyKey(k0); break;
      case Interpolation::Linear:
        if (rotation) {
          // Spherical linear interpolation along the shorter arc (glTF 2.0 Appendix C): q and -q are one rotation.
          const glm::quat qa(a[3], a[0], a[1], a[2]), qb(b[3], b[0], b[1], b[2]);
          const glm::quat q = glm::slerp(qa, glm::dot(qa, qb) < 0.0f ? -qb : qb, u);
          out = {q.x, q.y, q.z, q.w};
        } else {
          for (size_t i = 0; i < c; ++i) out[i] = a[i] + (b[i] - a[i]) * u;
        }
        break;
      case Interpolation::CubicSpline: {
        // Hermite basis of glTF 2.0 Appendix C: tangents are per second, so scaled by the key interval.
        const float u2 = u * u, u3 = u2 * u;
        const float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
        const float* outTangentA = a + c;  // key k0's out-tangent follows its value
        const float* inTangentB = b - c;   // key k1's in-tangent precedes its value
        for (size_t i = 0; i < c; ++i)
          out[i] = h00 * a[i] + h10 * interval * outTangentA[i] + h01 * b[i] + h11 * interval * inTangentB[i];
        break;
      }
    }
  }
  if (rotation) {
    const glm::vec4 q = glm::vec4(out[0], out[1], out[2], out[3]);
    const float length = glm::length(q);
    const glm::vec4 n = length > 0.0f ? q / length : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    out = {n.x, n.y, n.z, n.w};
  }
  return out;
}

std::vector<bool> movingNodes(const Scene& scene) {
  std::vector<bool> moving(scene.nodes.size(), false);
  for (const Animation& animation : scene.animations)
    for (const AnimationChannel& channel : animation.channels)
      if (channel.path != AnimationPath::Weights) moving[static_cast<size_t>(channel.node)] = true;
  // Parents precede their children in Scene::nodes.
  for (size_t n = 0; n < scene.nodes.size(); ++n)
    if (const int parent = scene.nodes[n].parent; parent >= 0 && moving[static_cast<size_t>(parent)]) moving[n] = true;
  return moving;
}

ScenePose evaluatePose(const Scene& scene, double time, const PoseOptions& options) {
  ScenePose pose;
  const size_t nodeCount = scene.nodes.size();

  // Local transforms: the rest pose, overridden by the chosen animations' channels.
  std::vector<glm::vec3> translation(nodeCount), scale(nodeCount);
  std::vector<glm::quat> rotation(nodeCount);
  std::vector<bool> animatedTrs(nodeCount, false);
  pose.nodeWeights.resize(nodeCount);
  for (size_t n = 0; n < nodeCount; ++n) {
    translation[n] = scene.nodes[n].translation;
    rotation[n] = scene.nodes[n].rotation;
    scale[n] = scene.nodes[n].scale;
    pose.nodeWeights[n] = scene.nodes[n].weights;
  }

  std::vector<const Animation*> playing;
  if (options.animation.kind == AnimationChoice::Kind::All) {
    for (const Animation& animation : scene.animations) playing.push_back(&animation);
  } else if (options.animation.kind == AnimationChoice::Kind::One && options.animation.index >= 0 &&
             static_cast<size_t>(options.animation.index) < scene.animations.size()) {
    playing.push_back(&scene.animations[static_cast<size_t>(options.animation.index)]);
  }
  // The timeline: times before 0 clamp to the first keys (no wrap backwards, so the frame before time 0 is the
  // rest of the first key, not the end of the loop); from 0 on, a looping timeline wraps at the duration.
  const double duration = animationDuration(scene, options.animation);
  double t = std::isfinite(time) ? time : 0.0;
  if (options.loop && duration > 0.0 && t >= duration) t = std::fmod(t, duration);
  for (const Animation* animation : playing) {
    for (const AnimationChannel& channel : animation->channels) {
      const AnimationSampler& sampler = animation->samplers[static_cast<size_t>(channel.sampler)];
      const size_t n = static_cast<size_t>(channel.node);
      const std::vector<float> v =
          sampleAnimation(sampler, static_cast<float>(t), channel.path == AnimationPath::Rotation);
      switch (channel.path) {
        case AnimationPath::Translation: translation[n] = glm::vec3(v[0], v[1], v[2]); break;
        case AnimationPath::Rotation: rotation[n] = glm::quat(v[3], v[0], v[1], v[2]); break;
        case AnimationPath::Scale: scale[n] = glm::vec3(v[0], v[1], v[2]); break;
        case AnimationPath::Weights: pose.nodeWeights[n] = v; break;
      }
      if (channel.path != AnimationPath::Weights) animatedTrs[n] = true;
    }
  }

  // World transforms: parents precede their children in Scene::nodes.
  pose.nodeWorld.resize(nodeCount);
  for (size_t n = 0; n < nodeCount; ++n) {
    const Node& node = scene.nodes[n];
    const glm::mat4 local =
        node.hasMatrix && !animatedTrs[n]
            ? node.matrix
            : glm::translate(glm::mat4(1.0f), translation[n]) * glm::mat4_cast(rotation[n]) *
                  glm::scale(glm::mat4(1.0f), scale[n]);
    pose.nodeWorld[n] = node.parent >= 0 ? pose.nodeWorld[static_cast<size_t>(node.parent)] * local : local;
  }

  pose.skinJoints.resize(scene.skins.size());
  for (size_t s = 0; s < scene.skins.size(); ++s) {
    const Skin& skin = scene.skins[s];
    pose.skinJoints[s].resize(skin.joints.size());
    for (size_t j = 0; j < skin.joints.size(); ++j)
      pose.skinJoints[s][j] = pose.nodeWorld[static_cast<size_t>(skin.joints[j])] * skin.inverseBind[j];
  }

  pose.instanceWorld.resize(scene.instances.size());
  pose.instanceWeights.resize(scene.instances.size());
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    // A skinned mesh's vertices reach world space through its joints alone; its node's transform is ignored
    // (glTF 2.0 "Skins": "only the joint transforms are applied").
    if (instance.skin >= 0 && mesh.skinned()) pose.instanceWorld[i] = glm::mat4(1.0f);
    else if (instance.node >= 0) pose.instanceWorld[i] = pose.nodeWorld[static_cast<size_t>(instance.node)];
    else pose.instanceWorld[i] = instance.world;
    if (!mesh.morphTargets.empty()) {
      std::vector<float> weights =
          instance.node >= 0 ? pose.nodeWeights[static_cast<size_t>(instance.node)] : std::vector<float>{};
      weights.resize(mesh.morphTargets.size(), 0.0f);
      pose.instanceWeights[i] = std::move(weights);
    }
  }
  return pose;
}

PosedVertices posedMesh(const Mesh& mesh, const std::vector<glm::mat4>& joints, const std::vector<float>& weights) {
  PosedVertices out{mesh.positions, mesh.normals, mesh.tangents};
  // Morph first (glTF 2.0 "Morph Targets": the displaced attributes are then skinned).
  for (size_t t = 0; t < mesh.morphTargets.size() && t < weights.size(); ++t) {
    const float w = weights[t];
    if (w == 0.0f) continue;
    const MorphTarget& target = mesh.morphTargets[t];
    for (size_t v = 0; v < out.positions.size(); ++v) out.positions[v] += w * target.positions[v];
    if (!target.normals.empty())
      for (size_t v = 0; v < out.normals.size(); ++v) out.normals[v] += w * target.normals[v];
    if (!target.tangents.empty() && !out.tangents.empty())
      for (size_t v = 0; v < out.tangents.size(); ++v) out.tangents[v] += glm::vec4(w * target.tangents[v], 0.0f);
  }
  if (mesh.skinned() && !joints.empty()) {
    for (size_t v = 0; v < out.positions.size(); ++v) {
      glm::mat4 m(0.0f);
      for (int k = 0; k < 4; ++k)
        if (mesh.weights[v][k] != 0.0f) m += mesh.weights[v][k] * joints[mesh.joints[v][k]];
      out.positions[v] = glm::vec3(m * glm::vec4(out.positions[v], 1.0f));
      // The blended matrix's linear part, not its inverse transpose: exact for rotations and uniform scale, and
      // what the vertex stage does (geometry.vert), so that the CPU mirror and the GPU agree.
      const glm::mat3 linear(m);
      out.normals[v] = linear * out.normals[v];
      if (!out.tangents.empty()) {
        // A mirroring joint (negative determinant) reverses the bitangent's cross product: w turns with it.
        const float handedness = glm::determinant(linear) < 0.0f ? -1.0f : 1.0f;
        out.tangents[v] = glm::vec4(linear * glm::vec3(out.tangents[v]), out.tangents[v].w * handedness);
      }
    }
  }
  for (glm::vec3& n : out.normals) {
    const float length = glm::length(n);
    n = length > 0.0f ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  for (glm::vec4& t : out.tangents) {
    const float length = glm::length(glm::vec3(t));
    if (length > 0.0f) t = glm::vec4(glm::vec3(t) / length, t.w);
  }
  return out;
}

Scene posedScene(const Scene& scene, const ScenePose& pose) {
  Scene out;
  out.name = scene.name;
  out.materials = scene.materials;
  out.textures = scene.textures;
  out.images = scene.images;
  out.designedAoRadius = scene.designedAoRadius;
  std::map<int, int> rigidMeshes;  // scene mesh -> out mesh, for instances the pose does not deform
  static const std::vector<glm::mat4> kNoJoints;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    const bool skinned = instance.skin >= 0 && mesh.skinned();
    const std::vector<float>& weights = pose.instanceWeights[i];
    const bool morphed = std::any_of(weights.begin(), weights.end(), [](float w) { return w != 0.0f; });
    Instance placed;
    placed.world = pose.instanceWorld[i];
    if (skinned || morphed) {
      Mesh baked = mesh;
      const PosedVertices posed =
          posedMesh(mesh, skinned ? pose.skinJoints[static_cast<size_t>(instance.skin)] : kNoJoints, weights);
      baked.positions = posed.positions;
      baked.normals = posed.normals;
      baked.tangents = posed.tangents;
      baked.joints.clear();
      baked.weights.clear();
      baked.morphTargets.clear();
      placed.mesh = static_cast<int>(out.meshes.size());
      out.meshes.push_back(std::move(baked));
    } else {
      auto found = rigidMeshes.find(instance.mesh);
      if (found == rigidMeshes.end()) {
        Mesh copy = mesh;
        copy.joints.clear();
        copy.weights.clear();
        copy.morphTargets.clear();
        found = rigidMeshes.emplace(instance.mesh, static_cast<int>(out.meshes.size())).first;
        out.meshes.push_back(std::move(copy));
      }
      placed.mesh = found->second;
    }
    out.instances.push_back(placed);
  }
  return out;
}

}  // namespace obscura
