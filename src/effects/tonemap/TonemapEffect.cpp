#include "effects/tonemap/TonemapEffect.h"

#include "frame/PassContext.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

ProgramSpec spec(ToneMapOperator op, bool autoExposure) {
  return ProgramSpec{std::string("tonemap[") + toneMapOperatorName(op) + (autoExposure ? ",auto-exposure" : "") + "]",
                     "lib/fullscreen.vert",
                     "tonemap/tonemap.frag",
                     {toneMapShaderDefine(op), {"AUTO_EXPOSURE", autoExposure ? "1" : "0"}, {"FAR_RAY", "0"}},
                     {}};
}

}  // namespace

const std::vector<Parameter<TonemapSettings>>& TonemapSettings::parameters() {
  using S = TonemapSettings;
  static const std::vector<Parameter<S>> table = [] {
    std::vector<std::pair<std::string, ToneMapOperator>> operators;
    for (ToneMapOperator curve : kToneMapOperators) operators.emplace_back(toneMapOperatorName(curve), curve);
    return std::vector<Parameter<S>>{
        switchParameter<S>("tonemap", "tone mapping on or off (off: no exposure, no curve: clamped to 0 .. 1)",
                           &S::enabled)
            .primary(),
        choiceParameter<S, ToneMapOperator>("operator", "tone curve", &S::op, operators).primary(),
        numberParameter<S>("exposure", -16, 16, "EV", "exposure: the HDR colour is multiplied by 2^EV", &S::exposure)
            .primary()};
  }();
  return table;
}

ToneMapInUse ToneMapInUse::of(const TonemapSettings& settings) {
  ToneMapInUse use;
  if (settings.enabled) {
    use.op = settings.op;
    use.exposureScale = obscura::exposureScale(settings.exposure);
  }
  return use;
}

glm::vec4 ToneMapInUse::displayColor(const glm::vec3& linearHdr, bool lumaInAlpha) const {
  const glm::vec3 srgb = linearToSrgb(toneMap(op, linearHdr * exposureScale));
  return glm::vec4(srgb, lumaInAlpha ? fxaaLuma(srgb) : 1.0f);
}

EffectInfo TonemapEffect::info() {
  return {"tonemap",
          "Tone mapping",
          true,
          false,
          {"tonemap"},
          {{"display-color", "RGB: display colour, sRGB-encoded; A: its luma (FXAA 3.11's input)", GL_NEAREST,
            {{"display-color", ViewDecoding::Color}}}}};
}

std::vector<ProgramSpec> TonemapEffect::programSpecs() {
  std::vector<ProgramSpec> specs;
  for (ToneMapOperator op : kToneMapOperators)
    for (bool autoExposure : {false, true}) specs.push_back(spec(op, autoExposure));
  return specs;
}

TonemapEffect::Variant::Variant(gl::Program built, bool autoExposure)
    : program(std::move(built)),
      color(program.uniform("u_color")),
      exposure(program.uniform("u_exposure")),
      lumaInAlpha(program.uniform("u_lumaInAlpha")),
      exposureTarget(autoExposure ? program.uniform("u_exposureTarget") : -1) {}

const TonemapEffect::Variant& TonemapEffect::variant(ToneMapOperator op, bool autoExposure) {
  auto it = variants_.find({op, autoExposure});
  if (it == variants_.end())
    it = variants_.emplace(std::make_pair(op, autoExposure),
                           Variant(resources_.build(spec(op, autoExposure)), autoExposure)).first;
  return it->second;
}

void TonemapEffect::plan(FramePlanner& planner) {
  // Off: the same pass without exposure or curve (it still decodes the HDR colour for display).
  // With auto exposure (an earlier effect writes `exposure`), its exposure replaces the manual one.
  const ToneMapInUse use = ToneMapInUse::of(planner.settings().of<TonemapSettings>());
  const bool autoExposure = planner.settings().of<TonemapSettings>().enabled && planner.declares("exposure");
  const ToneMapOperator op = use.op;
  const float exposure = autoExposure ? 1.0f : use.exposureScale;
  PassDecl pass;
  pass.name = "tonemap";
  pass.reads = {"scene-color"};
  if (autoExposure) pass.reads.push_back("exposure");
  pass.writes = {{"display-color", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
  pass.run = [this, op, exposure, autoExposure](PassContext& context) {
    const Variant& v = variant(op, autoExposure);
    context.bindForWriting("display-color");
    v.program.use();
    context.texture("scene-color").bind(0);
    gl::Program::set(v.color, 0);
    gl::Program::set(v.exposure, exposure);
    if (autoExposure) {
      context.texture("exposure").bind(1);
      gl::Program::set(v.exposureTarget, 1);
    }
    gl::Program::set(v.lumaInAlpha, context.writesOutput("display-color") ? 0.0f : 1.0f);
    resources_.triangle.draw();
    gl::restoreBaselineState();
  };
  planner.add(std::move(pass));
}

}  // namespace obscura
