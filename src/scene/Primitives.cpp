#include "scene/Primitives.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

namespace obscura {
namespace {
constexpr float kPi = glm::pi<float>();

}  // namespace

// Appends a quad (a, b, c, d counter-clockwise seen from the front) with its own four vertices and a flat normal.
void addQuad(Mesh& mesh, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
             const glm::vec2& uvScale) {
  const glm::vec3 n = glm::normalize(glm::cross(b - a, d - a));
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {a, b, c, d});
  mesh.normals.insert(mesh.normals.end(), {n, n, n, n});
  mesh.texcoords.insert(mesh.texcoords.end(), {glm::vec2(0.0f, 0.0f), glm::vec2(uvScale.x, 0.0f), uvScale,
                                               glm::vec2(0.0f, uvScale.y)});
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// Axis-aligned box from min to max, faces outward.
Mesh makeBox(const glm::vec3& lo, const glm::vec3& hi, float uvPerMetre) {
  Mesh m;
  auto uv = [&](float w, float h) { return uvPerMetre > 0.0f ? glm::vec2(w, h) * uvPerMetre : glm::vec2(1.0f); };
  const glm::vec3 s = hi - lo;
  addQuad(m, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}, uv(s.x, s.y));  // +z
  addQuad(m, {hi.x, lo.y, lo.z}, {lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, uv(s.x, s.y));  // -z
  addQuad(m, {hi.x, lo.y, hi.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, uv(s.z, s.y));  // +x
  addQuad(m, {lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z}, uv(s.z, s.y));  // -x
  addQuad(m, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z}, uv(s.x, s.z));  // +y
  addQuad(m, {lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}, uv(s.x, s.z));  // -y
  return m;
}

Mesh makeSphere(float radius, int slices, int stacks) {
  Mesh m;
  for (int j = 0; j <= stacks; ++j) {
    const float v = static_cast<float>(j) / static_cast<float>(stacks);
    const float theta = v * kPi;
    for (int i = 0; i <= slices; ++i) {
      const float u = static_cast<float>(i) / static_cast<float>(slices);
      const float phi = u * 2.0f * kPi;
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      m.positions.push_back(n * radius);
      m.normals.push_back(n);
      m.texcoords.emplace_back(u, v);
    }
  }
  const auto row = static_cast<std::uint32_t>(slices + 1);
  for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(stacks); ++j) {
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(slices); ++i) {
      const std::uint32_t a = j * row + i, b = a + row;
      if (j != 0) m.indices.insert(m.indices.end(), {a, b, a + 1});
      if (j + 1 != static_cast<std::uint32_t>(stacks)) m.indices.insert(m.indices.end(), {a + 1, b, b + 1});
    }
  }
  return m;
}

// Capped cylinder standing on y = 0.
Mesh makeCylinder(float radius, float height, int slices) {
  Mesh m;
  for (int i = 0; i < slices; ++i) {
    const float a0 = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(slices);
    const float a1 = 2.0f * kPi * static_cast<float>(i + 1) / static_cast<float>(slices);
    const glm::vec3 d0(std::cos(a0), 0.0f, -std::sin(a0)), d1(std::cos(a1), 0.0f, -std::sin(a1));
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {d0 * radius, d1 * radius, d1 * radius + glm::vec3(0, height, 0),
                                           d0 * radius + glm::vec3(0, height, 0)});
    m.normals.insert(m.normals.end(), {d0, d1, d1, d0});  // smooth sides
    m.texcoords.insert(m.texcoords.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    // Top cap fan.
    const auto top = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {glm::vec3(0, height, 0), d0 * radius + glm::vec3(0, height, 0),
                                           d1 * radius + glm::vec3(0, height, 0)});
    m.normals.insert(m.normals.end(), 3, glm::vec3(0, 1, 0));
    m.texcoords.insert(m.texcoords.end(), 3, glm::vec2(0.5f));
    m.indices.insert(m.indices.end(), {top, top + 1, top + 2});
  }
  return m;
}

Mesh makeRoundedTube(float radius, float length, int slices, int rings) {
  Mesh m;
  const int capRows = std::max(2, slices / 4);  // the hemisphere's rows above the side's top ring, the pole last
  const float top = length + radius;
  auto addRow = [&](float y, float radial, float rise) {  // rise: the normal's y; radial: its part outwards
    for (int i = 0; i <= slices; ++i) {
      const float u = static_cast<float>(i) / static_cast<float>(slices);
      const glm::vec3 d(std::cos(2.0f * kPi * u), 0.0f, -std::sin(2.0f * kPi * u));
      m.positions.push_back(d * (radius * radial) + glm::vec3(0.0f, y, 0.0f));
      m.normals.push_back(glm::normalize(d * radial + glm::vec3(0.0f, rise, 0.0f)));
      m.texcoords.emplace_back(u, y / top);
    }
  };
  for (int j = 0; j <= rings; ++j) addRow(length * static_cast<float>(j) / static_cast<float>(rings), 1.0f, 0.0f);
  for (int k = 1; k <= capRows; ++k) {
    const float elevation = 0.5f * kPi * static_cast<float>(k) / static_cast<float>(capRows);
    const float radial = k == capRows ? 0.0f : std::cos(elevation);  // exactly 0 at the pole
    addRow(length + radius * std::sin(elevation), radial, std::sin(elevation));
  }
  // Each row to the one above it, counter-clockwise seen from outside (as makeCylinder's sides).
  const auto row = static_cast<std::uint32_t>(slices + 1);
  const auto rows = static_cast<std::uint32_t>(rings + 1 + capRows);
  for (std::uint32_t j = 0; j + 1 < rows; ++j) {
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(slices); ++i) {
      const std::uint32_t a = j * row + i, b = a + row;
      m.indices.insert(m.indices.end(), {a, a + 1, b + 1});
      if (j + 2 != rows) m.indices.insert(m.indices.end(), {a, b + 1, b});  // the pole row: one triangle each
    }
  }
  return m;
}

// A semicircular arch ring in the xy plane (centre at the origin, opening downwards), `depth` thick along z.
Mesh makeArchRing(float innerRadius, float outerRadius, float depth, int segments) {
  Mesh m;
  const float z0 = -depth * 0.5f, z1 = depth * 0.5f;
  for (int i = 0; i < segments; ++i) {
    const float a0 = kPi * static_cast<float>(i) / static_cast<float>(segments);
    const float a1 = kPi * static_cast<float>(i + 1) / static_cast<float>(segments);
    const glm::vec2 d0(std::cos(a0), std::sin(a0)), d1(std::cos(a1), std::sin(a1));
    const glm::vec2 i0 = d0 * innerRadius, i1 = d1 * innerRadius, o0 = d0 * outerRadius, o1 = d1 * outerRadius;
    addQuad(m, {o0, z1}, {o0, z0}, {o1, z0}, {o1, z1});  // outer (faces away from the centre)
    addQuad(m, {i1, z1}, {i1, z0}, {i0, z0}, {i0, z1});  // intrados (faces the centre)
    addQuad(m, {i0, z1}, {o0, z1}, {o1, z1}, {i1, z1});  // front
    addQuad(m, {o0, z0}, {i0, z0}, {i1, z0}, {o1, z0});  // back
  }
  return m;
}

}  // namespace obscura
