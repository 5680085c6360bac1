#include "effects/grain/Grain.h"

#include <algorithm>
#include <cmath>

#include "encoding/ToneMapping.h"
#include "frame/PassContext.h"
#include "frame/PixelHash.h"
#include "frame/Stage.h"

namespace obscura {

const std::vector<Parameter<GrainSettings>>& GrainSettings::parameters() {
  using S = GrainSettings;
  static const std::vector<Parameter<S>> table = {
      switchParameter<S>("grain", "film grain on or off (noise on the display colour, new each frame)", &S::enabled)
          .primary(),
      numberParameter<S>("intensity", 0, 1, "", "the grain's amplitude in the darkest tones", &S::intensity)
          .primary(),
      numberParameter<S>("size", 0.5, 8, "px", "the grain's cells", &S::size).primary()};
  return table;
}

glm::vec4 grainUniform(const GrainSettings& s, std::uint64_t frameIndex) {
  // A frame's offset: far apart in the noise's plane from one frame to the next, in a range where float keeps the
  // cells exact (the index wraps after 2^16 frames).
  const float f = static_cast<float>(frameIndex % 65536);
  return {s.intensity, 1.0f / s.size, 1000.0f * hash12({f, 0.5f}), 1000.0f * hash12({0.5f, f})};
}

float grainNoise(glm::vec2 p) {
  const glm::vec2 cell = glm::floor(p);
  glm::vec2 f = p - cell;
  f = f * f * (3.0f - 2.0f * f);
  const float a = hash12(cell), b = hash12(cell + glm::vec2(1.0f, 0.0f));
  const float c = hash12(cell + glm::vec2(0.0f, 1.0f)), d = hash12(cell + glm::vec2(1.0f, 1.0f));
  const float top = a + (b - a) * f.x, bottom = c + (d - c) * f.x;
  return 2.0f * (top + (bottom - top) * f.y) - 1.0f;
}

glm::vec3 grained(const glm::vec3& srgb, glm::vec2 pixel, const glm::vec4& u) {
  const float n = grainNoise(pixel * u.y + glm::vec2(u.z, u.w));
  const float response = 1.0f - std::sqrt(std::clamp(fxaaLuma(srgb), 0.0f, 1.0f));
  return srgb + glm::vec3(u.x * response * n);
}

EffectInfo GrainEffect::info() { return {"grain", "Film grain", true, false, {"grain"}, {}}; }

StageDecl GrainEffect::stage() {
  StageDecl stage = displayStage("grain", 1);  // u_grain
  stage.uniforms = [](const gl::Program& program, const PassContext& context) {
    program.set("u_grain", grainUniform(context.settings().of<GrainSettings>(), context.frame().index));
  };
  return stage;
}

void GrainEffect::plan(FramePlanner& planner) {
  if (planner.settings().of<GrainSettings>().enabled) planner.add(stagePass(resources_, stage(), "display-color"));
}

}  // namespace obscura
