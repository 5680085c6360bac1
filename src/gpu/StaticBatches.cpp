// Static batches (gpu/GpuScene.h, staticBatchCount): the still, rigid, opaque instances that share a material drawn
// as one piece placed in world space.
#include <algorithm>
#include <map>
#include <utility>

#include <glm/gtc/matrix_inverse.hpp>

#include "gpu/GpuScene.h"

namespace obscura {
namespace {

// 16-bit indices, whatever the context offers: a batch's vertices fit them.
constexpr size_t kBatchVertices = 65536;

}  // namespace

void GpuScene::batchStaticInstances(const Scene& scene, const ScenePose& rest) {
  const std::vector<bool> moving = movingNodes(scene);
  auto meshOf = [&](size_t instance) -> const Mesh& {
    return scene.meshes[static_cast<size_t>(scene.instances[instance].mesh)];
  };
  // The candidates: still, rigid, opaque, single-piece, not mirrored, small.
  std::vector<size_t> candidates;
  for (size_t i = 0; i < instances_.size(); ++i) {
    const InstanceGpu& instance = instances_[i];
    const Mesh& mesh = meshOf(i);
    const int node = scene.instances[i].node;
    if (instance.transparent || instance.skin >= 0 || instance.morphed || instance.pieceCount != 1 ||
        mesh.skinned() || mesh.indices.empty() || mesh.positions.size() > static_cast<size_t>(kBatchMemberVertices) ||
        (node >= 0 && moving[static_cast<size_t>(node)]))
      continue;
    // A mirroring world matrix turns the winding, which drawInstance sets per instance: a batch has one.
    if (!(glm::determinant(glm::mat3(rest.instanceWorld[i])) > 0.0f)) continue;
    candidates.push_back(i);
  }
  // Grouped by what one draw shares: the material (its program, uniforms and textures; tangents come with a
  // material whose normal texture needs them) and whether the meshes carry colours (a vertex stream of the program).
  // Then, of the groups of two or more, within the copies' budget (GpuScene.h), the smallest meshes first.
  auto keyOf = [&](size_t i) { return std::make_pair(instances_[i].material, !meshOf(i).colors.empty()); };
  std::map<std::pair<int, bool>, int> groupSizes;
  for (size_t i : candidates) ++groupSizes[keyOf(i)];
  size_t budget = 0;
  for (const Mesh& mesh : scene.meshes) budget += mesh.positions.size();
  budget = std::max(budget, kBatchVertices);
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](size_t a, size_t b) { return meshOf(a).positions.size() < meshOf(b).positions.size(); });
  std::map<std::pair<int, bool>, std::vector<size_t>> groups;
  for (size_t i : candidates) {
    const size_t vertices = meshOf(i).positions.size();
    if (groupSizes[keyOf(i)] < 2) continue;
    if (vertices > budget) break;
    budget -= vertices;
    groups[keyOf(i)].push_back(i);
  }
  for (auto& [key, members] : groups) std::sort(members.begin(), members.end());  // instance order

  for (const auto& [key, members] : groups) {
    const bool tangents = materials_[static_cast<size_t>(key.first)].pbr;
    for (size_t begin = 0, end = 0; begin < members.size(); begin = end) {
      size_t vertices = 0;
      for (end = begin; end < members.size(); ++end) {
        const size_t count = meshOf(members[end]).positions.size();
        if (vertices + count > kBatchVertices) break;
        vertices += count;
      }
      if (end - begin < 2) continue;  // a batch of one saves nothing
      batches_.push_back(makeBatch(scene, rest,
                                   {members.begin() + static_cast<long>(begin), members.begin() + static_cast<long>(end)},
                                   key.first, tangents));
    }
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
}

GpuScene::StaticBatch GpuScene::makeBatch(const Scene& scene, const ScenePose& rest,
                                          const std::vector<size_t>& memberInstances, int material, bool tangents) {
  // The members' vertices placed at their rest world matrices. Normals and tangents are carried as the per-instance
  // draw carries them (the normal matrix, the linear part), not renormalised: with the view's applied after, the
  // vertex stage sees the same vectors up to rounding.
  Mesh merged;
  std::vector<const Mesh*> sources;  // as loaded: the levels index their vertices, which the upload keeps in order
  std::vector<std::uint32_t> bases;  // each member's first vertex
  std::vector<Piece::Member> members;
  Bounds bounds;
  for (size_t i : memberInstances) {
    const Mesh& source = scene.meshes[static_cast<size_t>(scene.instances[i].mesh)];
    Mesh storage;
    const Mesh& mesh = meshToUpload(scene, source, storage);
    const glm::mat4& world = rest.instanceWorld[i];
    const glm::mat3 linear(world);
    const glm::mat3 normalMatrix = glm::inverseTranspose(linear);
    bases.push_back(static_cast<std::uint32_t>(merged.positions.size()));
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      merged.positions.push_back(glm::vec3(world * glm::vec4(mesh.positions[v], 1.0f)));
      bounds.add(merged.positions.back());
      merged.normals.push_back(normalMatrix * mesh.normals[v]);
      merged.texcoords.push_back(mesh.texcoords.empty() ? glm::vec2(0.0f) : mesh.texcoords[v]);
      merged.texcoords1.push_back(mesh.texcoords1.empty() ? glm::vec2(0.0f) : mesh.texcoords1[v]);
      if (!mesh.colors.empty()) merged.colors.push_back(mesh.colors[v]);
      if (tangents) merged.tangents.emplace_back(linear * glm::vec3(mesh.tangents[v]), mesh.tangents[v].w);
    }
    for (std::uint32_t index : mesh.indices) merged.indices.push_back(bases.back() + index);
    Piece::Member& member = members.emplace_back();
    member.instance = static_cast<int>(i);
    member.world = world;
    member.full.indexCount = static_cast<GLsizei>(mesh.indices.size());
    member.levels.resize(source.levels.size());
    sources.push_back(&source);
  }
  // One index list: every member's full list in member order (a batch whose members all take their full detail
  // draws it in one call), then level by level every member's list at that level (members in a row at one level
  // draw in one call: a row of like meshes going away from the eye takes coarser levels in turn).
  std::vector<DetailLevel> levels;
  std::vector<std::pair<size_t, size_t>> levelOwners;  // per entry of `levels`: its member and its level
  for (size_t level = 0, more = 1; more; ++level) {
    more = 0;
    for (size_t m = 0; m < members.size(); ++m) {
      if (level >= sources[m]->levels.size()) continue;
      more = 1;
      const DetailLevel& own = sources[m]->levels[level];
      DetailLevel& rebased = levels.emplace_back();
      rebased.error = own.error;
      for (std::uint32_t index : own.indices) rebased.indices.push_back(bases[m] + index);
      levelOwners.emplace_back(m, level);
    }
  }
  const size_t vertexCount = merged.positions.size();
  Piece piece = uploadPiece(std::move(merged), {}, tangents, levels);
  const size_t indexBytes = piece.indexType == GL_UNSIGNED_INT ? 4 : 2;
  for (size_t m = 0, offset = 0; m < members.size(); ++m) {
    members[m].full.offset = offset;
    offset += static_cast<size_t>(members[m].full.indexCount) * indexBytes;
    instances_[static_cast<size_t>(members[m].instance)].batch = static_cast<int>(batches_.size());
  }
  for (size_t k = 0; k < levelOwners.size(); ++k)
    members[levelOwners[k].first].levels[levelOwners[k].second] = piece.levels[k];
  piece.levels.clear();
  piece.members = std::move(members);

  StaticBatch batch;
  batch.vertices = vertexCount;
  // At the identity (its piece is in world space already); what the draws read of it: the material, the piece, and
  // the centre for the drawing order. Its bounds, level of detail and pose are its members' (chooseDetail, setPose).
  InstanceGpu& drawn = batch.drawn;
  drawn.material = material;
  drawn.firstPiece = static_cast<int>(pieces_.size());
  drawn.pieceCount = 1;
  drawn.centre = bounds.center();
  pieces_.push_back(std::move(piece));
  return batch;
}

std::size_t GpuScene::staticBatchVertices() const {
  std::size_t vertices = 0;
  for (const StaticBatch& batch : batches_) vertices += batch.vertices;
  return vertices;
}

// The members' ranges at their levels this frame: adjacent ranges join, so that all at full detail are one draw.
void GpuScene::drawBatchMembers(const Piece& batch) const {
  const size_t indexBytes = batch.indexType == GL_UNSIGNED_INT ? 4 : 2;
  Piece::Level run;
  auto flush = [&] {
    if (run.indexCount == 0) return;
    glDrawElements(GL_TRIANGLES, run.indexCount, batch.indexType, reinterpret_cast<const void*>(run.offset));
    ++counts_.drawCalls;
  };
  for (const Piece::Member& member : batch.members) {
    const InstanceGpu& instance = instances_[static_cast<size_t>(member.instance)];
    if (!instance.inView) continue;  // the next member in view starts a run of its own (its offset does not follow)
    const int detail = instance.detail;
    const Piece::Level& level = detail > 0 ? member.levels[static_cast<size_t>(detail - 1)] : member.full;
    counts_.triangles += level.indexCount / 3;
    if (detail > 0) ++counts_.coarser;
    if (run.indexCount > 0 && run.offset + static_cast<size_t>(run.indexCount) * indexBytes == level.offset) {
      run.indexCount += level.indexCount;
    } else {
      flush();
      run = level;
    }
  }
  flush();
}

}  // namespace obscura
