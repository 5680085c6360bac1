#include "effects/edges/Hatching.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "encoding/ToneMapping.h"

namespace obscura {
namespace {

float strokeCoverage(glm::vec2 q, glm::vec2 direction, float period, float spacing, float phase) {
  const float s = (glm::dot(q, direction) + phase) / period;
  const float distanceInPixels = std::abs(s + 0.5f - std::floor(s + 0.5f) - 0.5f) * spacing;
  return std::clamp(1.0f - distanceInPixels, 0.0f, 1.0f);
}

}  // namespace

glm::vec2 hatchDirection(int layer) {
  static const float base[4] = {0.7853982f, 2.3561945f, 0.0f, 1.5707963f};
  const float angle = base[layer % 4] + 0.3926991f * static_cast<float>(layer / 4);
  return {std::cos(angle), std::sin(angle)};
}

float hatchLayerCoverage(const glm::vec3& p, const glm::vec3& weights, int layer, float pixel, float spacing) {
  const float octave = std::log2(spacing * pixel);
  const float lower = std::floor(octave);
  const float blend = octave - lower;
  const float fine = std::exp2(lower), coarse = 2.0f * fine;
  const glm::vec2 direction = hatchDirection(layer);
  const float phase = 0.37f * static_cast<float>(layer);
  auto plane = [&](glm::vec2 q) {
    const float a = strokeCoverage(q, direction, fine, fine / pixel, phase);
    const float b = strokeCoverage(q, direction, coarse, coarse / pixel, phase);
    return a + (b - a) * blend;
  };
  float covered = 0.0f;
  if (weights.x > 1e-3f) covered += weights.x * plane({p.z, p.y});
  if (weights.y > 1e-3f) covered += weights.y * plane({p.x, p.z});
  if (weights.z > 1e-3f) covered += weights.z * plane({p.x, p.y});
  return covered;
}

glm::vec3 hatchedColor(const glm::vec3& display, const glm::vec3& worldPosition, const glm::vec3& worldNormal,
                       float pixel, float spacing, int bands, const glm::vec3& strokeColor) {
  glm::vec3 n4 = worldNormal * worldNormal;
  n4 *= n4;
  const glm::vec3 weights = n4 / (n4.x + n4.y + n4.z);
  const float n = static_cast<float>(bands);
  const float layers = n - 1.0f - std::min(std::floor(fxaaLuma(display) * n), n - 1.0f);
  float paper = 1.0f;
  for (int k = 0; k < kMaxHatchLayers && static_cast<float>(k) < layers; ++k)
    paper *= 1.0f - hatchLayerCoverage(worldPosition, weights, k, std::max(pixel, 1e-6f), spacing);
  return glm::mix(strokeColor, glm::vec3(1.0f), paper);
}

glm::vec2 pixelWorldSize(const glm::mat4& projection, int height) {
  // Clip w = P[2][3] z + P[3][3] (column-major: column 2, row 3): -z for a perspective projection, 1 for an
  // orthographic one. A pixel spans 2 w / (P11 H) in the world.
  const float scale = 2.0f / (projection[1][1] * static_cast<float>(height));
  return {projection[2][3] * scale, projection[3][3] * scale};
}

void setHatching(const gl::Program& program, const FrameCamera& camera, float spacing, int bands, int gbufferUnit) {
  const glm::mat4 cameraToWorld = glm::inverse(camera.view);
  setReconstruction(program, camera.reconstruction);
  program.set("u_gbuffer", gbufferUnit);
  program.set("u_viewToWorld", glm::mat3(cameraToWorld));
  program.set("u_cameraWorld", glm::vec3(cameraToWorld[3]));
  program.set("u_pixelWorld", pixelWorldSize(camera.unjitteredProjection, camera.height));
  program.set("u_hatchSpacing", spacing);
  program.set("u_hatchBands", static_cast<float>(bands));
}

}  // namespace obscura
