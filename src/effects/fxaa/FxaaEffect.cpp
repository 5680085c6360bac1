#include "effects/fxaa/FxaaEffect.h"

#include <map>

#include "frame/FramePlan.h"
#include "frame/PassContext.h"

namespace obscura {
namespace {

// FXAA 3.11's quality presets (Fxaa3_11.h, "FXAA QUALITY - PRESETS"): 10 .. 15 medium dither, 20 .. 29 less dither,
// 39 no dither; the last digit grows with the number of steps.
const std::map<int, std::vector<float>>& searchStepTable() {
  static const std::map<int, std::vector<float>> table = {
      {10, {1.5f, 3.0f, 12.0f}},
      {11, {1.0f, 1.5f, 3.0f, 12.0f}},
      {12, {1.0f, 1.5f, 2.0f, 4.0f, 12.0f}},
      {13, {1.0f, 1.5f, 2.0f, 2.0f, 4.0f, 12.0f}},
      {14, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
      {15, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
      {20, {1.5f, 2.0f, 8.0f}},
      {21, {1.0f, 1.5f, 2.0f, 8.0f}},
      {22, {1.0f, 1.5f, 2.0f, 2.0f, 8.0f}},
      {23, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 8.0f}},
      {24, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 3.0f, 8.0f}},
      {25, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {26, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {27, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {28, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {29, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {39, {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
  };
  return table;
}

// The frame's quality presets as FXAA settings: Lottes' step tables and his suggested thresholds (Fxaa3_11.h,
// fxaaQualityEdgeThreshold "0.250 low quality, 0.166 default, 0.125 high quality, 0.063 overkill";
// fxaaQualityEdgeThresholdMin "0.0833 upper limit (default), 0.0625 high quality, 0.0312 visible limit").
struct FxaaPreset {
  QualityPreset preset;
  int quality;
  float edgeThreshold, edgeThresholdMin;
};
constexpr FxaaPreset kPresets[] = {
    {QualityPreset::Low, 10, 0.25f, 0.0833f},
    {QualityPreset::Medium, 12, 0.166f, 0.0833f},
    {QualityPreset::High, 29, 0.125f, 0.0625f},
    {QualityPreset::Ultra, 39, 0.063f, 0.0312f},
};

// quality 0: the classifying draw, which has no search; kPassThrough: every pixel as FXAA leaves one below its
// threshold (the draw around the scene's bounds on screen). `upscale`: the upscale the pass does too (null: none).
constexpr int kPassThrough = -1;

ProgramSpec spec(int quality, const ResolutionSettings* upscale = nullptr) {
  std::vector<std::pair<std::string, std::string>> defines = {{"FXAA_CLASSIFY", quality <= 0 ? "1" : "0"},
                                                              {"FXAA_PASS_THROUGH", quality < 0 ? "1" : "0"},
                                                              {"FAR_RAY", "0"}};
  if (quality > 0) defines.emplace_back("FXAA_SEARCH_STEPS", std::to_string(fxaaSearchSteps(quality).size()));
  std::string name = quality < 0    ? "fxaa[pass-through"
                     : quality == 0 ? "fxaa[classify"
                                    : "fxaa[quality=" + std::to_string(quality);
  if (upscale) {
    for (const auto& define : upscaleShaderDefines(*upscale)) defines.push_back(define);
    name += ",upscale=" + upscaleVariantName(*upscale);
  }
  return ProgramSpec{name + "]", "lib/fullscreen.vert", "fxaa/fxaa.frag", defines, {}};
}

}  // namespace

const std::vector<float>& fxaaSearchSteps(int quality) {
  const auto it = searchStepTable().find(quality);
  if (it == searchStepTable().end())
    throw InputError("fxaa.quality: " + std::to_string(quality) + " is not one of Lottes' presets");
  return it->second;
}

const std::vector<Parameter<FxaaSettings>>& FxaaSettings::parameters() {
  using S = FxaaSettings;
  static const std::vector<Parameter<S>> table = [] {
    std::vector<std::string> presetNames;
    for (QualityPreset p : allQualityPresets()) presetNames.push_back(presetName(p));
    Parameter<S> presetParameter{{"preset", parse::joinChoices(presetNames, " | "),
                                  "quality preset: search steps (Lottes' preset 10, 12, 29, 39) and edge thresholds "
                                  "(the frame's preset low also turns FXAA off)",
                                  ParameterKind::Choice, 0.0, 0.0, presetNames},
                                 {}, {}, {}, {}, {}};
    presetParameter.set = [](S& s, const std::string& v) { s.applySettingsOf(parsePreset(v)); };
    presetParameter.get = [](const S& s) {
      return s.settingsMatch(s.preset) ? std::string(presetName(s.preset)) : "";
    };
    presetParameter.valid = [](const S&) { return true; };

    std::vector<std::pair<std::string, int>> qualities;
    for (const auto& [lottes, steps] : searchStepTable()) qualities.emplace_back(std::to_string(lottes), lottes);
    return std::vector<Parameter<S>>{
        switchParameter<S>("fxaa", "FXAA antialiasing on or off", &S::enabled).primary(),
        std::move(presetParameter).primary(),
        choiceParameter<S, int>("quality", "Lottes' FXAA_QUALITY__PRESET: the edge search's steps", &S::quality,
                                qualities),
        numberParameter<S>("subpix", 0, 1, "", "subpixel aliasing removal (0 sharp .. 1 soft)", &S::subpix),
        numberParameter<S>("edge-threshold", 0.063, 0.333, "", "least local contrast processed, relative to the luma",
                           &S::edgeThreshold),
        numberParameter<S>("edge-threshold-min", 0, 0.0833, "", "least local contrast processed, absolute (darks)",
                           &S::edgeThresholdMin)};
  }();
  return table;
}

// The frame's `preset low` turns FXAA off: on the weak devices it is for, FXAA's full-screen pass costs about as much
// as the lit frame (on SwiftShader, docs/benchmarks.md) for 6 to 15 % of the error against a supersampled frame, and
// without it the lighting draws straight into the canvas (FrameContext::outputDepth). `fxaa.preset low` alone keeps
// FXAA on with Lottes' preset 10 (which the frame's low preset also sets, for `fxaa on` after it).
namespace {
bool fxaaRunsAt(QualityPreset which) { return which != QualityPreset::Low; }
}  // namespace

void FxaaSettings::applySettingsOf(QualityPreset which) {
  for (const FxaaPreset& p : kPresets)
    if (p.preset == which) {
      preset = which;
      quality = p.quality;
      edgeThreshold = p.edgeThreshold;
      edgeThresholdMin = p.edgeThresholdMin;
    }
}

bool FxaaSettings::settingsMatch(QualityPreset which) const {
  for (const FxaaPreset& p : kPresets)
    if (p.preset == which)
      return preset == which && quality == p.quality && edgeThreshold == p.edgeThreshold &&
             edgeThresholdMin == p.edgeThresholdMin;
  return false;
}

void FxaaSettings::applyPreset(QualityPreset which) {
  applySettingsOf(which);
  enabled = fxaaRunsAt(which);
}

bool FxaaSettings::matchesPreset(QualityPreset which) const {
  return settingsMatch(which) && enabled == fxaaRunsAt(which);
}

EffectInfo FxaaEffect::info() {
  EffectInfo info{"fxaa", "FXAA", true, false, {"fxaa"}, {}};
  info.waitsForFullFrame = true;
  return info;
}

std::vector<ProgramSpec> FxaaEffect::programSpecs() {
  std::vector<ProgramSpec> specs = {spec(0), spec(kPassThrough)};
  for (const auto& [lottes, steps] : searchStepTable()) specs.push_back(spec(lottes));
  for (const ResolutionSettings& upscale : upscaleVariants()) {
    specs.push_back(spec(0, &upscale));
    specs.push_back(spec(kPassThrough, &upscale));
    for (const auto& [lottes, steps] : searchStepTable()) specs.push_back(spec(lottes, &upscale));
  }
  return specs;
}

void FxaaEffect::plan(FramePlanner& planner) {
  const FxaaSettings& settings = planner.settings().of<FxaaSettings>();
  if (!settings.enabled) return;
  PassDecl pass;
  pass.name = "fxaa";
  pass.reads = {"display-color"};
  pass.writes = {{"display-color", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
  const ProgramSpec full = spec(settings.quality), classify = spec(0), passThrough = spec(kPassThrough);
  pass.programs = {passThrough.name, classify.name, full.name};
  pass.run = run(full, classify, passThrough, "display-color", false);
  if (planner.frame().upscaled()) {
    // The frame renders below the output's size: FXAA and the upscale in one pass over the output, where nothing
    // else reads FXAA's result (a retained display colour keeps the two passes).
    const ResolutionSettings& upscale = planner.settings().of<ResolutionSettings>();
    PassDecl::Alternative both;
    both.absorbing = "upscale";
    both.mayWriteOutput = true;
    both.reads = {"display-color"};
    both.writes = {{kOutputTarget, TargetSize::full(), PassDecl::Write::Depth::None, ""}};
    both.run = run(spec(settings.quality, &upscale), spec(0, &upscale), spec(kPassThrough, &upscale), kOutputTarget,
                   true);
    pass.alternatives.push_back(std::move(both));
  }
  planner.add(std::move(pass));
}

std::function<void(PassContext&)> FxaaEffect::run(ProgramSpec full, ProgramSpec classify, ProgramSpec passThrough,
                                                  std::string output, bool upscales) const {
  return [this, full, classify, passThrough, output, upscales](PassContext& context) {
    const FxaaSettings& fxaa = context.settings().of<FxaaSettings>();
    // The source's texel (FXAA's steps are in its pixels, also where the pass writes the larger output).
    const glm::vec2 texel = context.texelSize("display-color");
    auto draw = [&](const ProgramSpec& spec) {
      FullscreenDraw d = context.draw(spec);
      d.read("u_color", "display-color");
      // The pass-through tests no threshold, and reads the texel's size only to upscale.
      if (&spec != &passThrough || d.program().has("u_texel")) d.set("u_texel", texel);
      if (&spec != &passThrough) {
        d.set("u_edgeThreshold", fxaa.edgeThreshold);
        d.set("u_edgeThresholdMin", fxaa.edgeThresholdMin);
      }
      // The full draw's, and an upscaling one's (the size the upscale's own pass takes: the texel's exact inverse).
      if (d.program().has("u_size")) d.set("u_size", glm::vec2(context.size("display-color")));
      if (&spec == &full) {
        d.set("u_subpix", fxaa.subpix);
        // The preset's step table: the program's constant (uploaded when it changes, once).
        const std::vector<float>& steps = fxaaSearchSteps(fxaa.quality);
        d.set("u_searchSteps", steps.data(), static_cast<int>(steps.size()));
      }
      // The edge upscale's sharpening (its variants with UPSCALE_SHARPEN).
      if (upscales && d.program().has("u_sharpness"))
        d.set("u_sharpness", context.settings().of<ResolutionSettings>().sharpness);
      d.draw();
    };
    context.bindForWriting(output);
    // Around the scene's bounds on screen the pixels are the environment's background, a magnified image filtered
    // bilinearly, with no geometric edge to antialias: they are copied (upscaled) as they are, and FXAA runs within
    // the bounds, whose margin holds every pixel next to the scene's edges that FXAA moves.
    context.drawAroundScene(output, [&] { draw(passThrough); });
    // Only the output has a stencil buffer: the pooled display colour has no depth (the plan above). The quick
    // start's small output has none even so; there the stencil test passes everywhere (GLES 2.0 sec. 4.1.5) and the
    // full draw covers the classifying one, which warms both programs.
    const bool stencil = context.writesOutput(output) && context.frame().outputStencil;
    if (stencil && resources_.options.allowFxaaStencil) {
      // Stencil 1 everywhere (within the output's region: the clear is scissored like the draws); the classifying
      // draw sets 0 where it writes, and discards the edge pixels, which keep 1.
      glEnable(GL_STENCIL_TEST);
      glClearStencil(1);
      glClear(GL_STENCIL_BUFFER_BIT);
      glStencilFunc(GL_ALWAYS, 0, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
      draw(classify);
      glStencilFunc(GL_EQUAL, 1, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
      draw(full);
      glDisable(GL_STENCIL_TEST);
      glStencilFunc(GL_ALWAYS, 0, 0xFF);
      glClearStencil(0);
    } else {
      draw(full);
    }
  };
}

}  // namespace obscura
