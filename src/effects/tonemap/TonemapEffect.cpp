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

StageDecl TonemapEffect::stage(ToneMapOperator op, bool autoExposure, bool lensLight) {
  StageDecl stage;
  stage.name = "tonemap";
  stage.variant = std::string(toneMapOperatorName(op)) + (autoExposure ? ",auto-exposure" : "") +
                  (lensLight ? ",lens-light" : "");
  stage.file = "tonemap/tonemap.glsl";
  stage.function = "tonemapStage";
  stage.defines = {toneMapShaderDefine(op),
                   {"AUTO_EXPOSURE", autoExposure ? "1" : "0"},
                   {"LENS_LIGHT", lensLight ? "1" : "0"}};
  stage.input = "scene-color";
  stage.outputSpace = ColorSpace::Display;
  // Auto exposure's 1 x 1 result and the light the lens adds, read beside the colour (so the stage runs in a pass
  // after theirs: it cannot fuse into the lighting, which runs before them).
  if (autoExposure) stage.textures.push_back({"u_exposureTarget", "exposure"});
  if (lensLight) stage.textures.push_back({"u_lensLight", "lens-light"});
  // u_exposure and the output's u_lumaInAlpha: two floats, which take the spare columns of the rows of the programs
  // it fuses into; with the lens light, its size (a vec2) takes one row more at most
  // (Shaders.FusedStagesTakeNoMoreUniformVectorsThanTheyDeclare holds it).
  stage.uniformVectors = lensLight ? 1 : 0;
  stage.uniforms = [autoExposure, lensLight](const gl::Program& program, const PassContext& context) {
    // With auto exposure, its exposure replaces the manual one.
    program.set("u_exposure",
                autoExposure ? 1.0f : ToneMapInUse::of(context.settings().of<TonemapSettings>()).exposureScale);
    if (lensLight) program.set("u_lensLightSize", glm::vec2(context.size("lens-light")));
  };
  return stage;
}

std::vector<StageDecl> TonemapEffect::stages() {
  std::vector<StageDecl> stages;
  for (ToneMapOperator op : kToneMapOperators)
    for (bool autoExposure : {false, true})
      for (bool lensLight : {false, true}) stages.push_back(stage(op, autoExposure, lensLight));
  return stages;
}

void TonemapEffect::plan(FramePlanner& planner) {
  // Off: the same stage without exposure or curve (it still decodes the HDR colour for display). A per-pixel stage:
  // it runs inside the pass before it (the lighting, the fog) where nothing else reads the HDR colour.
  // With auto exposure (an earlier effect writes `exposure`), its exposure replaces the manual one. The light the
  // lens adds (`lens-light`: the lens flare, the glare), at 1/4 of the frame, is added before the exposure.
  const TonemapSettings& settings = planner.settings().of<TonemapSettings>();
  const bool autoExposure = settings.enabled && planner.declares("exposure");
  const bool lensLight = planner.declares("lens-light");
  planner.add(stagePass(resources_, stage(ToneMapInUse::of(settings).op, autoExposure, lensLight), "display-color"));
}

}  // namespace obscura
