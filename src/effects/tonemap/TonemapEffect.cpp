#include "effects/tonemap/TonemapEffect.h"

#include "frame/PassContext.h"
#include "frame/Stage.h"

namespace obscura {

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

StageDecl TonemapEffect::stage(ToneMapOperator op) {
  StageDecl stage;
  stage.name = "tonemap";
  stage.variant = toneMapOperatorName(op);
  stage.file = "tonemap/tonemap.glsl";
  stage.function = "tonemapStage";
  stage.defines = {toneMapShaderDefine(op)};
  stage.input = "scene-color";
  stage.outputSpace = ColorSpace::Display;
  // u_exposure and the output's u_lumaInAlpha: two floats, which take the spare columns of the rows of the programs
  // it fuses into (Shaders.FusedStagesTakeNoMoreUniformVectorsThanTheyDeclare holds it).
  stage.uniformVectors = 0;
  stage.uniforms = [](const gl::Program& program, const PassContext& context) {
    program.set("u_exposure", ToneMapInUse::of(context.settings().of<TonemapSettings>()).exposureScale);
  };
  return stage;
}

std::vector<StageDecl> TonemapEffect::stages() {
  std::vector<StageDecl> stages;
  for (ToneMapOperator op : kToneMapOperators) stages.push_back(stage(op));
  return stages;
}

void TonemapEffect::plan(FramePlanner& planner) {
  // Off: the same stage without exposure or curve (it still decodes the HDR colour for display). A per-pixel stage:
  // it runs inside the pass before it (the lighting, the fog) where nothing else reads the HDR colour.
  planner.add(stagePass(resources_, stage(ToneMapInUse::of(planner.settings().of<TonemapSettings>()).op),
                        "display-color"));
}

}  // namespace obscura
