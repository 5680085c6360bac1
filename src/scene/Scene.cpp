#include "scene/Scene.h"

#include <algorithm>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace obscura {

void Bounds::add(const glm::vec3& p) {
  min = glm::min(min, p);
  max = glm::max(max, p);
}

float Bounds::radius() const { return empty() ? 0.0f : 0.5f * glm::length(max - min); }

Bounds Scene::worldBounds() const {
  Bounds bounds;
  for (const Instance& instance : instances) {
    for (const glm::vec3& p : meshes[static_cast<size_t>(instance.mesh)].positions)
      bounds.add(glm::vec3(instance.world * glm::vec4(p, 1.0f)));
  }
  for (const LineInstance& instance : lineInstances)
    for (const glm::vec3& p : lineMeshes[static_cast<size_t>(instance.mesh)].positions)
      bounds.add(glm::vec3(instance.world * glm::vec4(p, 1.0f)));
  return bounds;
}

std::size_t Scene::triangleCount() const {
  std::size_t count = 0;
  for (const Instance& instance : instances) count += meshes[static_cast<size_t>(instance.mesh)].indices.size() / 3;
  return count;
}

glm::mat4 Node::localRest() const {
  if (hasMatrix) return matrix;
  return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) * glm::scale(glm::mat4(1.0f), scale);
}

std::string SceneCamera::label(size_t index) const {
  if (!nodeName.empty()) return nodeName;
  if (!name.empty()) return name;
  return "camera " + std::to_string(index);
}

float Animation::duration() const {
  float last = 0.0f;
  for (const AnimationSampler& sampler : samplers)
    if (!sampler.times.empty()) last = std::max(last, sampler.times.back());
  return last;
}

bool Scene::animated() const {
  if (!animations.empty() || !skins.empty()) return true;
  return std::any_of(meshes.begin(), meshes.end(), [](const Mesh& m) { return !m.morphTargets.empty(); });
}

}  // namespace obscura
