#include "platform/CameraControls.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

namespace obscura {
namespace {
constexpr float kPi = 3.14159265358979f;
constexpr float kPoleMargin = 0.05f;  // radians kept between the view direction and the up axis
}  // namespace

void orbitCamera(Camera& camera, float dxPixels, float dyPixels, int viewportHeight) {
  const float radiansPerPixel = kPi / static_cast<float>(std::max(viewportHeight, 1));
  const glm::vec3 up = glm::normalize(camera.up);
  glm::vec3 offset = camera.eye - camera.target;
  // Dragging right carries the scene right, so the eye goes left: a negative turn about up.
  offset = glm::angleAxis(-dxPixels * radiansPerPixel, up) * offset;
  // Dragging down lifts the eye over the target; the angle from the up axis stays inside (margin, pi - margin).
  const float fromUp = std::acos(std::clamp(glm::dot(glm::normalize(offset), up), -1.0f, 1.0f));
  const float turned = std::clamp(fromUp - dyPixels * radiansPerPixel, kPoleMargin, kPi - kPoleMargin);
  // A positive turn about offset x up tilts the offset towards up.
  const glm::vec3 axis = glm::cross(offset, up);
  if (glm::length(axis) > 1e-6f) offset = glm::angleAxis(fromUp - turned, glm::normalize(axis)) * offset;
  camera.eye = camera.target + offset;
}

void panCamera(Camera& camera, float dxPixels, float dyPixels, int viewportHeight) {
  const glm::vec3 forward = camera.target - camera.eye;
  const float distance = glm::length(forward);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::vec3 screenUp = glm::cross(right, forward / distance);
  const float metresPerPixel =
      2.0f * camera.halfHeightAt(distance, camera.aspect()) / static_cast<float>(std::max(viewportHeight, 1));
  // The point under the cursor follows it: the camera moves against the drag.
  const glm::vec3 shift = (-dxPixels * right + dyPixels * screenUp) * metresPerPixel;
  camera.eye += shift;
  camera.target += shift;
}

void zoomCamera(Camera& camera, float factor, float sceneRadius) {
  const glm::vec3 offset = camera.eye - camera.target;
  const float radius = std::max(sceneRadius, 1e-3f);
  const float before = glm::length(offset);
  const float distance = std::clamp(before * factor, radius * 1e-3f, radius * 1e3f);
  camera.eye = camera.target + glm::normalize(offset) * distance;
  // An orthographic view zooms by its size; it moves with the eye, so that going back to perspective keeps the view.
  if (camera.orthographic) camera.ymag *= distance / before;
}

void fitDepthRange(Camera& camera, const Bounds& scene) {
  const float radius = std::max(scene.empty() ? 1.0f : scene.radius(), 1e-3f) * 1.05f;
  const glm::vec3 center = scene.empty() ? camera.target : scene.center();
  const float distance = glm::length(camera.eye - center);
  camera.far = distance + radius;
  camera.near = std::max(distance - radius, camera.far / kMaxDepthRatio);
}

}  // namespace obscura
