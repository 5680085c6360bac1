#pragma once
// The final, forward-lit image: the scene drawn again with the same vertex stage as the G-buffer pass, lit by one
// directional light and a hemisphere ambient; the blurred AO multiplies the ambient term only. Draws into the
// caller's framebuffer (the antialiased back buffer on the web and desktop, an offscreen target headless).
#include <vector>

#include <glm/vec3.hpp>

#include "core/FrameContext.h"
#include "core/GpuScene.h"
#include "core/ShaderLibrary.h"
#include "gl/RenderTarget.h"

namespace obscura {

struct Lighting {
  // An overcast key light over a strong sky dome: ambient carries most of the light, so AO reads clearly.
  glm::vec3 directionToLight{0.45f, 0.8f, 0.35f};  // world space, normalised when used
  glm::vec3 lightColor{0.50f, 0.48f, 0.44f};
  glm::vec3 skyColor{0.62f, 0.66f, 0.72f};
  glm::vec3 groundColor{0.30f, 0.28f, 0.26f};
  glm::vec3 background{0.62f, 0.67f, 0.73f};  // display-encoded clear colour
};

class LightingPass {
 public:
  static std::vector<ProgramSpec> programSpecs();

  LightingPass();
  // `ao`: the blurred AO, sampled at gl_FragCoord / viewport. AO applies right of `aoSplitX` pixels (0: the whole
  // image; the viewport width or more: nowhere).
  void render(const GpuScene& scene, const FrameCamera& camera, const Lighting& lighting, const gl::Texture2D& ao,
              float aoSplitX);

 private:
  gl::Program program_;
};

}  // namespace obscura
