#include "frame/FrameContext.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace obscura {

FrameCamera FrameCamera::from(const Camera& camera, int width, int height, glm::vec2 jitterPixels, float aspect) {
  FrameCamera frame;
  frame.width = width;
  frame.height = height;
  frame.near = camera.near;
  frame.far = camera.far;
  frame.fovyRadians = camera.fovyRadians();
  frame.jitter = jitterPixels;
  if (aspect <= 0.0f) aspect = static_cast<float>(width) / static_cast<float>(height);
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

ReconstructionUniforms::ReconstructionUniforms(const gl::Program& program)
    : farHalfExtent_(program.uniform("u_farHalfExtent")),
      farPlane_(program.uniform("u_farPlane")),
      depthToRay_(program.uniform("u_depthToRay")) {}

void ReconstructionUniforms::set(const ViewReconstruction& r) const {
  gl::Program::set(farHalfExtent_, r.farHalfExtent);
  gl::Program::set(farPlane_, r.far);
  gl::Program::set(depthToRay_, glm::vec2(r.depthScale, r.depthBias));
}

}  // namespace obscura
