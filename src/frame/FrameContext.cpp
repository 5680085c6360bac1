#include "frame/FrameContext.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace obscura {

FrameCamera FrameCamera::from(const Camera& camera, int width, int height, glm::vec2 jitterPixels) {
  FrameCamera frame;
  frame.width = width;
  frame.height = height;
  frame.near = camera.near;
  frame.far = camera.far;
  frame.fovyRadians = camera.fovyRadians();
  frame.jitter = jitterPixels;
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  frame.view = camera.view();
  frame.projection = glm::perspective(frame.fovyRadians, aspect, camera.near, camera.far);
  frame.unjitteredProjection = frame.projection;
  // A jitter of j pixels is 2 j / width in normalised device x. The projection's third column multiplies z_view, and
  // w = -z_view, so subtracting 2 j / width there moves every depth by the same +2 j / width after the division.
  frame.projection[2][0] -= 2.0f * jitterPixels.x / static_cast<float>(width);
  frame.projection[2][1] -= 2.0f * jitterPixels.y / static_cast<float>(height);
  frame.reconstruction = ViewReconstruction::fromPerspective(frame.fovyRadians, aspect, camera.near, camera.far);
  return frame;
}

float FrameCamera::projScale(int targetHeight) const {
  return static_cast<float>(targetHeight) / (2.0f * std::tan(fovyRadians * 0.5f));
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
  program.set("u_farPlane", r.far);
}

void setReconstruction(const gl::Program& program, const ViewReconstruction& r) {
  setFarRay(program, r);
  program.set("u_depthToRay", glm::vec2(r.depthScale, r.depthBias));
}

}  // namespace obscura
