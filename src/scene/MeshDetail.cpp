#include "scene/MeshDetail.h"

#include <obscura_meshoptimizer.h>

#include "base/TimeSpent.h"

namespace obscura {

std::vector<DetailLevel> detailLevels(const Mesh& mesh) {
  std::vector<DetailLevel> levels;
  if (mesh.indices.size() < 3 * kDetailMinTriangles || mesh.skinned() || !mesh.morphTargets.empty() ||
      mesh.normals.size() != mesh.positions.size())  // the simplifier weighs one normal per vertex
    return levels;
  const TimedScope timed("levels of detail");  // start-up's breakdown (base/TimeSpent.h)
  const float* positions = &mesh.positions.front().x;
  const size_t vertexCount = mesh.positions.size();
  // meshoptimizer's errors are relative to the mesh's extent; the levels keep absolute ones.
  const float extent = obscura_meshopt_simplifyScale(positions, vertexCount, sizeof(glm::vec3));
  if (!(extent > 0.0f)) return levels;
  // Relative error bounds from 1/4096 of the extent (a quarter of a pixel for a mesh 1000 pixels across) doubling to
  // 1/64 (a pixel for a mesh 64 pixels across): past that, a mesh small enough on screen to take the level has few
  // pixels left to cost anything. The normals count in the error (kDetailNormalWeight).
  const float normalWeights[3] = {kDetailNormalWeight, kDetailNormalWeight, kDetailNormalWeight};
  size_t previousCount = mesh.indices.size();
  std::vector<std::uint32_t> simplified(mesh.indices.size());
  for (float bound = 1.0f / 4096.0f; bound <= 1.0f / 64.0f; bound *= 2.0f) {
    float relativeError = 0.0f;
    const size_t count = obscura_meshopt_simplifyWithAttributes(
        simplified.data(), mesh.indices.data(), mesh.indices.size(), positions, vertexCount, sizeof(glm::vec3),
        &mesh.normals.front().x, sizeof(glm::vec3), normalWeights, 3, nullptr, 0, bound, 0, &relativeError);
    if (count == 0 || count * 5 > previousCount * 4) continue;  // empty, or under a fifth fewer: not worth a level
    // Each level's error above the one before (GpuScene::chooseDetail stops at the first level over its bound).
    const float error = relativeError * extent;
    if (!levels.empty() && !(error > levels.back().error)) continue;
    levels.push_back({std::vector<std::uint32_t>(simplified.begin(), simplified.begin() + static_cast<long>(count)),
                      error});
    previousCount = count;
  }
  return levels;
}

void addDetailLevels(Scene& scene) {
  for (Mesh& mesh : scene.meshes)
    if (mesh.levels.empty()) mesh.levels = detailLevels(mesh);
}

}  // namespace obscura
