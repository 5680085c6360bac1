#include "effects/fxaa/FxaaEffect.h"

#include <map>

#include "frame/PassContext.h"
#include "gl/PipelineState.h"

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

// quality 0: the classifying draw, which has no search.
ProgramSpec spec(int quality) {
  if (quality == 0)
    return ProgramSpec{"fxaa[classify]", "lib/fullscreen.vert", "fxaa/fxaa.frag",
                       {{"FXAA_CLASSIFY", "1"}, {"FAR_RAY", "0"}},
                       {}};
  return ProgramSpec{"fxaa[quality=" + std::to_string(quality) + "]",
                     "lib/fullscreen.vert",
                     "fxaa/fxaa.frag",
                     {{"FXAA_CLASSIFY", "0"},
                      {"FXAA_SEARCH_STEPS", std::to_string(fxaaSearchSteps(quality).size())},
                      {"FAR_RAY", "0"}},
                     {}};
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
                                  "quality preset: search steps (Lottes' preset 10, 12, 29, 39) and edge thresholds",
                                  ParameterKind::Choice, 0.0, 0.0, presetNames},
                                 {}, {}, {}, {}};
    presetParameter.set = [](S& s, const std::string& v) { s.applyPreset(parsePreset(v)); };
    presetParameter.get = [](const S& s) {
      return s.matchesPreset(s.preset) ? std::string(presetName(s.preset)) : "";
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

void FxaaSettings::applyPreset(QualityPreset which) {
  for (const FxaaPreset& p : kPresets)
    if (p.preset == which) {
      preset = which;
      quality = p.quality;
      edgeThreshold = p.edgeThreshold;
      edgeThresholdMin = p.edgeThresholdMin;
    }
}

bool FxaaSettings::matchesPreset(QualityPreset which) const {
  for (const FxaaPreset& p : kPresets)
    if (p.preset == which)
      return preset == which && quality == p.quality && edgeThreshold == p.edgeThreshold &&
             edgeThresholdMin == p.edgeThresholdMin;
  return false;
}

EffectInfo FxaaEffect::info() { return {"fxaa", "FXAA", true, false, {"fxaa"}, {}}; }

std::vector<ProgramSpec> FxaaEffect::programSpecs() {
  std::vector<ProgramSpec> specs = {spec(0)};
  for (const auto& [lottes, steps] : searchStepTable()) specs.push_back(spec(lottes));
  return specs;
}

FxaaEffect::Variant::Variant(gl::Program built, int quality)
    : program(std::move(built)),
      color(program.uniform("u_color")),
      texel(program.uniform("u_texel")),
      edgeThreshold(program.uniform("u_edgeThreshold")),
      edgeThresholdMin(program.uniform("u_edgeThresholdMin")) {
  if (quality == 0) return;
  size = program.uniform("u_size");
  subpix = program.uniform("u_subpix");
  // The step table is the preset's constant: set once, it stays with the program.
  const std::vector<float>& steps = fxaaSearchSteps(quality);
  program.use();
  glUniform1fv(program.uniform("u_searchSteps[0]"), static_cast<GLsizei>(steps.size()), steps.data());
  glUseProgram(0);
}

const FxaaEffect::Variant& FxaaEffect::variant(int quality) {
  auto it = variants_.find(quality);
  if (it == variants_.end()) it = variants_.emplace(quality, Variant(resources_.build(spec(quality)), quality)).first;
  return it->second;
}

void FxaaEffect::plan(FramePlanner& planner) {
  const FxaaSettings settings = planner.settings().of<FxaaSettings>();
  if (!settings.enabled) return;
  PassDecl pass;
  pass.name = "fxaa";
  pass.reads = {"display-color"};
  pass.writes = {{"display-color", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
  pass.run = [this, settings](PassContext& context) {
    const gl::Texture2D& input = context.texture("display-color");
    const glm::vec2 size(static_cast<float>(input.width()), static_cast<float>(input.height()));
    context.bindForWriting("display-color");
    input.bind(0);
    GLint stencilBits = 0;
    glGetIntegerv(GL_STENCIL_BITS, &stencilBits);
    if (stencilBits > 0 && resources_.options.allowFxaaStencil) {
      // Stencil 1 everywhere (within the output's region: the clear is scissored like the draws); the classifying
      // draw sets 0 where it writes, and discards the edge pixels, which keep 1.
      glEnable(GL_STENCIL_TEST);
      glClearStencil(1);
      glClear(GL_STENCIL_BUFFER_BIT);
      glStencilFunc(GL_ALWAYS, 0, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
      draw(variant(0), settings, size);
      glStencilFunc(GL_EQUAL, 1, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    }
    draw(variant(settings.quality), settings, size);
    gl::restoreBaselineState();
  };
  planner.add(std::move(pass));
}

void FxaaEffect::draw(const Variant& v, const FxaaSettings& settings, glm::vec2 size) const {
  v.program.use();
  gl::Program::set(v.color, 0);
  gl::Program::set(v.texel, 1.0f / size);
  gl::Program::set(v.edgeThreshold, settings.edgeThreshold);
  gl::Program::set(v.edgeThresholdMin, settings.edgeThresholdMin);
  if (v.size >= 0) {
    gl::Program::set(v.size, size);
    gl::Program::set(v.subpix, settings.subpix);
  }
  resources_.triangle.draw();
}

}  // namespace obscura
