#include "effects/chromatic_aberration/ChromaticAberrationEffect.h"

#include "frame/PassContext.h"
#include "gl/PipelineState.h"

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
  return {"chromatic-aberration", "Chromatic aberration", true, false, {"chromatic-aberration"}, {}};
}

std::vector<ProgramSpec> ChromaticAberrationEffect::programSpecs() { return {spec()}; }

const ChromaticAberrationEffect::Program& ChromaticAberrationEffect::program() {
  if (!program_) {
    program_ = std::make_unique<Program>();
    program_->program = resources_.build(spec());
    program_->color = program_->program.uniform("u_color");
    program_->size = program_->program.uniform("u_size");
    program_->shift = program_->program.uniform("u_shift");
    program_->lumaInAlpha = program_->program.uniform("u_lumaInAlpha");
  }
  return *program_;
}

void ChromaticAberrationEffect::plan(FramePlanner& planner) {
  const ChromaticAberrationSettings settings = planner.settings().of<ChromaticAberrationSettings>();
  if (!settings.enabled) return;
  PassDecl pass;
  pass.name = "chromatic-aberration";
  pass.reads = {"display-color"};
  pass.writes = {{"display-color", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
  pass.run = [this](PassContext& context) {
    const float intensity = context.settings().of<ChromaticAberrationSettings>().intensity;
    const Program& p = program();
    context.bindForWriting("display-color");
    p.program.use();
    context.texture("display-color").bind(0);
    gl::Program::set(p.color, 0);
    gl::Program::set(p.size, glm::vec2(context.size("display-color")));
    gl::Program::set(p.shift, aberrationScales(intensity));
    gl::Program::set(p.lumaInAlpha, context.writesOutput("display-color") ? 0.0f : 1.0f);
    resources_.triangle.draw();
    gl::restoreBaselineState();
  };
  planner.add(std::move(pass));
}

}  // namespace obscura
