#pragma once
// The view-space normal of a G-buffer pixel reconstructed from its neighbours' depths (gbuffer.normals
// reconstructed): the CPU mirror of shaders_es2/lib/normal_from_depth.glsl, which explains the choice of differences.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "encoding/LinearDepthPacking.h"
#include "frame/ViewReconstruction.h"

namespace obscura {

inline constexpr float kNormalEdgeJump = 0.1f;

// `depthCode(x, y)`: the G-buffer's 16-bit depth code at integer pixel (x, y), row 0 at the bottom (GL's order).
// Returns the normal, or nothing where a direction has no side on the pixel's own surface (the shader's fallback).
inline std::optional<glm::vec3> normalFromDepth(const ViewReconstruction& view, glm::ivec2 size, glm::ivec2 pixel,
                                                const std::function<std::uint16_t(int, int)>& depthCode) {
  auto codeAt = [&](glm::ivec2 p) {
    const bool outside = p.x < 0 || p.y < 0 || p.x > size.x - 1 || p.y > size.y - 1;
    const std::uint16_t code = outside ? LinearDepthPacking::kBackgroundCode : depthCode(p.x, p.y);
    return code == LinearDepthPacking::kBackgroundCode ? 1e9f : static_cast<float>(code);
  };
  auto point = [&](glm::ivec2 p, float code) {
    return view.viewPosition((glm::vec2(p) + 0.5f) / glm::vec2(size), code * (1.0f / 65535.0f));
  };
  const glm::ivec2 dx(1, 0), dy(0, 1);
  const float code = static_cast<float>(depthCode(pixel.x, pixel.y));
  const float left = codeAt(pixel - dx), right = codeAt(pixel + dx), below = codeAt(pixel - dy),
              above = codeAt(pixel + dy);
  const float edge = kNormalEdgeJump * (code + 65535.0f * view.depthToRay.w / view.depthToRay.z);
  if (std::min(std::abs(code - left), std::abs(right - code)) > edge ||
      std::min(std::abs(code - below), std::abs(above - code)) > edge)
    return std::nullopt;
  const glm::vec3 centre = point(pixel, code);
  auto tangent = [&](glm::ivec2 axis, float before, float after) {
    const glm::vec3 back = centre - point(pixel - axis, before), ahead = point(pixel + axis, after) - centre;
    const float stepBack = std::abs(code - before), stepAhead = std::abs(after - code);
    const glm::vec3 lesser = stepBack < stepAhead ? back : ahead;
    const float agreement =
        std::clamp(1.0f - std::abs(stepBack - stepAhead) / (0.5f * (stepBack + stepAhead) + 1.0f), 0.0f, 1.0f);
    return lesser + (0.5f * (back + ahead) - lesser) * agreement;
  };
  const glm::vec3 n = glm::normalize(glm::cross(tangent(dx, left, right), tangent(dy, below, above)));
  return glm::dot(n, view.eyeRayDirection(centre)) > 0.0f ? -n : n;  // towards the camera
}

}  // namespace obscura
