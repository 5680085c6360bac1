#include "effects/dof/DepthOfFieldEffect.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include "base/Text.h"
#include "frame/PassContext.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

using Write = PassDecl::Write;

constexpr float kReferenceHeight = 720.0f;  // max-radius is in pixels at this many rows

// The gather passes' taps per quality preset: a golden-angle disc (Vogel's spiral) of T taps.
struct DofPreset {
  QualityPreset preset;
  int taps;
};
constexpr DofPreset kPresets[] = {
    {QualityPreset::Low, 12}, {QualityPreset::Medium, 24}, {QualityPreset::High, 40}, {QualityPreset::Ultra, 64}};

enum Pass { kCoc = 1, kDownsample = 2, kTileColumns = 3, kTiles = 4, kNeighbors = 5, kNear = 6, kFar = 7,
            kComposite = 8 };

ProgramSpec spec(int pass, int taps = 0) {
  std::string name = "dof[pass=" + std::to_string(pass);
  std::vector<std::pair<std::string, std::string>> defines = {
      {"DOF_PASS", std::to_string(pass)},
      {"MAX_TILE", std::to_string(DepthOfFieldEffect::kMaxTile)},
      {"FAR_RAY", "0"}};
  if (pass == kNear || pass == kFar) {
    name += ",taps=" + std::to_string(taps);
    defines.emplace_back("TAPS", std::to_string(taps));
  }
  if (pass == kComposite || pass == kNear) {
    defines.emplace_back("SMALL_COC", formatShortest(kDofSmallCoc) + (kDofSmallCoc == std::floor(kDofSmallCoc) ? ".0"
                                                                                                            : ""));
  }
  return ProgramSpec{name + "]", "lib/fullscreen.vert", "dof/dof.frag", defines, {}};
}

const char* kTileEncoding =
    "R: the largest |CoC| of the near field (in front of the focus) over the tile, as a fraction of the CoC range, "
    "rounded up to bytes";

}  // namespace

const std::vector<Parameter<DofSettings>>& DofSettings::parameters() {
  using S = DofSettings;
  static const std::vector<Parameter<S>> table = [] {
    std::vector<std::string> presetNames;
    for (QualityPreset p : allQualityPresets()) presetNames.push_back(presetName(p));
    // The issue's `dof.quality`, named `preset` as every effect's preset is (the viewers' state text writes
    // EFFECT.preset for each effect with presets).
    Parameter<S> quality{{"preset", parse::joinChoices(presetNames, " | "),
                          "quality preset: taps of each gather (12, 24, 40, 64)", ParameterKind::Choice, 0.0, 0.0,
                          presetNames},
                         {}, {}, {}, {}};
    quality.set = [](S& s, const std::string& v) { s.applyPreset(parsePreset(v)); };
    quality.get = [](const S& s) { return std::string(presetName(s.preset)); };
    quality.valid = [](const S&) { return true; };
    // The focus's "auto" resolves on the GPU (the G-buffer's depth at the focus point): nothing to show on the CPU.
    Parameter<S> focusParameter = autoNumberParameter<S>(
        "focus", 0.01, 1e5, "metres",
        "the distance in focus (along the view axis), or auto: the depth at the focus point",
        &S::focus, [](const S&) { return 0.0f; });
    focusParameter.effective = nullptr;
    return std::vector<Parameter<S>>{
        switchParameter<S>("dof", "depth of field on or off (a thin lens: near and far fields gathered at half size)",
                           &S::enabled)
            .primary(),
        std::move(focusParameter).primary(),
        numberParameter<S>("fstop", 0.5, 64, "", "the f-number N: the aperture's diameter is focal-length / N",
                           &S::fstop)
            .primary(),
        numberParameter<S>("focal-length", 1, 2000, "mm", "the lens's focal length F", &S::focalLength).primary(),
        numberParameter<S>("sensor-height", 1, 200, "mm", "the sensor's height, imaged onto the frame's rows",
                           &S::sensorHeight),
        numberParameter<S>("focus-x", 0, 1, "of the width", "autofocus point, from the left", &S::focusX),
        numberParameter<S>("focus-y", 0, 1, "of the height", "autofocus point, from the top", &S::focusY),
        numberParameter<S>("max-radius", 1, 64, "px at 720 rows",
                           "the largest blur radius in pixels at 720 rows (scaled with the height)", &S::maxRadius),
        std::move(quality)};
  }();
  return table;
}

int DofSettings::taps() const {
  for (const DofPreset& p : kPresets)
    if (p.preset == preset) return p.taps;
  return kPresets[1].taps;
}

glm::vec3 dofFieldEncode(const glm::vec3& linear) { return glm::sqrt(linear / (1.0f + linear)); }

glm::vec3 dofFieldDecode(const glm::vec3& field) {
  const glm::vec3 f2 = field * field;
  return f2 / glm::max(1.0f - f2, glm::vec3(1.0f / 255.0f));
}

glm::ivec2 DofSettings::focusPixel(int width, int height) const {
  return {std::clamp(static_cast<int>(std::floor(focusX * static_cast<float>(width))), 0, width - 1),
          std::clamp(static_cast<int>(std::floor(focusY * static_cast<float>(height))), 0, height - 1)};
}

float DofSettings::maxRadiusPixels(int height) const {
  return std::clamp(maxRadius * static_cast<float>(height) / kReferenceHeight, 0.5f,
                    static_cast<float>(DepthOfFieldEffect::kMaxTile));
}

ThinLens ThinLens::of(const DofSettings& settings, int height, bool orthographic) {
  ThinLens lens;
  lens.orthographic = orthographic;
  lens.focalLength = settings.focalLength * 1e-3f;
  const float aperture = lens.focalLength / settings.fstop;  // A = F / N
  lens.scale = aperture * lens.focalLength * static_cast<float>(height) / (settings.sensorHeight * 1e-3f);
  return lens;
}

float ThinLens::usableFocus(float focus) const { return std::max(focus, 1.001f * focalLength); }

float ThinLens::coc(float depth, float focus) const {
  const float p = usableFocus(focus);
  return scale * (depth - p) / ((orthographic ? p : depth) * (p - focalLength));
}

float ThinLens::pinholeAperture(float focus, float projScale) const {
  const float p = usableFocus(focus);
  return scale * p / ((p - focalLength) * projScale);
}

float ThinLens::parallelAperture(float focus, float pixelsPerMetre) const {
  const float p = usableFocus(focus);
  return scale / (p * (p - focalLength) * pixelsPerMetre);
}

EffectInfo DepthOfFieldEffect::info() {
  return {"dof",
          "Depth of field",
          true,
          false,
          {"dof-coc", "dof-downsample", "dof-tiles-h", "dof-tiles", "dof-neighbors", "dof-near", "dof-far",
           "dof-composite"},
          {{"dof-coc", "RG: the signed circle of confusion, 16 bits (encoding/CocPacking.h); BA zero", GL_NEAREST, {}},
           {"dof-half", "RGB: the 2 x 2 mean HDR colour as sqrt(c / (1 + c)); A: the smallest CoC of the four, 8 bits",
            GL_NEAREST, {}},
           {"dof-tile-columns", kTileEncoding, GL_NEAREST, {}},
           {"dof-tiles", kTileEncoding, GL_NEAREST, {}},
           {"dof-neighbors", kTileEncoding, GL_NEAREST, {}},
           {"dof-near", "the near field's HDR colour premultiplied by its coverage (A), as sqrt(c / (1 + c))",
            GL_LINEAR, {}},
           {"dof-far", "the far field's HDR colour as sqrt(c / (1 + c)); A 1 where the pixel is far, else all zero",
            GL_LINEAR, {}}}};
}

std::vector<ProgramSpec> DepthOfFieldEffect::programSpecs() {
  std::vector<ProgramSpec> specs = {spec(kCoc), spec(kDownsample), spec(kTileColumns), spec(kTiles),
                                    spec(kNeighbors), spec(kComposite)};
  for (const DofPreset& p : kPresets) {
    specs.push_back(spec(kNear, p.taps));
    specs.push_back(spec(kFar, p.taps));
  }
  return specs;
}

DepthOfFieldEffect::CocProgram::CocProgram(gl::Program built)
    : program(std::move(built)),
      gbuffer(program.uniform("u_gbuffer")),
      lens(program.uniform("u_lens")),
      focus(program.uniform("u_focus")),
      focusUv(program.uniform("u_focusUv")),
      autofocus(program.uniform("u_autofocus")),
      depthRange(program.uniform("u_depthRange")),
      range(program.uniform("u_range")) {}

DepthOfFieldEffect::DownsampleProgram::DownsampleProgram(gl::Program built)
    : program(std::move(built)),
      color(program.uniform("u_color")),
      coc(program.uniform("u_coc")),
      fullSize(program.uniform("u_fullSize")),
      halfSize(program.uniform("u_halfSize")),
      range(program.uniform("u_range")) {}

DepthOfFieldEffect::GatherProgram::GatherProgram(gl::Program built)
    : program(std::move(built)),
      half(program.uniform("u_half")),
      halfSize(program.uniform("u_halfSize")),
      range(program.uniform("u_range")) {}

DepthOfFieldEffect::CompositeProgram::CompositeProgram(gl::Program built)
    : program(std::move(built)),
      color(program.uniform("u_color")),
      coc(program.uniform("u_coc")),
      nearField(program.uniform("u_near")),
      farField(program.uniform("u_far")),
      range(program.uniform("u_range")),
      fullSize(program.uniform("u_fullSize")),
      neighbors(program.uniform("u_neighbors")) {}

DepthOfFieldEffect::DepthOfFieldEffect(const EffectResources& resources)
    : resources_(resources),
      coc_(resources.build(spec(kCoc))),
      downsample_(resources.build(spec(kDownsample))),
      tileMax_(resources, spec(kTileColumns), spec(kTiles), spec(kNeighbors)),
      columnsRange_(tileMax_.columnsProgram().uniform("u_range")),
      composite_(resources.build(spec(kComposite))) {}

const DepthOfFieldEffect::GatherProgram& DepthOfFieldEffect::gather(bool nearField, int taps) {
  auto it = gathers_.find({nearField, taps});
  if (it == gathers_.end()) {
    GatherProgram p(resources_.build(spec(nearField ? kNear : kFar, taps)));
    if (nearField) p.neighbors = p.program.uniform("u_neighbors");
    else p.maxRadius = p.program.uniform("u_maxRadius");
    it = gathers_.emplace(std::make_pair(nearField, taps), std::move(p)).first;
  }
  return it->second;
}

void DepthOfFieldEffect::plan(FramePlanner& planner) {
  const DofSettings settings = planner.settings().of<DofSettings>();
  if (!settings.enabled) return;
  const FrameCamera& camera = planner.frame().camera;
  // The frame's constants, derived once here: the lens, the CoC range, the tile size K.
  const ThinLens lens = ThinLens::of(settings, camera.height, camera.orthographic);
  const float maxRadius = settings.maxRadiusPixels(camera.height);
  const float range = 2.0f * maxRadius;  // the largest |C| drawn: a diameter
  const int k = std::clamp(static_cast<int>(std::ceil(maxRadius)), 1, kMaxTile);
  const bool autofocus = !settings.focus.has_value();
  const float focus = autofocus ? 0.0f : lens.usableFocus(*settings.focus);
  // The focus pixel's centre in uv (y up), so that NEAREST reads that texel on any rasteriser.
  const glm::ivec2 focusPixel = settings.focusPixel(camera.width, camera.height);
  const glm::vec2 focusUv((static_cast<float>(focusPixel.x) + 0.5f) / static_cast<float>(camera.width),
                          (static_cast<float>(camera.height - 1 - focusPixel.y) + 0.5f) /
                              static_cast<float>(camera.height));
  const glm::vec2 depthRange(camera.near, camera.far - camera.near);  // view depth = near + d (far - near)
  const int taps = settings.taps();

  PassDecl coc;
  coc.name = "dof-coc";
  coc.reads = {"gbuffer"};
  coc.writes = {{"dof-coc", TargetSize::full(), Write::Depth::None, ""}};
  coc.run = [this, lens, range, autofocus, focus, focusUv, depthRange](PassContext& context) {
    context.bindForWriting("dof-coc");
    coc_.program.use();
    context.texture("gbuffer").bind(0);
    gl::Program::set(coc_.gbuffer, 0);
    gl::Program::set(coc_.lens, glm::vec3(lens.scale, lens.focalLength, lens.orthographic ? 0.0f : 1.0f));
    gl::Program::set(coc_.focus, focus);
    gl::Program::set(coc_.focusUv, focusUv);
    gl::Program::set(coc_.autofocus, autofocus ? 1.0f : 0.0f);
    gl::Program::set(coc_.depthRange, depthRange);
    gl::Program::set(coc_.range, range);
    resources_.triangle.draw();
    gl::restoreBaselineState();
  };
  planner.add(std::move(coc));

  PassDecl down;
  down.name = "dof-downsample";
  down.reads = {"scene-color", "dof-coc"};
  down.writes = {{"dof-half", TargetSize::half(), Write::Depth::None, ""}};
  down.run = [this, range](PassContext& context) {
    context.bindForWriting("dof-half");
    downsample_.program.use();
    context.texture("scene-color").bind(0);
    context.texture("dof-coc").bind(1);
    gl::Program::set(downsample_.color, 0);
    gl::Program::set(downsample_.coc, 1);
    gl::Program::set(downsample_.fullSize, glm::vec2(context.size("dof-coc")));
    gl::Program::set(downsample_.halfSize, glm::vec2(context.size("dof-half")));
    gl::Program::set(downsample_.range, range);
    resources_.triangle.draw();
    gl::restoreBaselineState();
  };
  planner.add(std::move(down));

  const glm::vec2 frame(static_cast<float>(camera.width), static_cast<float>(camera.height));
  tileMax_.plan(planner, "dof", "dof-coc", k, frame,
                [this, range] { gl::Program::set(columnsRange_, range); });

  auto gatherPass = [this, taps, range, maxRadius](bool nearField) {
    return [this, nearField, taps, range, maxRadius](PassContext& context) {
      const GatherProgram& p = gather(nearField, taps);
      const std::string target = nearField ? "dof-near" : "dof-far";
      context.bindForWriting(target);
      p.program.use();
      context.texture("dof-half").bind(0);
      gl::Program::set(p.half, 0);
      if (nearField) {
        context.texture("dof-neighbors").bind(1);
        gl::Program::set(p.neighbors, 1);
      }
      gl::Program::set(p.halfSize, glm::vec2(context.size("dof-half")));
      gl::Program::set(p.range, range);
      if (!nearField) gl::Program::set(p.maxRadius, maxRadius);
      resources_.triangle.draw();
      gl::restoreBaselineState();
    };
  };
  PassDecl nearPass;
  nearPass.name = "dof-near";
  nearPass.reads = {"dof-half", "dof-neighbors"};
  nearPass.writes = {{"dof-near", TargetSize::half(), Write::Depth::None, ""}};
  nearPass.run = gatherPass(true);
  planner.add(std::move(nearPass));

  PassDecl farPass;
  farPass.name = "dof-far";
  farPass.reads = {"dof-half"};
  farPass.writes = {{"dof-far", TargetSize::half(), Write::Depth::None, ""}};
  farPass.run = gatherPass(false);
  planner.add(std::move(farPass));

  PassDecl composite;
  composite.name = "dof-composite";
  composite.reads = {"scene-color", "dof-coc", "dof-near", "dof-far", "dof-neighbors"};
  composite.writes = {{"scene-color", TargetSize::full(), Write::Depth::None, ""}};
  composite.run = [this, range](PassContext& context) {
    context.bindForWriting("scene-color");
    composite_.program.use();
    context.texture("scene-color").bind(0);
    context.texture("dof-coc").bind(1);
    context.texture("dof-near").bind(2);
    context.texture("dof-far").bind(3);
    gl::Program::set(composite_.color, 0);
    gl::Program::set(composite_.coc, 1);
    gl::Program::set(composite_.nearField, 2);
    gl::Program::set(composite_.farField, 3);
    gl::Program::set(composite_.range, range);
    gl::Program::set(composite_.fullSize, glm::vec2(context.size("scene-color")));
    context.texture("dof-neighbors").bind(4);
    gl::Program::set(composite_.neighbors, 4);
    resources_.triangle.draw();
    gl::restoreBaselineState();
  };
  planner.add(std::move(composite));
}

}  // namespace obscura
