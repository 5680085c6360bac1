#include "effects/motion_blur/MotionBlurEffect.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "frame/PassContext.h"

namespace obscura {
namespace {

constexpr float kReferenceHeight = 720.0f;  // max-radius is in pixels at this many rows

ProgramSpec spec(int pass, int samples = 0) {
  std::string name = "motion-blur[pass=" + std::to_string(pass);
  std::vector<std::pair<std::string, std::string>> defines = {
      {"MOTION_BLUR_PASS", std::to_string(pass)},
      {"MAX_TILE", std::to_string(MotionBlurEffect::kMaxTile)},
      {"FAR_RAY", "0"}};
  if (pass == 4) {
    name += ",samples=" + std::to_string(samples);
    defines.emplace_back("SAMPLES", std::to_string(samples));
  }
  return ProgramSpec{name + "]", "lib/fullscreen.vert", "motion_blur/motion_blur.frag", defines, {}};
}

const char* kTileEncoding =
    "RG, BA: the largest blur half-vector V of the tile (pixels / frame size), each component as the velocity "
    "target's 16-bit code, high byte first (encoding/VelocityPacking.h)";

}  // namespace

const std::vector<Parameter<MotionBlurSettings>>& MotionBlurSettings::parameters() {
  using S = MotionBlurSettings;
  static const std::vector<Parameter<S>> table = {
      switchParameter<S>("motion-blur", "motion blur on or off (McGuire et al. 2012's reconstruction filter)",
                         &S::enabled)
          .primary(),
      numberParameter<S>("shutter", 0, 1, "of the frame interval",
                         "how long the shutter stays open, centred on the frame's time (0.5: 180 degrees)",
                         &S::shutter)
          .primary(),
      integerParameter<S>("samples", MotionBlurEffect::kMinSamples, MotionBlurEffect::kMaxSamples, "", "",
                          "taps per pixel along the neighbourhood's motion", &S::samples),
      numberParameter<S>("max-radius", 1, 64, "px at 720 rows",
                         "the longest blur, half its length in pixels at 720 rows (scaled with the height)",
                         &S::maxRadius)
          .shapesPlan()};  // the tiles' size
  return table;
}

int MotionBlurSettings::tileSize(int height) const {
  const int k = static_cast<int>(std::lround(maxRadius * static_cast<float>(height) / kReferenceHeight));
  return std::clamp(k, 1, MotionBlurEffect::kMaxTile);
}

EffectInfo MotionBlurEffect::info() {
  EffectInfo info{"motion-blur",
                  "Motion blur",
                  true,
                  false,
                  {"motion-tiles-h", "motion-tiles", "motion-neighbors", "motion-blur"},
                  {{"motion-tile-columns", kTileEncoding, GL_NEAREST, {}},
                   {"motion-tiles", kTileEncoding, GL_NEAREST, {{"motion-tiles", ViewDecoding::Velocity}}},
                   {"motion-neighbors", kTileEncoding, GL_NEAREST, {{"motion-neighbors", ViewDecoding::Velocity}}}}};
  info.temporal = true;
  info.waitsForFullFrame = true;
  return info;
}

std::vector<ProgramSpec> MotionBlurEffect::programSpecs() {
  std::vector<ProgramSpec> specs = {spec(1), spec(2), spec(3)};
  for (int samples = kMinSamples; samples <= kMaxSamples; ++samples) specs.push_back(spec(4, samples));
  return specs;
}

MotionBlurEffect::MotionBlurEffect(const EffectResources&) {}

void MotionBlurEffect::plan(FramePlanner& planner) {
  const MotionBlurSettings& settings = planner.settings().of<MotionBlurSettings>();
  if (!settings.enabled && !planner.showsTargetOf(info())) return;
  // K, from the frame's height: the tiles' size.
  const int k = settings.tileSize(planner.frame().camera.height);
  const float tile = static_cast<float>(k);
  // The velocity-to-half-vector scale, from this frame's shutter and size.
  auto halfExposure = [](const PassContext& context) {
    const FrameCamera& camera = context.camera();
    return 0.5f * context.settings().of<MotionBlurSettings>().shutter * glm::vec2(camera.width, camera.height);
  };

  TileMaxPasses::plan(planner, "motion", "velocity", k, spec(1), spec(2), spec(3),
                      [halfExposure, tile](FullscreenDraw& draw, const PassContext& context) {
                        draw.set("u_halfExposure", halfExposure(context));
                        draw.set("u_maxRadius", tile);
                      });

  if (!settings.enabled) return;  // a debug view of the tiles
  planner.add(fullscreenPass(
      "motion-blur", spec(4, settings.samples),
      {{"u_color", "display-color"}, {"u_velocity", "velocity"}, {"u_gbuffer", "gbuffer"},
       {"u_neighborMax", "motion-neighbors"}},
      {"display-color"}, [halfExposure, tile](FullscreenDraw& draw, const PassContext& context) {
        const FrameCamera& camera = context.camera();
        draw.set("u_tilesSize", glm::vec2(context.size("motion-neighbors")));
        draw.set("u_tile", tile);
        draw.set("u_near", camera.near);
        draw.set("u_depthRange", camera.far - camera.near);
        draw.set("u_alphaIsOne", context.writesOutput("display-color") ? 1.0f : 0.0f);
        draw.set("u_frameSize", glm::vec2(camera.width, camera.height));
        draw.set("u_halfExposure", halfExposure(context));
        draw.set("u_maxRadius", tile);
      }));
}

}  // namespace obscura
