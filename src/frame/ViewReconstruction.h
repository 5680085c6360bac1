#pragma once
// View-space position from 16-bit linear depth, along the pixel's far-plane ray (Gravås 2013, eq. 3.1.3).
// CPU mirror of shaders_es2/lib/reconstruct.glsl.
//
// For a symmetric perspective camera, the view-space point of pixel uv in [0,1]^2 on the far plane is
//   F(uv) = ((2 uv - 1) * farHalfExtent, -far),   farHalfExtent = far * (tan(fovx/2), tan(fovy/2)).
// A point at linear depth d = (-z - near)/(far - near) lies on the same ray at the fraction -z/far of F:
//   P = F(uv) * (d * (1 - near/far) + near/far)        -- one multiply-add per pixel, then a vec3 scale.
#include <cmath>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace obscura {

struct ViewReconstruction {
  glm::vec2 farHalfExtent{1.0f};  // far * tan(half field of view), x and y
  float far = 1.0f;
  float depthScale = 1.0f;  // 1 - near/far
  float depthBias = 0.0f;   // near/far

  static ViewReconstruction fromPerspective(float fovyRadians, float aspect, float near, float far);

  glm::vec3 farPlaneRay(const glm::vec2& uv) const {
    return glm::vec3((uv * 2.0f - 1.0f) * farHalfExtent, -far);
  }
  glm::vec3 viewPosition(const glm::vec2& uv, float linearDepth) const {
    return farPlaneRay(uv) * (linearDepth * depthScale + depthBias);
  }
};

inline ViewReconstruction ViewReconstruction::fromPerspective(float fovyRadians, float aspect, float near, float far) {
  ViewReconstruction r;
  const float tanHalfY = std::tan(fovyRadians * 0.5f);
  r.farHalfExtent = glm::vec2(tanHalfY * aspect, tanHalfY) * far;
  r.far = far;
  r.depthScale = 1.0f - near / far;
  r.depthBias = near / far;
  return r;
}

}  // namespace obscura
