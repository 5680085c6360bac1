#include "effects/dither/Dither.h"

#include <glm/common.hpp>

#include "frame/FramePlan.h"
#include "frame/PixelHash.h"
#include "frame/Stage.h"

namespace obscura {

const std::vector<Parameter<DitherSettings>>& DitherSettings::parameters() {
  using S = DitherSettings;
  static const std::vector<Parameter<S>> table = {
      switchParameter<S>("dither", "dithering before 8-bit quantisation on or off (triangular noise of one step: no "
                         "banding on dark gradients)",
                         &S::enabled)
          .primary()};
  return table;
}

float ditherOffset(glm::vec2 pixel) {
  const float r1 = hash12(pixel), r2 = hash12(pixel + glm::vec2(57.31f, 113.7f));
  return (r1 + r2 - 1.0f) / 255.0f;
}

glm::vec3 dithered(const glm::vec3& srgb, glm::vec2 pixel) {
  const glm::vec3 amplitude = glm::clamp(glm::min(srgb, 1.0f - srgb) * 255.0f, 0.0f, 1.0f);
  return srgb + amplitude * ditherOffset(pixel);
}

EffectInfo DitherEffect::info() { return {"dither", "Dithering", true, false, {"dither"}, {}}; }

StageDecl DitherEffect::stage() {
  return displayStage("dither", 0);  // no uniforms: the pattern is the pixel's
}

void DitherEffect::plan(FramePlanner& planner) {
  if (planner.settings().of<DitherSettings>().enabled) planner.add(stagePass(resources_, stage(), "display-color"));
}

}  // namespace obscura
