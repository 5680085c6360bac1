#include "scene/MeshProcessing.h"

#include <algorithm>
#include <cmath>
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
      if (!mesh.texcoords1.empty()) flat.texcoords1.push_back(mesh.texcoords1[source]);
      if (!mesh.colors.empty()) flat.colors.push_back(mesh.colors[source]);
      if (!mesh.tangents.empty()) flat.tangents.push_back(mesh.tangents[source]);
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

glm::vec3 anyPerpendicular(const glm::vec3& n) {
  // Cross with the axis least aligned with n: never degenerate for a unit n.
  const glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::normalize(glm::cross(axis, n));
}

void generateTangents(Mesh& mesh, int texCoord) {
  const size_t count = mesh.positions.size();
  std::vector<glm::vec3> tangent(count, glm::vec3(0.0f)), bitangent(count, glm::vec3(0.0f));
  const std::vector<glm::vec2>& uvs = texCoord == 1 ? mesh.texcoords1 : mesh.texcoords;
  if (uvs.size() == count) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const std::uint32_t corner[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
      const glm::vec3 e1 = mesh.positions[corner[1]] - mesh.positions[corner[0]];
      const glm::vec3 e2 = mesh.positions[corner[2]] - mesh.positions[corner[0]];
      const glm::vec2 d1 = uvs[corner[1]] - uvs[corner[0]];
      const glm::vec2 d2 = uvs[corner[2]] - uvs[corner[0]];
      // The face's dP/du and dP/dv. MikkTSpace divides by the signed uv area too, so a mirrored face's gradients
      // keep their geometric sense; a face without uv area contributes nothing (mikktspace.c: "degenerate").
      const float det = d1.x * d2.y - d2.x * d1.y;
      if (!(std::abs(det) > 1e-20f)) continue;
      const glm::vec3 faceT = (e1 * d2.y - e2 * d1.y) / det;
      const glm::vec3 faceB = (e2 * d1.x - e1 * d2.x) / det;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = corner[k];
        const glm::vec3& n = mesh.normals[v];
        // MikkTSpace: project onto the vertex normal's plane, normalise, weight by the corner's angle.
        glm::vec3 pt = faceT - n * glm::dot(n, faceT), pb = faceB - n * glm::dot(n, faceB);
        const float lt = glm::length(pt), lb = glm::length(pb);
        if (lt > 0.0f) pt /= lt;
        if (lb > 0.0f) pb /= lb;
        const glm::vec3 a = mesh.positions[corner[(k + 1) % 3]] - mesh.positions[v];
        const glm::vec3 b = mesh.positions[corner[(k + 2) % 3]] - mesh.positions[v];
        const float la = glm::length(a), lbEdge = glm::length(b);
        if (!(la > 0.0f && lbEdge > 0.0f)) continue;
        const float angle = std::acos(std::clamp(glm::dot(a, b) / (la * lbEdge), -1.0f, 1.0f));
        tangent[v] += angle * pt;
        bitangent[v] += angle * pb;
      }
    }
  }
  mesh.tangents.resize(count);
  for (size_t v = 0; v < count; ++v) {
    const glm::vec3& n = mesh.normals[v];
    glm::vec3 t = tangent[v] - n * glm::dot(n, tangent[v]);
    const float length = glm::length(t);
    t = length > 1e-12f ? t / length : anyPerpendicular(n);
    // The bitangent's sign: +1 where (N x T) points along the accumulated dP/dv (right-handed uv), -1 where mirrored.
    const float sign = glm::dot(glm::cross(n, t), bitangent[v]) < 0.0f ? -1.0f : 1.0f;
    mesh.tangents[v] = glm::vec4(t, sign);
  }
}

Mesh extractTriangles(const Mesh& mesh, const std::vector<std::uint32_t>& triangles) {
  Mesh piece;
  piece.material = mesh.material;
  piece.morphTargets.resize(mesh.morphTargets.size());
  std::unordered_map<std::uint32_t, std::uint32_t> remap;
  for (std::uint32_t t : triangles) {
    for (size_t k = 0; k < 3; ++k) {
      const std::uint32_t source = mesh.indices[3 * static_cast<size_t>(t) + k];
      auto [it, inserted] = remap.try_emplace(source, static_cast<std::uint32_t>(piece.positions.size()));
      if (inserted) {
        piece.positions.push_back(mesh.positions[source]);
        piece.normals.push_back(mesh.normals[source]);
        if (!mesh.texcoords.empty()) piece.texcoords.push_back(mesh.texcoords[source]);
        if (!mesh.texcoords1.empty()) piece.texcoords1.push_back(mesh.texcoords1[source]);
        if (!mesh.colors.empty()) piece.colors.push_back(mesh.colors[source]);
        if (!mesh.tangents.empty()) piece.tangents.push_back(mesh.tangents[source]);
        if (!mesh.joints.empty()) piece.joints.push_back(mesh.joints[source]);
        if (!mesh.weights.empty()) piece.weights.push_back(mesh.weights[source]);
        for (size_t m = 0; m < mesh.morphTargets.size(); ++m) {
          const MorphTarget& target = mesh.morphTargets[m];
          piece.morphTargets[m].positions.push_back(target.positions[source]);
          if (!target.normals.empty()) piece.morphTargets[m].normals.push_back(target.normals[source]);
          if (!target.tangents.empty()) piece.morphTargets[m].tangents.push_back(target.tangents[source]);
        }
      }
      piece.indices.push_back(it->second);
    }
  }
  return piece;
}

std::vector<Mesh> splitForShortIndices(const Mesh& mesh, std::uint32_t maxVertices) {
  if (mesh.positions.size() <= maxVertices) return {mesh};
  std::vector<Mesh> pieces;
  std::vector<std::uint32_t> group;
  std::unordered_map<std::uint32_t, bool> used;  // vertices of the current group
  const auto triangleCount = static_cast<std::uint32_t>(mesh.indices.size() / 3);
  for (std::uint32_t t = 0; t < triangleCount; ++t) {
    // A triangle adds at most three new vertices: start a new piece if they might not fit.
    if (used.size() + 3 > maxVertices) {
      pieces.push_back(extractTriangles(mesh, group));
      group.clear();
      used.clear();
    }
    group.push_back(t);
    for (size_t k = 0; k < 3; ++k) used[mesh.indices[3 * static_cast<size_t>(t) + k]] = true;
  }
  if (!group.empty()) pieces.push_back(extractTriangles(mesh, group));
  return pieces;
}

std::vector<PalettePiece> splitForJointPalette(const Mesh& mesh, int paletteSize) {
  std::vector<PalettePiece> pieces;
  std::vector<std::uint32_t> group;
  std::vector<int> palette;                   // skin joints of the current group, in order of first use
  std::unordered_map<int, int> paletteIndex;  // skin joint -> palette entry
  auto flush = [&] {
    if (group.empty()) return;
    PalettePiece piece{extractTriangles(mesh, group), palette};
    // Renumber the influences into the palette; a zero-weight influence points at entry 0 (it contributes nothing).
    for (size_t v = 0; v < piece.mesh.joints.size(); ++v)
      for (int k = 0; k < 4; ++k) {
        const auto found = paletteIndex.find(piece.mesh.joints[v][k]);
        piece.mesh.joints[v][k] = piece.mesh.weights[v][k] != 0.0f && found != paletteIndex.end()
                                      ? static_cast<std::uint16_t>(found->second)
                                      : 0;
      }
    pieces.push_back(std::move(piece));
    group.clear();
    palette.clear();
    paletteIndex.clear();
  };
  // The joints triangle t adds to the current palette.
  auto newJoints = [&](std::uint32_t t) {
    std::vector<int> needed;
    for (size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.indices[3 * static_cast<size_t>(t) + k];
      for (int i = 0; i < 4; ++i) {
        const int joint = mesh.joints[v][i];
        if (mesh.weights[v][i] != 0.0f && !paletteIndex.count(joint) &&
            std::find(needed.begin(), needed.end(), joint) == needed.end())
          needed.push_back(joint);
      }
    }
    return needed;
  };
  const auto triangleCount = static_cast<std::uint32_t>(mesh.indices.size() / 3);
  for (std::uint32_t t = 0; t < triangleCount; ++t) {
    std::vector<int> needed = newJoints(t);
    if (palette.size() + needed.size() > static_cast<size_t>(paletteSize)) {
      flush();
      needed = newJoints(t);
      if (needed.size() > static_cast<size_t>(paletteSize)) return {};
    }
    for (int joint : needed) {
      paletteIndex.emplace(joint, static_cast<int>(palette.size()));
      palette.push_back(joint);
    }
    group.push_back(t);
  }
  flush();
  return pieces;
}

}  // namespace obscura
