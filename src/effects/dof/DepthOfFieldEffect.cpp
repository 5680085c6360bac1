#include "effects/dof/DepthOfFieldEffect.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include "base/Text.h"
#include "frame/PassContext.h"

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
                         {}, {}, {}, {}, {}};
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
                           "the largest blur radius in pixels at 720 rows (scaled with the height)", &S::maxRadius)
            .shapesPlan(),  // the tiles' size
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
  EffectInfo info{
      "dof",
      "Depth of field",
      true,
      false,
      {"dof-coc", "dof-downsample", "dof-tiles-h", "dof-tiles", "dof-neighbors", "dof-near", "dof-far",
       "dof-composite"},
      {{"dof-coc", "RG: the signed circle of confusion, 16 bits (encoding/CocPacking.h); BA zero", GL_NEAREST, {}},
       {"dof-half",
        "RGB: the 2 x 2 mean HDR colour as sqrt(c / (1 + c)); A: the smallest CoC of the four, 8 bits",
        GL_NEAREST,
        {}},
       {"dof-tile-columns", kTileEncoding, GL_NEAREST, {}},
       {"dof-tiles", kTileEncoding, GL_NEAREST, {}},
       {"dof-neighbors", kTileEncoding, GL_NEAREST, {}},
       {"dof-near",
        "the near field's HDR colour premultiplied by its coverage (A), as sqrt(c / (1 + c))",
        GL_LINEAR,
        {}},
       {"dof-far",
        "the far field's HDR colour as sqrt(c / (1 + c)); A 1 where the pixel is far, else all zero",
        GL_LINEAR,
        {}}}};
  info.waitsForFullFrame = true;
  return info;
}

std::vector<ProgramSpec> DepthOfFieldEffect::programSpecs() {
  std::vector<ProgramSpec> specs = {spec(kCoc), spec(kDownsample), spec(kTileColumns), spec(kTiles),
                                    spec(kNeighbors), fusedProgram(spec(kComposite), {}, ColorSpace::Hdr)};
  for (const DofPreset& p : kPresets) {
    specs.push_back(spec(kNear, p.taps));
    specs.push_back(spec(kFar, p.taps));
  }
  return specs;
}

std::vector<StageHeadSpec> DepthOfFieldEffect::stageHeads() {
  return {{spec(kComposite), ColorSpace::Hdr, kCompositeUniformVectors}};
}

DepthOfFieldEffect::DepthOfFieldEffect(const EffectResources& resources) : resources_(resources) {}

void DepthOfFieldEffect::plan(FramePlanner& planner) {
  const DofSettings& settings = planner.settings().of<DofSettings>();
  if (!settings.enabled) return;
  // What shapes the passes: the CoC range and the tile size K (from the largest radius and the frame's height), the
  // gathers' taps (the preset).
  const float maxRadius = settings.maxRadiusPixels(planner.frame().camera.height);
  const float range = 2.0f * maxRadius;  // the largest |C| drawn: a diameter
  const int k = std::clamp(static_cast<int>(std::ceil(maxRadius)), 1, kMaxTile);
  const int taps = settings.taps();

  planner.add(fullscreenPass(
      "dof-coc", spec(kCoc), {{"u_gbuffer", "gbuffer"}}, {"dof-coc"},
      [range](FullscreenDraw& draw, const PassContext& context) {
        // This frame's lens and focus.
        const DofSettings& dof = context.settings().of<DofSettings>();
        const FrameCamera& camera = context.camera();
        const ThinLens lens = ThinLens::of(dof, camera.height, camera.orthographic);
        const bool autofocus = !dof.focus.has_value();
        // The focus pixel's centre in uv (y up), so that NEAREST reads that texel on any rasteriser.
        const glm::ivec2 focusPixel = dof.focusPixel(camera.width, camera.height);
        const glm::vec2 focusUv((static_cast<float>(focusPixel.x) + 0.5f) / static_cast<float>(camera.width),
                                (static_cast<float>(camera.height - 1 - focusPixel.y) + 0.5f) /
                                    static_cast<float>(camera.height));
        draw.set("u_lens", glm::vec3(lens.scale, lens.focalLength, lens.orthographic ? 0.0f : 1.0f));
        draw.set("u_focus", autofocus ? 0.0f : lens.usableFocus(*dof.focus));
        draw.set("u_focusUv", focusUv);
        draw.set("u_autofocus", autofocus ? 1.0f : 0.0f);
        draw.set("u_depthRange", glm::vec2(camera.near, camera.far - camera.near));  // depth = near + d (far - near)
        draw.set("u_range", range);
      }));

  planner.add(fullscreenPass("dof-downsample", spec(kDownsample),
                             {{"u_color", "scene-color"}, {"u_coc", "dof-coc"}},
                             {"dof-half", TargetSize::half(), Write::Depth::None, ""},
                             [range](FullscreenDraw& draw, const PassContext& context) {
                               draw.set("u_fullSize", glm::vec2(context.size("dof-coc")));
                               draw.set("u_halfSize", glm::vec2(context.size("dof-half")));
                               draw.set("u_range", range);
                             }));

  // The first tile pass decodes the 16-bit CoC; the others compare bytes.
  TileMaxPasses::plan(planner, "dof", "dof-coc", k, spec(kTileColumns), spec(kTiles), spec(kNeighbors),
                      [range](FullscreenDraw& draw, const PassContext&) { draw.set("u_range", range); });

  auto gather = [range, maxRadius](bool nearField) {
    return [range, nearField, maxRadius](FullscreenDraw& draw, const PassContext& context) {
      draw.set("u_halfSize", glm::vec2(context.size("dof-half")));
      draw.set("u_range", range);
      if (!nearField) draw.set("u_maxRadius", maxRadius);
    };
  };
  planner.add(fullscreenPass("dof-near", spec(kNear, taps), {{"u_half", "dof-half"}, {"u_neighbors", "dof-neighbors"}},
                             {"dof-near", TargetSize::half(), Write::Depth::None, ""}, gather(true)));
  planner.add(fullscreenPass("dof-far", spec(kFar, taps), {{"u_half", "dof-half"}},
                             {"dof-far", TargetSize::half(), Write::Depth::None, ""}, gather(false)));

  planner.add(fullscreenStageHead(resources_, "dof-composite", spec(kComposite),
                                  {{"u_color", "scene-color"},
                                   {"u_coc", "dof-coc"},
                                   {"u_near", "dof-near"},
                                   {"u_far", "dof-far"},
                                   {"u_neighbors", "dof-neighbors"}},
                                  {"scene-color"}, ColorSpace::Hdr, kCompositeUniformVectors,
                                  [range](FullscreenDraw& draw, const PassContext& context) {
                                    draw.set("u_range", range);
                                    draw.set("u_fullSize", glm::vec2(context.size("dof-coc")));
                                  }));
}

}  // namespace obscura
