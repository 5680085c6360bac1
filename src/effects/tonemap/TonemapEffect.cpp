#include "effects/tonemap/TonemapEffect.h"

#include "frame/PassContext.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

ProgramSpec spec(ToneMapOperator op, bool autoExposure, bool lensLight) {
  return ProgramSpec{std::string("tonemap[") + toneMapOperatorName(op) + (autoExposure ? ",auto-exposure" : "") +
                         (lensLight ? ",lens-light" : "") + "]",
                     "lib/fullscreen.vert",
                     "tonemap/tonemap.frag",
                     {toneMapShaderDefine(op),
                      {"AUTO_EXPOSURE", autoExposure ? "1" : "0"},
                      {"LENS_LIGHT", lensLight ? "1" : "0"},
                      {"FAR_RAY", "0"}},
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
    for (bool autoExposure : {false, true})
      for (bool lensLight : {false, true}) specs.push_back(spec(op, autoExposure, lensLight));
  return specs;
}

TonemapEffect::Variant::Variant(gl::Program built, bool autoExposure, bool addsLensLight)
    : program(std::move(built)),
      color(program.uniform("u_color")),
      exposure(program.uniform("u_exposure")),
      lumaInAlpha(program.uniform("u_lumaInAlpha")),
      exposureTarget(autoExposure ? program.uniform("u_exposureTarget") : -1),
      lensLight(addsLensLight ? program.uniform("u_lensLight") : -1),
      lensLightSize(addsLensLight ? program.uniform("u_lensLightSize") : -1) {}

const TonemapEffect::Variant& TonemapEffect::variant(ToneMapOperator op, bool autoExposure, bool lensLight) {
  const auto key = std::make_tuple(op, autoExposure, lensLight);
  auto it = variants_.find(key);
  if (it == variants_.end())
    it = variants_.emplace(key, Variant(resources_.build(spec(op, autoExposure, lensLight)), autoExposure, lensLight))
             .first;
  return it->second;
}

void TonemapEffect::plan(FramePlanner& planner) {
  // Off: the same pass without exposure or curve (it still decodes the HDR colour for display).
  // With auto exposure (an earlier effect writes `exposure`), its exposure replaces the manual one. The light the
  // lens adds (`lens-light`: the lens flare, the glare), at 1/4 of the frame, is added before the exposure.
  const ToneMapInUse use = ToneMapInUse::of(planner.settings().of<TonemapSettings>());
  const bool autoExposure = planner.settings().of<TonemapSettings>().enabled && planner.declares("exposure");
  const bool lensLight = planner.declares("lens-light");
  const ToneMapOperator op = use.op;
  const float exposure = autoExposure ? 1.0f : use.exposureScale;
  PassDecl pass;
  pass.name = "tonemap";
  pass.reads = {"scene-color"};
  if (autoExposure) pass.reads.push_back("exposure");
  if (lensLight) pass.reads.push_back("lens-light");
  pass.writes = {{"display-color", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
  pass.run = [this, op, exposure, autoExposure, lensLight](PassContext& context) {
    const Variant& v = variant(op, autoExposure, lensLight);
    context.bindForWriting("display-color");
    v.program.use();
    context.texture("scene-color").bind(0);
    gl::Program::set(v.color, 0);
    gl::Program::set(v.exposure, exposure);
    if (autoExposure) {
      context.texture("exposure").bind(1);
      gl::Program::set(v.exposureTarget, 1);
    }
    if (lensLight) {
      context.texture("lens-light").bind(2);
      gl::Program::set(v.lensLight, 2);
      gl::Program::set(v.lensLightSize, glm::vec2(context.size("lens-light")));
    }
    gl::Program::set(v.lumaInAlpha, context.writesOutput("display-color") ? 0.0f : 1.0f);
    resources_.triangle.draw();
    gl::restoreBaselineState();
  };
  planner.add(std::move(pass));
}

}  // namespace obscura
