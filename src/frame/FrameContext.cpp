#include "frame/FrameContext.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace obscura {

FrameCamera FrameCamera::from(const Camera& camera, int width, int height, glm::vec2 jitterPixels,
                              glm::vec2 shearPixelsPerMetre, float aspect) {
  FrameCamera frame;
  frame.width = width;
  frame.height = height;
  frame.near = camera.near;
  frame.far = camera.far;
  frame.orthographic = camera.orthographic;
  frame.jitter = jitterPixels;
  if (aspect <= 0.0f) aspect = static_cast<float>(width) / static_cast<float>(height);
  frame.halfExtent = camera.halfExtent(aspect);
  frame.view = camera.view();
  frame.projection = camera.projection(aspect);
  frame.unjitteredProjection = frame.projection;
  // A jitter of j pixels is 2 j / width in normalised device x, a shift by that much after the division by w: the
  // projection's row x gains 2 j / width times its row w. In perspective row w is (0, 0, -1, 0), so the third column
  // changes (every depth moves alike once divided by w = -z_view); in orthographic projection w = 1, the fourth.
  const glm::vec2 shift = 2.0f * jitterPixels / glm::vec2(width, height);
  for (int column = 0; column < 4; ++column) {
    frame.projection[column][0] += shift.x * frame.projection[column][3];
    frame.projection[column][1] += shift.y * frame.projection[column][3];
  }
  // The shear: x_ndc += 2 k / width times the view depth -z_view, with w = 1 (orthographic).
  if (camera.orthographic) {
    frame.projection[2][0] -= 2.0f * shearPixelsPerMetre.x / static_cast<float>(width);
    frame.projection[2][1] -= 2.0f * shearPixelsPerMetre.y / static_cast<float>(height);
  }
  frame.reconstruction =
      ViewReconstruction::fromCamera(frame.halfExtent, camera.near, camera.far, camera.orthographic);
  return frame;
}

glm::vec2 FrameCamera::projScale(int targetHeight) const {
  const float scale = static_cast<float>(targetHeight) / (2.0f * halfExtent.y);
  return orthographic ? glm::vec2(0.0f, scale) : glm::vec2(scale, 0.0f);
}

float halton(std::uint32_t index, std::uint32_t base) {
  float result = 0.0f, fraction = 1.0f;
  for (std::uint32_t i = index; i > 0; i /= base) {
    fraction /= static_cast<float>(base);
    result += fraction * static_cast<float>(i % base);
  }
  return result;
}

void setFarRay(const gl::Program& program, const ViewReconstruction& r) {
  program.set("u_farHalfExtent", r.farHalfExtent);
  if (program.has("u_farPlane")) program.set("u_farPlane", r.far);
  if (program.has("u_perspective")) program.set("u_perspective", r.perspective ? 1.0f : 0.0f);
}

void setReconstruction(const gl::Program& program, const ViewReconstruction& r) {
  setFarRay(program, r);
  program.set("u_depthToRay", r.depthToRay);
}

}  // namespace obscura
