#include "scene/SkinnedTube.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace obscura {

int addSkinnedTube(Scene& scene, const SkinnedTubeShape& shape, const glm::vec3& base, int animation) {
  const int joints = std::max(1, shape.joints);
  const float segment = shape.height / static_cast<float>(joints);
  Mesh tube;
  for (int r = 0; r <= shape.rings; ++r) {
    const float y = shape.height * static_cast<float>(r) / static_cast<float>(shape.rings);
    // Joint j's segment is [j, j + 1) segments; blend linearly between the centres of the two nearest.
    const float along = y / segment - 0.5f;
    const int j0 = std::clamp(static_cast<int>(std::floor(along)), 0, joints - 1);
    const int j1 = std::min(j0 + 1, joints - 1);
    const float t = std::clamp(along - static_cast<float>(j0), 0.0f, 1.0f);
    for (int s = 0; s < shape.sides; ++s) {
      const float a = 6.2831853f * static_cast<float>(s) / static_cast<float>(shape.sides);
      tube.positions.emplace_back(shape.radius * std::cos(a), y, shape.radius * std::sin(a));
      tube.normals.emplace_back(std::cos(a), 0.0f, std::sin(a));
      tube.joints.emplace_back(j0, j1, 0, 0);
      tube.weights.emplace_back(j1 == j0 ? 1.0f : 1.0f - t, j1 == j0 ? 0.0f : t, 0.0f, 0.0f);
    }
  }
  for (int r = 0; r < shape.rings; ++r)
    for (int s = 0; s < shape.sides; ++s) {
      const auto a = static_cast<std::uint32_t>(r * shape.sides + s);
      const auto b = static_cast<std::uint32_t>(r * shape.sides + (s + 1) % shape.sides);
      const auto c = a + static_cast<std::uint32_t>(shape.sides), d = b + static_cast<std::uint32_t>(shape.sides);
      tube.indices.insert(tube.indices.end(), {a, c, b, b, c, d});
    }
  const int mesh = static_cast<int>(scene.meshes.size());
  scene.meshes.push_back(std::move(tube));

  if (animation >= static_cast<int>(scene.animations.size())) {
    scene.animations.resize(static_cast<size_t>(animation) + 1);
    scene.animations.back().name = "bend";
  }
  Animation& bend = scene.animations[static_cast<size_t>(animation)];
  const int firstNode = static_cast<int>(scene.nodes.size());
  Skin skin;
  const glm::quat perJoint = glm::angleAxis(shape.bendRadians / static_cast<float>(joints), glm::vec3(0, 0, 1));
  for (int j = 0; j < joints; ++j) {
    Node node;
    node.name = "tube joint " + std::to_string(j);
    node.parent = j == 0 ? -1 : firstNode + j - 1;
    node.translation = j == 0 ? base : glm::vec3(0.0f, segment, 0.0f);
    scene.nodes.push_back(node);
    skin.joints.push_back(firstNode + j);
    // The inverse of the joint's rest world matrix (a translation up the chain).
    skin.inverseBind.push_back(
        glm::translate(glm::mat4(1.0f), -(base + glm::vec3(0.0f, segment * static_cast<float>(j), 0.0f))));
    AnimationSampler rotation;
    rotation.times = {0.0f, shape.seconds};
    rotation.values = std::vector<float>{0, 0, 0, 1, perJoint.x, perJoint.y, perJoint.z, perJoint.w};
    rotation.components = 4;
    bend.channels.push_back({static_cast<int>(bend.samplers.size()), firstNode + j, AnimationPath::Rotation});
    bend.samplers.push_back(rotation);
  }
  AnimationSampler slide;
  slide.times = {0.0f, shape.seconds};
  slide.values = std::vector<float>{base.x, base.y, base.z, base.x + shape.slide, base.y, base.z};
  slide.components = 3;
  bend.channels.push_back({static_cast<int>(bend.samplers.size()), firstNode, AnimationPath::Translation});
  bend.samplers.push_back(slide);

  Instance instance;
  instance.mesh = mesh;
  instance.node = firstNode;
  instance.skin = static_cast<int>(scene.skins.size());
  instance.world = glm::translate(glm::mat4(1.0f), base);
  scene.skins.push_back(std::move(skin));
  scene.instances.push_back(instance);
  return static_cast<int>(scene.instances.size()) - 1;
}

}  // namespace obscura
