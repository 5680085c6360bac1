#include "effects/vignette/Vignette.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "encoding/ToneMapping.h"
#include "frame/PassContext.h"
#include "frame/Stage.h"

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

glm::vec3 vignetted(const glm::vec3& srgb, glm::vec2 uv, const glm::vec3& shape) {
  return linearToSrgb(srgbToLinear(glm::clamp(srgb, 0.0f, 1.0f)) * vignetteFactor(uv, shape));
}

EffectInfo VignetteEffect::info() { return {"vignette", "Vignette", true, false, {"vignette"}, {}}; }

StageDecl VignetteEffect::stage() {
  StageDecl stage = displayStage("vignette", 1);  // u_vignetteShape
  stage.uniforms = [](const gl::Program& program, const PassContext& context) {
    const FrameCamera& camera = context.camera();
    const float aspect = static_cast<float>(camera.width) / static_cast<float>(camera.height);
    program.set("u_vignetteShape", vignetteShape(context.settings().of<VignetteSettings>(), aspect));
  };
  return stage;
}

void VignetteEffect::plan(FramePlanner& planner) {
  if (planner.settings().of<VignetteSettings>().enabled)
    planner.add(stagePass(resources_, stage(), "display-color"));
}

}  // namespace obscura
