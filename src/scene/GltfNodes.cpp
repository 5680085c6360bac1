#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "scene/GltfReading.h"

namespace obscura::gltf {
namespace {

// A node's rest transform, checked: a matrix of 16 finite numbers, or finite TRS with a non-zero rotation (kept
// normalised). A node with both keeps the matrix, as before nodes were kept.
Node readNode(const LoaderContext& ctx, const tinygltf::Node& source, int index) {
  const std::string what = "node " + std::to_string(index);
  Node node;
  node.name = source.name;
  if (source.matrix.size() == 16) {
    if (!allFinite(source.matrix)) ctx.refuse(what + " has a non-finite matrix");
    node.hasMatrix = true;
    for (int i = 0; i < 16; ++i)
      glm::value_ptr(node.matrix)[i] = static_cast<float>(source.matrix[static_cast<size_t>(i)]);
    return node;
  }
  if (!source.matrix.empty())
    ctx.refuse(what + " has a matrix of " + std::to_string(source.matrix.size()) + " numbers, expected 16");
  if (!source.translation.empty()) {
    if (source.translation.size() != 3 || !allFinite(source.translation))
      ctx.refuse(what + " has an invalid translation");
    node.translation = glm::vec3(source.translation[0], source.translation[1], source.translation[2]);
  }
  if (!source.rotation.empty()) {
    if (source.rotation.size() != 4 || !allFinite(source.rotation)) ctx.refuse(what + " has an invalid rotation");
    const glm::quat q(static_cast<float>(source.rotation[3]), static_cast<float>(source.rotation[0]),
                      static_cast<float>(source.rotation[1]), static_cast<float>(source.rotation[2]));
    const float length = glm::length(q);
    if (length < 1e-6f) ctx.refuse(what + " has a zero rotation quaternion");
    node.rotation = q / length;
  }
  if (!source.scale.empty()) {
    if (source.scale.size() != 3 || !allFinite(source.scale)) ctx.refuse(what + " has an invalid scale");
    node.scale = glm::vec3(source.scale[0], source.scale[1], source.scale[2]);
  }
  return node;
}

// The default scene's nodes, meshes, skins and lights, as Scene data. Nodes are collected first (parents before
// children), then every node's mesh is placed, loading each skin it needs.
class NodeReader {
 public:
  NodeReader(const LoaderContext& ctx, Scene& scene)
      : ctx_(ctx), model_(ctx.model), scene_(scene), copies_(ctx.model.nodes.size()) {}

  std::vector<std::vector<int>> read() && {
    for (int root : roots()) visit(root, -1);
    placeInstances();
    return std::move(copies_);
  }

 private:
  std::vector<int> roots() const {
    if (!model_.scenes.empty()) {
      const int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (static_cast<size_t>(sceneIndex) >= model_.scenes.size())
        ctx_.refuse("default scene " + std::to_string(sceneIndex) + " does not exist");
      return model_.scenes[static_cast<size_t>(sceneIndex)].nodes;
    }
    // No scene: show every node that is nobody's child.
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes)
      for (int child : node.children)
        if (child >= 0 && static_cast<size_t>(child) < isChild.size()) isChild[static_cast<size_t>(child)] = true;
    std::vector<int> out;
    for (size_t i = 0; i < model_.nodes.size(); ++i)
      if (!isChild[i]) out.push_back(static_cast<int>(i));
    return out;
  }

  // Depth first, so that a node's parent is always collected before it (Node::parent is lower than its index).
  void visit(int nodeIndex, int parent) {
    if (nodeIndex < 0 || static_cast<size_t>(nodeIndex) >= model_.nodes.size())
      ctx_.refuse("node " + std::to_string(nodeIndex) + " is referenced but does not exist");
    if (std::find(path_.begin(), path_.end(), nodeIndex) != path_.end())
      ctx_.refuse("node hierarchy has a cycle through node " + std::to_string(nodeIndex));
    if (static_cast<int>(path_.size()) >= ctx_.limits.maxNodeDepth)
      ctx_.refuse("node hierarchy is deeper than " + std::to_string(ctx_.limits.maxNodeDepth) + " levels");
    if (scene_.nodes.size() >= ctx_.limits.maxNodes)
      ctx_.refuse("has more than " + std::to_string(ctx_.limits.maxNodes) + " nodes in its hierarchy");
    const tinygltf::Node& source = model_.nodes[static_cast<size_t>(nodeIndex)];
    Node node = readNode(ctx_, source, nodeIndex);
    node.parent = parent;
    if (source.mesh >= 0) {
      if (static_cast<size_t>(source.mesh) >= model_.meshes.size())
        ctx_.refuse("node " + std::to_string(nodeIndex) + " refers to mesh " + std::to_string(source.mesh) +
                    ", which does not exist");
      node.weights = restWeights(source, nodeIndex);
    }
    // glTF 2.0 (sec. 3.5.3) requires disjoint trees; a node under two parents has been drawn twice since before
    // nodes were kept, so it still is: one Scene node per path.
    if (!copies_[static_cast<size_t>(nodeIndex)].empty() && !warnedSharedNode_) {
      warnedSharedNode_ = true;
      ctx_.report.warnings.push_back("node " + std::to_string(nodeIndex) +
                                     " has more than one parent (glTF requires disjoint trees); each path gets a copy");
    }
    const int index = static_cast<int>(scene_.nodes.size());
    restWorld_.push_back((parent >= 0 ? restWorld_[static_cast<size_t>(parent)] : glm::mat4(1.0f)) * node.localRest());
    addLight(source, nodeIndex, index);
    addCamera(source, nodeIndex, index, node.name);
    scene_.nodes.push_back(std::move(node));
    sourceNode_.push_back(nodeIndex);
    copies_[static_cast<size_t>(nodeIndex)].push_back(index);
    path_.push_back(nodeIndex);
    for (int child : source.children) visit(child, index);
    path_.pop_back();
  }

  // KHR_lights_punctual: the node's point, spot or directional light. A directional light shines along the node's
  // -z with its intensity in lux; the renderer's sun stays beside it (lighting.sun: file takes the first instead).
  void addLight(const tinygltf::Node& source, int nodeIndex, int index) {
    const auto it = source.extensions.find("KHR_lights_punctual");
    if (it == source.extensions.end() || !it->second.IsObject() || !it->second.Has("light")) return;
    const tinygltf::Value& reference = it->second.Get("light");
    const int lightIndex = reference.IsInt() ? reference.GetNumberAsInt() : -1;
    if (lightIndex < 0 || static_cast<size_t>(lightIndex) >= model_.lights.size())
      ctx_.refuse("node " + std::to_string(nodeIndex) + " refers to light " + std::to_string(lightIndex) +
                  ", which does not exist");
    const tinygltf::Light& light = model_.lights[static_cast<size_t>(lightIndex)];
    const std::string what = "light " + std::to_string(lightIndex);
    if (light.type != "point" && light.type != "spot" && light.type != "directional")
      ctx_.refuse(what + " has unknown type '" + light.type + "'");
    PunctualLight out;
    out.type = light.type == "spot" ? LightType::Spot
               : light.type == "directional" ? LightType::Directional
                                             : LightType::Point;
    if (light.color.size() == 3 && allFinite(light.color))
      out.color = glm::max(glm::vec3(light.color[0], light.color[1], light.color[2]), glm::vec3(0.0f));
    if (!std::isfinite(light.intensity) || light.intensity < 0.0 || !std::isfinite(light.range) || light.range < 0.0)
      ctx_.refuse(what + " has a negative or non-finite intensity or range");
    out.intensity = static_cast<float>(light.intensity);
    out.range = out.type == LightType::Directional ? 0.0f : static_cast<float>(light.range);
    const double inner = light.spot.innerConeAngle, outer = light.spot.outerConeAngle;
    if (out.type == LightType::Spot &&
        !(std::isfinite(inner) && std::isfinite(outer) && inner >= 0.0 && inner < outer && outer <= 1.5707963268))
      ctx_.refuse(what + " needs 0 <= innerConeAngle < outerConeAngle <= pi/2");
    out.innerConeAngle = static_cast<float>(inner);
    out.outerConeAngle = static_cast<float>(outer);
    out.node = index;
    out.world = restWorld_[static_cast<size_t>(index)];
    scene_.lights.push_back(out);
  }

  // The node's camera (glTF 2.0 sec. 3.10), perspective or orthographic, with the values the spec requires checked.
  void addCamera(const tinygltf::Node& source, int nodeIndex, int index, const std::string& nodeName) {
    if (source.camera < 0) return;
    if (static_cast<size_t>(source.camera) >= model_.cameras.size())
      ctx_.refuse("node " + std::to_string(nodeIndex) + " refers to camera " + std::to_string(source.camera) +
                  ", which does not exist");
    const tinygltf::Camera& camera = model_.cameras[static_cast<size_t>(source.camera)];
    const std::string what = "camera " + std::to_string(source.camera);
    SceneCamera out;
    out.name = camera.name;
    out.nodeName = nodeName;
    out.node = index;
    out.world = restWorld_[static_cast<size_t>(index)];
    auto finite = [](double v) { return std::isfinite(v); };
    if (camera.type == "perspective") {
      const tinygltf::PerspectiveCamera& p = camera.perspective;
      if (!(finite(p.yfov) && p.yfov > 0.0 && p.yfov < 3.14159265358979))
        ctx_.refuse(what + " has yfov " + std::to_string(p.yfov) + " (glTF: radians, > 0 and < pi)");
      if (!(finite(p.znear) && p.znear > 0.0)) ctx_.refuse(what + " needs znear > 0");
      if (!(finite(p.zfar) && (p.zfar == 0.0 || p.zfar > p.znear)))
        ctx_.refuse(what + " needs zfar > znear (or none: infinite)");
      if (!(finite(p.aspectRatio) && p.aspectRatio >= 0.0)) ctx_.refuse(what + " needs aspectRatio > 0");
      // The renderer's cameras span 1 .. 170 degrees (scene/Camera.h); a wider one is drawn at 170.
      const double widest = 170.0 * 3.14159265358979 / 180.0, narrowest = 3.14159265358979 / 180.0;
      if (p.yfov > widest || p.yfov < narrowest)
        ctx_.report.warnings.push_back(what + " has yfov " + std::to_string(p.yfov) +
                                       " radians, beyond 1 .. 170 degrees: drawn at the nearest");
      out.yfov = static_cast<float>(std::clamp(p.yfov, narrowest, widest));
      out.aspectRatio = static_cast<float>(p.aspectRatio);
      out.znear = static_cast<float>(p.znear);
      out.zfar = static_cast<float>(p.zfar);
    } else if (camera.type == "orthographic") {
      const tinygltf::OrthographicCamera& o = camera.orthographic;
      if (!(finite(o.xmag) && finite(o.ymag) && o.xmag != 0.0 && o.ymag != 0.0))
        ctx_.refuse(what + " needs xmag and ymag other than 0");
      // glTF: "SHOULD NOT be negative" (a mirrored view); drawn unmirrored.
      if (o.xmag < 0.0 || o.ymag < 0.0)
        ctx_.report.warnings.push_back(what + " has a negative xmag or ymag: drawn with their magnitudes");
      if (!(finite(o.znear) && finite(o.zfar) && o.znear >= 0.0 && o.zfar > o.znear))
        ctx_.refuse(what + " needs 0 <= znear < zfar");
      out.orthographic = true;
      out.xmag = static_cast<float>(std::abs(o.xmag));
      out.ymag = static_cast<float>(std::abs(o.ymag));
      out.znear = static_cast<float>(o.znear);
      out.zfar = static_cast<float>(o.zfar);
    } else {
      ctx_.refuse(what + " has unknown type '" + camera.type + "'");
    }
    scene_.cameras.push_back(std::move(out));
  }

  // The morph target count of a glTF mesh: every primitive must have the same (glTF 2.0 sec. 3.7.2.2), and the
  // mesh's default weights, when given, one per target.
  size_t morphTargetCount(int meshIndex) {
    auto found = targetCounts_.find(meshIndex);
    if (found != targetCounts_.end()) return found->second;
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<size_t>(meshIndex)];
    const std::string what = "mesh " + std::to_string(meshIndex);
    const size_t count = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
    for (size_t p = 1; p < mesh.primitives.size(); ++p)
      if (mesh.primitives[p].targets.size() != count)
        ctx_.refuse(what + " primitive " + std::to_string(p) + " has " +
                    std::to_string(mesh.primitives[p].targets.size()) + " morph targets but primitive 0 has " +
                    std::to_string(count) + " (glTF requires the same in every primitive)");
    if (!mesh.weights.empty() && mesh.weights.size() != count)
      ctx_.refuse(what + " has " + std::to_string(mesh.weights.size()) + " weights for " + std::to_string(count) +
                  " morph targets");
    if (!allFinite(mesh.weights)) ctx_.refuse(what + " has a weight that is not finite");
    targetCounts_[meshIndex] = count;
    return count;
  }

  // A node's rest morph weights: its own, else its mesh's, else zeros; one per morph target.
  std::vector<float> restWeights(const tinygltf::Node& source, int nodeIndex) {
    const size_t count = morphTargetCount(source.mesh);
    const std::vector<double>& mesh = model_.meshes[static_cast<size_t>(source.mesh)].weights;
    if (!source.weights.empty()) {
      if (source.weights.size() != count)
        ctx_.refuse("node " + std::to_string(nodeIndex) + " has " + std::to_string(source.weights.size()) +
                    " weights for its mesh's " + std::to_string(count) + " morph targets");
      if (!allFinite(source.weights))
        ctx_.refuse("node " + std::to_string(nodeIndex) + " has a weight that is not finite");
    }
    const std::vector<double>& chosen = !source.weights.empty() ? source.weights : mesh;
    std::vector<float> out(count, 0.0f);
    for (size_t i = 0; i < chosen.size() && i < count; ++i) out[i] = static_cast<float>(chosen[i]);
    return out;
  }

  // The Scene mesh of a glTF primitive drawn skinned or rigid (-1: nothing to draw), loaded on first use.
  int primitiveMesh(int meshIndex, size_t primitive, bool skinned) {
    const auto key = std::make_tuple(meshIndex, primitive, skinned);
    auto found = primitiveMeshes_.find(key);
    if (found != primitiveMeshes_.end()) return found->second;
    const tinygltf::Primitive& source = model_.meshes[static_cast<size_t>(meshIndex)].primitives[primitive];
    const std::string what = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primitive);
    bool skipped = false;
    Mesh mesh = loadPrimitive(ctx_, source, what, skinned, &skipped);
    if (skipped) {
      LineMesh lines = loadLinePrimitive(ctx_, source, what);
      if (!lines.positions.empty()) {
        lineMeshes_[key] = static_cast<int>(scene_.lineMeshes.size());
        scene_.lineMeshes.push_back(std::move(lines));
      }
    }
    int index = -1;
    if (!skipped && !mesh.indices.empty()) {
      if (!skinned && attributeAccessor(source, "JOINTS_0") >= 0)
        ctx_.report.warnings.push_back(what + " has JOINTS_0 but a node without a skin places it; drawn rigid");
      int maxJoint = -1;
      for (const glm::u16vec4& joints : mesh.joints)
        for (int c = 0; c < 4; ++c) maxJoint = std::max(maxJoint, static_cast<int>(joints[c]));
      index = static_cast<int>(scene_.meshes.size());
      scene_.meshes.push_back(std::move(mesh));
      maxJoint_.push_back(maxJoint);
    }
    primitiveMeshes_[key] = index;
    return index;
  }

  // A glTF skin as a Scene skin (loaded on first use): its joints must be nodes of the loaded hierarchy.
  int sceneSkin(int skinIndex) {
    auto found = skins_.find(skinIndex);
    if (found != skins_.end()) return found->second;
    const tinygltf::Skin& source = model_.skins[static_cast<size_t>(skinIndex)];
    const std::string what = "skin " + std::to_string(skinIndex);
    if (source.joints.empty()) ctx_.refuse(what + " has no joints");
    if (source.joints.size() > static_cast<size_t>(ctx_.limits.maxSkinJoints))
      ctx_.refuse(what + " has " + std::to_string(source.joints.size()) + " joints, over the limit of " +
                  std::to_string(ctx_.limits.maxSkinJoints));
    Skin skin;
    skin.name = source.name;
    for (size_t j = 0; j < source.joints.size(); ++j) {
      const int joint = source.joints[j];
      if (joint < 0 || static_cast<size_t>(joint) >= model_.nodes.size())
        ctx_.refuse(what + " joint " + std::to_string(j) + " is node " + std::to_string(joint) +
                    ", which does not exist");
      const std::vector<int>& copies = copies_[static_cast<size_t>(joint)];
      if (copies.empty())
        ctx_.refuse(what + " joint " + std::to_string(j) + " is node " + std::to_string(joint) +
                    ", which is not in the default scene");
      if (copies.size() > 1)
        ctx_.report.warnings.push_back(what + " joint " + std::to_string(j) + " is node " + std::to_string(joint) +
                                       ", reached by several paths; the first is used");
      skin.joints.push_back(copies.front());
    }
    skin.inverseBind.assign(skin.joints.size(), glm::mat4(1.0f));
    if (source.inverseBindMatrices >= 0) {
      const std::vector<double> matrices = readAccessor(ctx_, source.inverseBindMatrices,
                                                        what + " inverseBindMatrices", 16,
                                                        {TINYGLTF_COMPONENT_TYPE_FLOAT});
      if (matrices.size() / 16 < skin.joints.size())
        ctx_.refuse(what + " has " + std::to_string(matrices.size() / 16) + " inverse bind matrices for " +
                    std::to_string(skin.joints.size()) + " joints");
      if (!allFinite(matrices)) ctx_.refuse(what + " has an inverse bind matrix that is not finite");
      for (size_t j = 0; j < skin.joints.size(); ++j)
        for (int i = 0; i < 16; ++i)
          glm::value_ptr(skin.inverseBind[j])[i] = static_cast<float>(matrices[j * 16 + static_cast<size_t>(i)]);
    }
    // Only a hint of the joints' common root (glTF 2.0 sec. 3.7.3.2): kept where it is a loaded node.
    if (source.skeleton >= 0 && static_cast<size_t>(source.skeleton) < model_.nodes.size() &&
        !copies_[static_cast<size_t>(source.skeleton)].empty())
      skin.skeleton = copies_[static_cast<size_t>(source.skeleton)].front();
    const int index = static_cast<int>(scene_.skins.size());
    scene_.skins.push_back(std::move(skin));
    skins_[skinIndex] = index;
    return index;
  }

  // One instance per drawable primitive of every node with a mesh, in node order, at the node's rest world matrix.
  void placeInstances() {
    std::uint64_t triangles = 0;
    for (size_t n = 0; n < scene_.nodes.size(); ++n) {
      const int nodeIndex = sourceNode_[n];
      const tinygltf::Node& source = model_.nodes[static_cast<size_t>(nodeIndex)];
      if (source.mesh < 0) continue;
      if (source.skin >= 0 && static_cast<size_t>(source.skin) >= model_.skins.size())
        ctx_.refuse("node " + std::to_string(nodeIndex) + " refers to skin " + std::to_string(source.skin) +
                    ", which does not exist");
      const tinygltf::Mesh& mesh = model_.meshes[static_cast<size_t>(source.mesh)];
      bool anySkinned = false;
      for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        const bool skinned = source.skin >= 0 && attributeAccessor(mesh.primitives[p], "JOINTS_0") >= 0;
        const int meshIndex = primitiveMesh(source.mesh, p, skinned);
        const auto lines = lineMeshes_.find(std::make_tuple(source.mesh, p, skinned));
        if (lines != lineMeshes_.end()) {
          scene_.lineInstances.push_back({lines->second, restWorld_[n], static_cast<int>(n)});
          if (scene_.lineInstances.size() > ctx_.limits.maxInstances)
            ctx_.refuse("places more than " + std::to_string(ctx_.limits.maxInstances) + " point or line instances");
        }
        if (meshIndex < 0) continue;
        Instance instance;
        instance.mesh = meshIndex;
        instance.world = restWorld_[n];
        instance.node = static_cast<int>(n);
        if (skinned) {
          anySkinned = true;
          instance.skin = sceneSkin(source.skin);
          const size_t jointCount = scene_.skins[static_cast<size_t>(instance.skin)].joints.size();
          const int maxJoint = maxJoint_[static_cast<size_t>(meshIndex)];
          if (maxJoint >= static_cast<int>(jointCount))
            ctx_.refuse("mesh " + std::to_string(source.mesh) + " primitive " + std::to_string(p) +
                        " has joint index " + std::to_string(maxJoint) + " but skin " + std::to_string(source.skin) +
                        " has " + std::to_string(jointCount) + " joints");
        }
        scene_.instances.push_back(instance);
        triangles += scene_.meshes[static_cast<size_t>(meshIndex)].indices.size() / 3;
        if (scene_.instances.size() > ctx_.limits.maxInstances)
          ctx_.refuse("places more than " + std::to_string(ctx_.limits.maxInstances) + " mesh instances");
        if (triangles > ctx_.limits.maxSceneTriangles)
          ctx_.refuse("has more than " + std::to_string(ctx_.limits.maxSceneTriangles) + " triangles after instancing");
      }
      if (source.skin >= 0 && !anySkinned && !mesh.primitives.empty())
        ctx_.report.warnings.push_back("node " + std::to_string(nodeIndex) + " has skin " +
                                       std::to_string(source.skin) + " but its mesh has no JOINTS_0; drawn rigid");
    }
  }

  const LoaderContext& ctx_;
  const tinygltf::Model& model_;
  Scene& scene_;
  std::vector<std::vector<int>> copies_;  // per glTF node: its Scene::nodes indices (several: reached by several paths)
  std::vector<int> sourceNode_;           // per Scene node: its glTF node
  std::vector<glm::mat4> restWorld_;      // per Scene node
  std::vector<int> path_;                 // glTF nodes from the root to the one visited, to detect cycles
  bool warnedSharedNode_ = false;
  std::map<int, size_t> targetCounts_;                        // per glTF mesh
  std::map<std::tuple<int, size_t, bool>, int> primitiveMeshes_;  // (mesh, primitive, skinned) -> Scene mesh
  std::vector<int> maxJoint_;                                 // per Scene mesh: its highest joint index, -1: none
  std::map<int, int> skins_;                                  // glTF skin -> Scene skin
  std::map<std::tuple<int, size_t, bool>, int> lineMeshes_;  // (mesh, primitive, skinned) -> Scene::lineMeshes
};

}  // namespace

std::vector<std::vector<int>> loadNodes(const LoaderContext& ctx, Scene& scene) {
  return NodeReader(ctx, scene).read();
}

}  // namespace obscura::gltf
