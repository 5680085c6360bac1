#include "scene/MeshProcessing.h"

#include <unordered_map>

#include <glm/geometric.hpp>

namespace obscura {

void generateFlatNormals(Mesh& mesh) {
  Mesh flat;
  flat.material = mesh.material;
  const bool hasUv = !mesh.texcoords.empty();
  flat.positions.reserve(mesh.indices.size());
  flat.normals.reserve(mesh.indices.size());
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[t]];
    const glm::vec3 b = mesh.positions[mesh.indices[t + 1]];
    const glm::vec3 c = mesh.positions[mesh.indices[t + 2]];
    const glm::vec3 cross = glm::cross(b - a, c - a);
    const float length = glm::length(cross);
    // Degenerate triangles get an arbitrary unit normal; they cover no pixels.
    const glm::vec3 n = length > 0.0f ? cross / length : glm::vec3(0.0f, 1.0f, 0.0f);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t source = mesh.indices[t + static_cast<size_t>(k)];
      flat.indices.push_back(static_cast<std::uint32_t>(flat.positions.size()));
      flat.positions.push_back(mesh.positions[source]);
      flat.normals.push_back(n);
      if (hasUv) flat.texcoords.push_back(mesh.texcoords[source]);
    }
  }
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
      }
      piece.indices.push_back(it->second);
    }
  }
  flush();
  return pieces;
}

}  // namespace obscura
