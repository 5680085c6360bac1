#pragma once
// What every pass of one frame shares: the camera's matrices and reconstruction constants, and the full-screen
// triangle the image-space passes draw.
#include <glm/mat4x4.hpp>

#include "core/ViewReconstruction.h"
#include "gl/GlObjects.h"
#include "gl/Program.h"
#include "scene/Camera.h"

namespace obscura {

struct FrameCamera {
  glm::mat4 view{1.0f}, projection{1.0f};
  ViewReconstruction reconstruction;
  float near = 0.1f, far = 100.0f, fovyRadians = 1.0f;
  int width = 1, height = 1;  // the output size; the camera's aspect follows it

  static FrameCamera from(const Camera& camera, int width, int height);
  // Pixels per metre at 1 m in front of the camera, for a target `targetHeight` pixels tall.
  float projScale(int targetHeight) const;
};

// Sets the uniforms of shaders_es2/lib/reconstruct.glsl.
void setReconstructionUniforms(const gl::Program& program, const ViewReconstruction& reconstruction);

// One triangle covering the viewport (attribute slot 0: a_position, clip-space xy).
class FullscreenTriangle {
 public:
  FullscreenTriangle();
  void draw() const;

 private:
  gl::BufferHandle vertices_;
};

}  // namespace obscura
