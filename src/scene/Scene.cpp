#include "scene/Scene.h"

#include <glm/geometric.hpp>

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
  return bounds;
}

std::size_t Scene::triangleCount() const {
  std::size_t count = 0;
  for (const Instance& instance : instances) count += meshes[static_cast<size_t>(instance.mesh)].indices.size() / 3;
  return count;
}

}  // namespace obscura
