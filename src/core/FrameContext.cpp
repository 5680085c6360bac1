#include "core/FrameContext.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace obscura {

FrameCamera FrameCamera::from(const Camera& camera, int width, int height) {
  FrameCamera frame;
  frame.width = width;
  frame.height = height;
  frame.near = camera.near;
  frame.far = camera.far;
  frame.fovyRadians = camera.fovyRadians();
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  frame.view = camera.view();
  frame.projection = glm::perspective(frame.fovyRadians, aspect, camera.near, camera.far);
  frame.reconstruction = ViewReconstruction::fromPerspective(frame.fovyRadians, aspect, camera.near, camera.far);
  return frame;
}

float FrameCamera::projScale(int targetHeight) const {
  return static_cast<float>(targetHeight) / (2.0f * std::tan(fovyRadians * 0.5f));
}

void setReconstructionUniforms(const gl::Program& program, const ViewReconstruction& r) {
  program.set("u_farHalfExtent", r.farHalfExtent);
  program.set("u_farPlane", r.far);
  program.set("u_depthToRay", glm::vec2(r.depthScale, r.depthBias));
}

FullscreenTriangle::FullscreenTriangle() : vertices_(gl::BufferHandle::create()) {
  const float corners[6] = {-1.0f, -1.0f, 3.0f, -1.0f, -1.0f, 3.0f};
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.id());
  glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void FullscreenTriangle::draw() const {
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.id());
  glEnableVertexAttribArray(gl::kAttribPosition);
  glVertexAttribPointer(gl::kAttribPosition, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisableVertexAttribArray(gl::kAttribPosition);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

}  // namespace obscura
