#include <algorithm>
#include <cmath>
#include <map>

#include "scene/GltfReading.h"

namespace obscura::gltf {
namespace {

// The file's animations, their channels on the Scene nodes the node reader collected.
class AnimationReader {
 public:
  AnimationReader(const LoaderContext& ctx, const std::vector<std::vector<int>>& copies, Scene& scene)
      : ctx_(ctx), model_(ctx.model), scene_(scene), copies_(copies) {}

  void read() {
    for (size_t a = 0; a < model_.animations.size(); ++a) {
      const tinygltf::Animation& source = model_.animations[a];
      const std::string what = "animation " + std::to_string(a);
      Animation animation;
      animation.name = source.name;
      struct LoadedSampler {
        int index;
        AnimationPath path;
        int components;
      };
      std::map<int, LoadedSampler> samplers;           // by glTF sampler
      std::map<std::pair<int, std::string>, size_t> targets;  // (node, path) -> the first channel on it
      int outsideHierarchy = 0, unknownPath = 0, withoutNode = 0;
      for (size_t c = 0; c < source.channels.size(); ++c) {
        const tinygltf::AnimationChannel& channel = source.channels[c];
        const std::string channelWhat = what + " channel " + std::to_string(c);
        if (channel.target_node < 0) {
          ++withoutNode;
          continue;
        }
        if (static_cast<size_t>(channel.target_node) >= model_.nodes.size())
          ctx_.refuse(channelWhat + " targets node " + std::to_string(channel.target_node) + ", which does not exist");
        AnimationPath path;
        if (channel.target_path == "translation") path = AnimationPath::Translation;
        else if (channel.target_path == "rotation") path = AnimationPath::Rotation;
        else if (channel.target_path == "scale") path = AnimationPath::Scale;
        else if (channel.target_path == "weights") path = AnimationPath::Weights;
        else {
          ++unknownPath;
          continue;
        }
        if (channel.sampler < 0 || static_cast<size_t>(channel.sampler) >= source.samplers.size())
          ctx_.refuse(channelWhat + " refers to sampler " + std::to_string(channel.sampler) +
                      ", which does not exist");
        // glTF 2.0 sec. 5.5: "Within one animation, each target ... MUST NOT be used more than once."
        const auto target = std::make_pair(channel.target_node, channel.target_path);
        if (targets.count(target))
          ctx_.refuse(channelWhat + " animates node " + std::to_string(channel.target_node) + " " +
                      channel.target_path + ", as channel " + std::to_string(targets[target]) + " does");
        targets[target] = c;
        const std::vector<int>& copies = copies_[static_cast<size_t>(channel.target_node)];
        if (copies.empty()) {
          ++outsideHierarchy;
          continue;
        }
        // glTF 2.0 sec. 3.5.2: a node targeted by an animation has TRS, never a matrix.
        if (scene_.nodes[static_cast<size_t>(copies.front())].hasMatrix)
          ctx_.refuse(channelWhat + " animates node " + std::to_string(channel.target_node) +
                      ", which has a matrix (glTF allows animating only TRS nodes)");
        int components = path == AnimationPath::Rotation ? 4 : 3;
        if (path == AnimationPath::Weights) {
          components = static_cast<int>(scene_.nodes[static_cast<size_t>(copies.front())].weights.size());
          if (components == 0)
            ctx_.refuse(channelWhat + " animates the weights of node " + std::to_string(channel.target_node) +
                        ", which has no morph targets");
        }
        auto loaded = samplers.find(channel.sampler);
        if (loaded == samplers.end()) {
          animation.samplers.push_back(loadSampler(static_cast<int>(a), channel.sampler, path, components));
          loaded = samplers
                       .emplace(channel.sampler,
                                LoadedSampler{static_cast<int>(animation.samplers.size()) - 1, path, components})
                       .first;
        } else if (loaded->second.components != components ||
                   (loaded->second.path == AnimationPath::Rotation) != (path == AnimationPath::Rotation)) {
          ctx_.refuse(channelWhat + " shares sampler " + std::to_string(channel.sampler) +
                      " with a channel that needs other values");
        }
        for (int node : copies) animation.channels.push_back({loaded->second.index, node, path});
      }
      if (outsideHierarchy > 0)
        ctx_.report.warnings.push_back(what + ": " + std::to_string(outsideHierarchy) +
                                       " channels target nodes outside the default scene; skipped");
      if (unknownPath > 0)
        ctx_.report.warnings.push_back(what + ": " + std::to_string(unknownPath) +
                                       " channels have a path other than translation, rotation, scale or weights; "
                                       "skipped");
      if (withoutNode > 0)
        ctx_.report.warnings.push_back(what + ": " + std::to_string(withoutNode) +
                                       " channels have no target node; skipped");
      scene_.animations.push_back(std::move(animation));
    }
  }

 private:
  // Reads a sampler for a channel of `path` with `components` values per key (glTF 2.0 sec. 3.11, 5.6):
  // input float SCALAR times, finite and strictly increasing; output float VEC3 (translation, scale), VEC4 float
  // or normalised integers (rotation), SCALAR float or normalised integers (weights, one per morph target per key).
  AnimationSampler loadSampler(int animationIndex, int samplerIndex, AnimationPath path, int components) {
    const tinygltf::AnimationSampler& source =
        model_.animations[static_cast<size_t>(animationIndex)].samplers[static_cast<size_t>(samplerIndex)];
    const std::string what = "animation " + std::to_string(animationIndex) + " sampler " + std::to_string(samplerIndex);
    AnimationSampler sampler;
    sampler.components = components;
    if (source.interpolation == "LINEAR") sampler.interpolation = Interpolation::Linear;
    else if (source.interpolation == "STEP") sampler.interpolation = Interpolation::Step;
    else if (source.interpolation == "CUBICSPLINE") sampler.interpolation = Interpolation::CubicSpline;
    else ctx_.refuse(what + " has interpolation '" + source.interpolation + "', not LINEAR, STEP or CUBICSPLINE");

    // The budget is charged from the accessors' declared counts before reading them (readAccessor checks bounds).
    for (int accessor : {source.input, source.output}) {
      if (accessor < 0 || static_cast<size_t>(accessor) >= model_.accessors.size())
        ctx_.refuse(what + " refers to accessor " + std::to_string(accessor) + ", which does not exist");
      const tinygltf::Accessor& a = model_.accessors[static_cast<size_t>(accessor)];
      ctx_.budget.animationValues += std::uint64_t(a.count) * std::max(componentCount(a.type), 1);
    }
    if (ctx_.budget.animationValues > ctx_.limits.maxAnimationValues)
      ctx_.refuse(what + ": more than " + std::to_string(ctx_.limits.maxAnimationValues) +
                  " animation values in the scene");

    const std::vector<double> times = readAccessor(ctx_, source.input, what + " input", 1,
                                                   {TINYGLTF_COMPONENT_TYPE_FLOAT});
    if (times.empty()) ctx_.refuse(what + " input has no key times");
    for (size_t k = 0; k < times.size(); ++k) {
      if (!std::isfinite(times[k])) ctx_.refuse(what + " input time " + std::to_string(k) + " is not finite");
      if (k > 0 && !(times[k] > times[k - 1]))
        ctx_.refuse(what + " input time " + std::to_string(k) + " (" + std::to_string(times[k]) +
                    ") is not after the one before (" + std::to_string(times[k - 1]) + ")");
    }
    if (times.front() < 0.0)
      ctx_.report.warnings.push_back(what + " starts at " + std::to_string(times.front()) +
                                     " s (glTF requires times >= 0); what comes before 0 never plays");

    const bool vector = path != AnimationPath::Weights;
    std::vector<int> allowed = {TINYGLTF_COMPONENT_TYPE_FLOAT};
    if (path == AnimationPath::Rotation || path == AnimationPath::Weights)
      allowed.insert(allowed.end(), {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                     TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
    const std::vector<double> values =
        readAccessor(ctx_, source.output, what + " output", vector ? components : 1, allowed);
    const tinygltf::Accessor& output = model_.accessors[static_cast<size_t>(source.output)];
    if (output.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !output.normalized)
      ctx_.refuse(what + " output (accessor " + std::to_string(source.output) + ") has component type " +
                  componentTypeName(output.componentType) + " without normalized: true, which glTF does not allow");
    const int perKey = sampler.interpolation == Interpolation::CubicSpline ? 3 : 1;
    const std::uint64_t expected = std::uint64_t(times.size()) * perKey * std::uint64_t(components);
    if (values.size() != expected)
      ctx_.refuse(what + " has " + std::to_string(vector ? values.size() / components : values.size()) +
                  " output values for " + std::to_string(times.size()) + " key times (expected " +
                  std::to_string(vector ? expected / components : expected) + ": " +
                  (perKey == 3 ? "3 per key for CUBICSPLINE" : "1 per key") +
                  (vector ? "" : ", times " + std::to_string(components) + " morph targets") + ")");
    if (!allFinite(values)) ctx_.refuse(what + " output has a value that is not finite");
    if (path == AnimationPath::Rotation) {
      // Key rotations (not CUBICSPLINE tangents) must be quaternions a slerp can normalise.
      for (size_t k = 0; k < times.size(); ++k) {
        const size_t at = (k * perKey + (perKey == 3 ? 1 : 0)) * 4;
        const double length = std::sqrt(values[at] * values[at] + values[at + 1] * values[at + 1] +
                                        values[at + 2] * values[at + 2] + values[at + 3] * values[at + 3]);
        if (length < 1e-6) ctx_.refuse(what + " output rotation " + std::to_string(k) + " is a zero quaternion");
      }
    }
    sampler.times.assign(times.begin(), times.end());
    sampler.values.assign(values.begin(), values.end());
    return sampler;
  }

  const LoaderContext& ctx_;
  const tinygltf::Model& model_;
  Scene& scene_;
  const std::vector<std::vector<int>>& copies_;  // per glTF node: its Scene::nodes indices
};

}  // namespace

void loadAnimations(const LoaderContext& ctx, const std::vector<std::vector<int>>& copies, Scene& scene) {
  AnimationReader(ctx, copies, scene).read();
}

}  // namespace obscura::gltf
