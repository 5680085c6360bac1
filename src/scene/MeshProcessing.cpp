#include "scene/MeshProcessing.h"

#include <unordered_map>

#include <glm/geometric.hpp>

namespace obscura {

void generateFlatNormals(Mesh& mesh) {
  Mesh flat;
  flat.material = mesh.material;
  const bool hasUv = !mesh.texcoords.empty();
  const bool skinned = mesh.skinned();
  flat.positions.reserve(mesh.indices.size());
  flat.normals.reserve(mesh.indices.size());
  flat.morphTargets.resize(mesh.morphTargets.size());
  std::vector<bool> targetMovesNormals(mesh.morphTargets.size(), false);
  auto faceNormal = [](const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, glm::vec3* n) {
    const glm::vec3 cross = glm::cross(b - a, c - a);
    const float length = glm::length(cross);
    if (!(length > 0.0f)) return false;
    *n = cross / length;
    return true;
  };
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t corners[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    const glm::vec3 a = mesh.positions[corners[0]], b = mesh.positions[corners[1]], c = mesh.positions[corners[2]];
    // Degenerate triangles get an arbitrary unit normal; they cover no pixels.
    glm::vec3 n(0.0f, 1.0f, 0.0f);
    faceNormal(a, b, c, &n);
    for (size_t m = 0; m < mesh.morphTargets.size(); ++m) {
      // The target's normal displacement is the change of the face normal when the target is fully applied: exact
      // at weights 0 and 1 of one target, an approximation between (the vertex stage renormalises).
      const std::vector<glm::vec3>& d = mesh.morphTargets[m].positions;
      glm::vec3 moved = n;
      if (!faceNormal(a + d[corners[0]], b + d[corners[1]], c + d[corners[2]], &moved)) moved = n;
      const glm::vec3 delta = moved - n;
      if (delta != glm::vec3(0.0f)) targetMovesNormals[m] = true;
      for (std::uint32_t corner : corners) {
        flat.morphTargets[m].positions.push_back(d[corner]);
        flat.morphTargets[m].normals.push_back(delta);
      }
    }
    for (std::uint32_t source : corners) {
      flat.indices.push_back(static_cast<std::uint32_t>(flat.positions.size()));
      flat.positions.push_back(mesh.positions[source]);
      flat.normals.push_back(n);
      if (hasUv) flat.texcoords.push_back(mesh.texcoords[source]);
      if (skinned) {
        flat.joints.push_back(mesh.joints[source]);
        flat.weights.push_back(mesh.weights[source]);
      }
    }
  }
  for (size_t m = 0; m < flat.morphTargets.size(); ++m)
    if (!targetMovesNormals[m]) flat.morphTargets[m].normals.clear();
  mesh = std::move(flat);
}

void generateSmoothNormals(Mesh& mesh) {
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t ia = mesh.indices[t], ib = mesh.indices[t + 1], ic = mesh.indices[t + 2];
    // The cross product's length is twice the area: larger faces weigh more.
    const glm::vec3 n = glm::cross(mesh.positions[ib] - mesh.positions[ia], mesh.positions[ic] - mesh.positions[ia]);
    mesh.normals[ia] += n;
    mesh.normals[ib] += n;
    mesh.normals[ic] += n;
  }
  for (glm::vec3& n : mesh.normals) {
    const float length = glm::length(n);
    n = length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
  }
}

std::vector<Mesh> splitForShortIndices(const Mesh& mesh, std::uint32_t maxVertices) {
  if (mesh.positions.size() <= maxVertices) return {mesh};
  std::vector<Mesh> pieces;
  const bool hasUv = !mesh.texcoords.empty();
  Mesh piece;
  std::unordered_map<std::uint32_t, std::uint32_t> remap;
  auto flush = [&] {
    if (!piece.indices.empty()) {
      piece.material = mesh.material;
      pieces.push_back(std::move(piece));
    }
    piece = Mesh();
    remap.clear();
  };
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    // A triangle adds at most three new vertices: start a new piece if they might not fit.
    if (piece.positions.size() + 3 > maxVertices) flush();
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t source = mesh.indices[t + static_cast<size_t>(k)];
      auto [it, inserted] = remap.try_emplace(source, static_cast<std::uint32_t>(piece.positions.size()));
      if (inserted) {
        piece.positions.push_back(mesh.positions[source]);
        piece.normals.push_back(mesh.normals[source]);
        if (hasUv) piece.texcoords.push_back(mesh.texcoords[source]);
        if (mesh.skinned()) {
          piece.joints.push_back(mesh.joints[source]);
          piece.weights.push_back(mesh.weights[source]);
        }
        piece.morphTargets.resize(mesh.morphTargets.size());
        for (size_t m = 0; m < mesh.morphTargets.size(); ++m) {
          piece.morphTargets[m].positions.push_back(mesh.morphTargets[m].positions[source]);
          if (!mesh.morphTargets[m].normals.empty())
            piece.morphTargets[m].normals.push_back(mesh.morphTargets[m].normals[source]);
        }
      }
      piece.indices.push_back(it->second);
    }
  }
  flush();
  return pieces;
}

}  // namespace obscura
