#pragma once
// The vignette (shaders_es2/vignette/vignette.glsl): the HDR colour darkened towards the frame's edges before the tone
// curve, as a lens's light falls off towards the edge of its field, after Unity's post-processing stack (v2, the
// "classic" vignette): d = 3 intensity |uv - 1/2|, its x scaled by the aspect ratio as far as `roundness` asks (1: a
// circle on screen, 0: the frame's own shape), factor = (1 - d.d)^(5 smoothness), clamped to [0, 1].
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "frame/Parameters.h"

namespace obscura {

struct VignetteSettings : ParameterAccess<VignetteSettings> {
  bool enabled = false;
  float intensity = 0.35f;
  float smoothness = 0.25f;
  float roundness = 1.0f;

  static const std::vector<Parameter<VignetteSettings>>& parameters();
  void validate() const { validateParameters("vignette"); }
};

// The shader's u_vignetteShape for a frame of `aspect` (width / height), and the factor at uv (CPU mirror).
glm::vec3 vignetteShape(const VignetteSettings& settings, float aspect);
float vignetteFactor(glm::vec2 uv, const glm::vec3& shape);

}  // namespace obscura
