#pragma once
// View-space position from 16-bit linear depth, along the pixel's ray (Gravås 2013, eq. 3.1.3), for a perspective or
// an orthographic camera. CPU mirror of shaders_es2/lib/reconstruct.glsl.
//
// The view-space point of pixel uv in [0,1]^2 on the far plane is
//   F(uv) = ((2 uv - 1) * farHalfExtent, -far),
// farHalfExtent the far plane's half width and height: far * (tan(fovx/2), tan(fovy/2)) in perspective, the view's
// own half extent in orthographic projection. Linear depth d = (-z - near)/(far - near) is linear in z under both, so
//   z = -(near + d (far - near)).
// In perspective the point lies on the eye's ray through F, at the fraction -z/far = d (1 - near/far) + near/far of
// it; in orthographic projection on the parallel ray through F, with F's own x and y. Both are
//   P = (F.xy * (d * depthToRay.x + depthToRay.y), d * depthToRay.z + depthToRay.w),
//   depthToRay = (1 - near/far, near/far, near - far, -near)   perspective
//                (0,            1,        near - far, -near)   orthographic,
// two multiply-adds and two multiplies per pixel, as many as the perspective-only form F * (d (1 - n/f) + n/f) took.
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace obscura {

struct ViewReconstruction {
  glm::vec2 farHalfExtent{1.0f};  // the far plane's half width and height
  float far = 1.0f;
  glm::vec4 depthToRay{1.0f, 0.0f, -1.0f, 0.0f};  // (xy scale, xy bias, z scale, z bias), as above
  bool perspective = true;

  // `halfExtent`: Camera::halfExtent (tan of the half fields of view, or the orthographic view's half size).
  static ViewReconstruction fromCamera(glm::vec2 halfExtent, float near, float far, bool orthographic);

  glm::vec3 farPlaneRay(const glm::vec2& uv) const {
    return glm::vec3((uv * 2.0f - 1.0f) * farHalfExtent, -far);
  }
  glm::vec3 viewPosition(const glm::vec2& uv, float linearDepth) const {
    const glm::vec3 farRay = farPlaneRay(uv);
    return glm::vec3(glm::vec2(farRay) * (linearDepth * depthToRay.x + depthToRay.y),
                     linearDepth * depthToRay.z + depthToRay.w);
  }
  // The unit direction of the ray the camera sees view-space point p along: from the eye in perspective, the view
  // axis (0, 0, -1) in orthographic projection.
  glm::vec3 eyeRayDirection(const glm::vec3& p) const {
    return perspective ? glm::normalize(p) : glm::vec3(0.0f, 0.0f, -1.0f);
  }
  // Where that ray starts: the eye, or the point of the plane z = 0 (the eye's) behind p.
  glm::vec3 eyeRayOrigin(const glm::vec3& p) const {
    return perspective ? glm::vec3(0.0f) : glm::vec3(p.x, p.y, 0.0f);
  }
  // The pixel uv that view-space point p projects to (the inverse of viewPosition's ray).
  glm::vec2 uvOf(const glm::vec3& p) const {
    const float toFarPlane = perspective ? far / -p.z : 1.0f;
    return glm::vec2(p.x, p.y) * toFarPlane / farHalfExtent * 0.5f + 0.5f;
  }
};

inline ViewReconstruction ViewReconstruction::fromCamera(glm::vec2 halfExtent, float near, float far,
                                                         bool orthographic) {
  ViewReconstruction r;
  r.perspective = !orthographic;
  r.farHalfExtent = orthographic ? halfExtent : halfExtent * far;
  r.far = far;
  r.depthToRay = orthographic ? glm::vec4(0.0f, 1.0f, near - far, -near)
                              : glm::vec4(1.0f - near / far, near / far, near - far, -near);
  return r;
}

}  // namespace obscura
