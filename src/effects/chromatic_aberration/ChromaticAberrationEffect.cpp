#include "effects/chromatic_aberration/ChromaticAberrationEffect.h"

#include "frame/FullscreenPass.h"
#include "frame/PassContext.h"

namespace obscura {
namespace {

ProgramSpec spec() {
  return ProgramSpec{"chromatic-aberration", "lib/fullscreen.vert", "chromatic_aberration/chromatic_aberration.frag",
                     {{"FAR_RAY", "0"}}};
}

}  // namespace

const std::vector<Parameter<ChromaticAberrationSettings>>& ChromaticAberrationSettings::parameters() {
  using S = ChromaticAberrationSettings;
  static const std::vector<Parameter<S>> table = {
      switchParameter<S>("chromatic-aberration", "chromatic aberration on or off (red and blue fringes growing "
                         "towards the edges; a pass of its own)",
                         &S::enabled)
          .primary(),
      numberParameter<S>("intensity", 0, 0.05, "", "red and blue's shift at a pixel, as a fraction of its distance "
                         "from the centre", &S::intensity)
          .primary()};
  return table;
}

glm::vec2 aberrationScales(float intensity) { return {1.0f / (1.0f + intensity), 1.0f / (1.0f - intensity)}; }

glm::vec2 aberrationSource(glm::vec2 uv, int channel, float intensity) {
  const glm::vec2 scales = aberrationScales(intensity);
  const float scale = channel == 0 ? scales.x : channel == 2 ? scales.y : 1.0f;
  return 0.5f + (uv - 0.5f) * scale;
}

EffectInfo ChromaticAberrationEffect::info() {
  EffectInfo info{"chromatic-aberration", "Chromatic aberration", true, false, {"chromatic-aberration"}, {}};
  info.waitsForFullFrame = true;
  return info;
}

std::vector<ProgramSpec> ChromaticAberrationEffect::programSpecs() { return {spec()}; }

void ChromaticAberrationEffect::plan(FramePlanner& planner) {
  if (!planner.settings().of<ChromaticAberrationSettings>().enabled) return;
  planner.add(fullscreenPass("chromatic-aberration", spec(), {{"u_color", "display-color"}}, {"display-color"},
                             [](FullscreenDraw& draw, const PassContext& context) {
                               const float intensity = context.settings().of<ChromaticAberrationSettings>().intensity;
                               draw.set("u_size", glm::vec2(context.size("display-color")));
                               draw.set("u_shift", aberrationScales(intensity));
                               draw.set("u_lumaInAlpha", context.writesOutput("display-color") ? 0.0f : 1.0f);
                             }));
}

}  // namespace obscura
