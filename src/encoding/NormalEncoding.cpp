#include "encoding/NormalEncoding.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec2.hpp>

namespace obscura {
namespace {

float signNotZero(float v) { return v >= 0.0f ? 1.0f : -1.0f; }

// Octahedral projection onto [-1,1]^2: the lower hemisphere is folded over the diagonals.
glm::vec2 octahedronFromNormal(const glm::vec3& n) {
  glm::vec2 p = glm::vec2(n.x, n.y) * (1.0f / (std::abs(n.x) + std::abs(n.y) + std::abs(n.z)));
  if (n.z < 0.0f) {
    p = glm::vec2((1.0f - std::abs(p.y)) * signNotZero(p.x), (1.0f - std::abs(p.x)) * signNotZero(p.y));
  }
  return p;
}

glm::vec3 normalFromOctahedron(glm::vec2 p) {
  glm::vec3 n(p.x, p.y, 1.0f - std::abs(p.x) - std::abs(p.y));
  if (n.z < 0.0f) {
    n.x = (1.0f - std::abs(p.y)) * signNotZero(p.x);
    n.y = (1.0f - std::abs(p.x)) * signNotZero(p.y);
  }
  return glm::normalize(n);
}

std::uint8_t quantize(float v, float scale, float offset) {
  return static_cast<std::uint8_t>(std::clamp(std::floor(v * scale + (offset + 0.5f)), 0.0f, 255.0f));
}

}  // namespace

std::array<std::uint8_t, 2> encodeNormal(const glm::vec3& n, NormalEncodingKind kind) {
  switch (kind) {
    case NormalEncodingKind::Octahedral254: {
      const glm::vec2 p = octahedronFromNormal(n);
      return {quantize(p.x, 127.0f, 127.0f), quantize(p.y, 127.0f, 127.0f)};
    }
    case NormalEncodingKind::Octahedral255: {
      const glm::vec2 p = octahedronFromNormal(n);
      return {quantize(p.x, 127.5f, 127.5f), quantize(p.y, 127.5f, 127.5f)};
    }
    case NormalEncodingKind::LambertAzimuthal: {
      // enc = n.xy / sqrt(8 n.z + 8) + 0.5 (Pranckevicius 2010, "spheremap transform").
      const float f = std::sqrt(std::max(8.0f * n.z + 8.0f, 1e-20f));
      return {quantize(n.x / f + 0.5f, 255.0f, 0.0f), quantize(n.y / f + 0.5f, 255.0f, 0.0f)};
    }
  }
  return {0, 0};
}

glm::vec3 decodeNormal(std::uint8_t x, std::uint8_t y, NormalEncodingKind kind) {
  switch (kind) {
    case NormalEncodingKind::Octahedral254:
      return normalFromOctahedron(glm::vec2(static_cast<float>(x) - 127.0f, static_cast<float>(y) - 127.0f) /
                                  127.0f);
    case NormalEncodingKind::Octahedral255:
      return normalFromOctahedron(glm::vec2(static_cast<float>(x) - 127.5f, static_cast<float>(y) - 127.5f) /
                                  127.5f);
    case NormalEncodingKind::LambertAzimuthal: {
      const glm::vec2 fenc = glm::vec2(static_cast<float>(x), static_cast<float>(y)) / 255.0f * 4.0f - 2.0f;
      const float f = glm::dot(fenc, fenc);
      const float g = std::sqrt(std::max(1.0f - f / 4.0f, 0.0f));
      return glm::normalize(glm::vec3(fenc * g, 1.0f - f / 2.0f));
    }
  }
  return glm::vec3(0.0f, 0.0f, 1.0f);
}

std::vector<glm::vec3> encodingTestDirections(int count) {
  std::vector<glm::vec3> dirs;
  dirs.reserve(static_cast<size_t>(count) * 5 / 4 + 8);
  const double golden = glm::pi<double>() * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (i + 0.5) * 2.0 / count;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * i;
    dirs.emplace_back(glm::normalize(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z)));
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      glm::vec3 d(0.0f);
      d[axis] = sign;
      dirs.push_back(d);
    }
  }
  const int band = count / 4;
  for (int i = 0; i < band; ++i) {
    const double z = -0.3 * (i + 0.5) / band;
    const double phi = 2.0 * glm::pi<double>() * i * 0.618033988749895;
    const double r = std::sqrt(1.0 - z * z);
    dirs.emplace_back(glm::normalize(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z)));
  }
  return dirs;
}

double angleBetweenDegrees(const glm::vec3& a, const glm::vec3& b) {
  // atan2(|a x b|, a.b) is accurate at both ends, unlike acos(a.b).
  const glm::dvec3 da(a), db(b);
  return glm::degrees(std::atan2(glm::length(glm::cross(da, db)), glm::dot(da, db)));
}

}  // namespace obscura
