#include "effects/vignette/Vignette.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace obscura {

const std::vector<Parameter<VignetteSettings>>& VignetteSettings::parameters() {
  using S = VignetteSettings;
  static const std::vector<Parameter<S>> table = {
      switchParameter<S>("vignette", "vignette on or off (the light falling off towards the frame's edges)",
                         &S::enabled)
          .primary(),
      numberParameter<S>("intensity", 0, 1, "", "how far in the darkening reaches", &S::intensity).primary(),
      numberParameter<S>("smoothness", 0.01, 1, "", "how gradually it darkens", &S::smoothness).primary(),
      numberParameter<S>("roundness", 0, 1, "", "1: a circle on screen; 0: the frame's shape", &S::roundness)
          .primary()};
  return table;
}

glm::vec3 vignetteShape(const VignetteSettings& s, float aspect) {
  return {3.0f * s.intensity, 1.0f + (aspect - 1.0f) * s.roundness, 5.0f * s.smoothness};
}

float vignetteFactor(glm::vec2 uv, const glm::vec3& shape) {
  glm::vec2 d = glm::abs(uv - 0.5f) * shape.x;
  d.x *= shape.y;
  return std::pow(std::clamp(1.0f - glm::dot(d, d), 0.0f, 1.0f), shape.z);
}

}  // namespace obscura
