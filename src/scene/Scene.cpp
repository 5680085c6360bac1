#include "scene/Scene.h"

#include <algorithm>
#include <iterator>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace obscura {

void Bounds::add(const glm::vec3& p) {
  min = glm::min(min, p);
  max = glm::max(max, p);
}

glm::vec3 Material::dielectricF0() const {
  const float r = (ior - 1.0f) / (ior + 1.0f);  // ior 0 (the extension's "infinite"): 1
  return glm::min(glm::vec3(r * r) * specularColorFactor, glm::vec3(1.0f)) * specularFactor;
}

float Bounds::radius() const { return empty() ? 0.0f : 0.5f * glm::length(max - min); }

std::array<glm::vec4, 8> Bounds::clipCorners(const glm::mat4& toClip) const {
  // The minimum corner's image plus, per axis, the matrix's column times the extent: one matrix product, not eight
  // (the render's host time, docs/benchmarks.md).
  const glm::vec4 origin = toClip * glm::vec4(min, 1.0f);
  const glm::vec3 extent = max - min;
  const glm::vec4 steps[3] = {toClip[0] * extent.x, toClip[1] * extent.y, toClip[2] * extent.z};
  std::array<glm::vec4, 8> corners;
  for (int corner = 0; corner < 8; ++corner) {
    glm::vec4 clip = origin;
    for (int axis = 0; axis < 3; ++axis)
      if (corner & (1 << axis)) clip += steps[axis];
    corners[static_cast<size_t>(corner)] = clip;
  }
  return corners;
}

bool Bounds::outsideClip(const glm::mat4& toClip) const {
  if (empty()) return true;
  // Per plane, whether every corner is beyond it: x < -w, x > w, y < -w, y > w, z < -w, z > w.
  bool beyond[6] = {true, true, true, true, true, true};
  for (const glm::vec4& clip : clipCorners(toClip))
    for (int axis = 0; axis < 3; ++axis) {
      beyond[2 * axis] = beyond[2 * axis] && clip[axis] < -clip.w;
      beyond[2 * axis + 1] = beyond[2 * axis + 1] && clip[axis] > clip.w;
    }
  return std::any_of(std::begin(beyond), std::end(beyond), [](bool b) { return b; });
}

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
