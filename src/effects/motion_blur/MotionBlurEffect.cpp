#include "effects/motion_blur/MotionBlurEffect.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "frame/PassContext.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

using Write = PassDecl::Write;

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
                         &S::maxRadius)};
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
  return info;
}

std::vector<ProgramSpec> MotionBlurEffect::programSpecs() {
  std::vector<ProgramSpec> specs = {spec(1), spec(2), spec(3)};
  for (int samples = kMinSamples; samples <= kMaxSamples; ++samples) specs.push_back(spec(4, samples));
  return specs;
}

MotionBlurEffect::ReconstructProgram::ReconstructProgram(gl::Program built)
    : program(std::move(built)),
      color(program.uniform("u_color")),
      velocity(program.uniform("u_velocity")),
      gbuffer(program.uniform("u_gbuffer")),
      neighborMax(program.uniform("u_neighborMax")),
      tilesSize(program.uniform("u_tilesSize")),
      tile(program.uniform("u_tile")),
      near(program.uniform("u_near")),
      depthRange(program.uniform("u_depthRange")),
      alphaIsOne(program.uniform("u_alphaIsOne")),
      frameSize(program.uniform("u_frameSize")),
      halfExposure(program.uniform("u_halfExposure")),
      maxRadius(program.uniform("u_maxRadius")) {}

MotionBlurEffect::MotionBlurEffect(const EffectResources& resources)
    : resources_(resources),
      tileMax_(resources, spec(1), spec(2), spec(3)),
      columnsHalfExposure_(tileMax_.columnsProgram().uniform("u_halfExposure")),
      columnsMaxRadius_(tileMax_.columnsProgram().uniform("u_maxRadius")) {}

const MotionBlurEffect::ReconstructProgram& MotionBlurEffect::reconstruction(int samples) {
  auto it = reconstructions_.find(samples);
  if (it == reconstructions_.end())
    it = reconstructions_.emplace(samples, ReconstructProgram(resources_.build(spec(4, samples)))).first;
  return it->second;
}

void MotionBlurEffect::plan(FramePlanner& planner) {
  const MotionBlurSettings& settings = planner.settings().of<MotionBlurSettings>();
  if (!settings.enabled && !planner.showsTargetOf(info())) return;
  const FrameCamera& camera = planner.frame().camera;
  // The frame's constants, derived once here: K, the velocity-to-half-vector scale, the depth range.
  const int k = settings.tileSize(camera.height);
  const glm::vec2 frame(static_cast<float>(camera.width), static_cast<float>(camera.height));
  const glm::vec2 halfExposure = 0.5f * settings.shutter * frame;
  const float maxRadius = static_cast<float>(k);
  const float tile = static_cast<float>(k);

  tileMax_.plan(planner, "motion", "velocity", k, frame, [this, halfExposure, maxRadius] {
    gl::Program::set(columnsHalfExposure_, halfExposure);
    gl::Program::set(columnsMaxRadius_, maxRadius);
  });

  if (!settings.enabled) return;  // a debug view of the tiles
  PassDecl blur;
  blur.name = "motion-blur";
  blur.reads = {"display-color", "velocity", "gbuffer", "motion-neighbors"};
  blur.writes = {{"display-color", TargetSize::full(), Write::Depth::None, ""}};
  const int samples = settings.samples;
  const float near = camera.near, depthRange = camera.far - camera.near;
  blur.run = [this, samples, frame, tile, halfExposure, maxRadius, near, depthRange](PassContext& context) {
    const ReconstructProgram& p = reconstruction(samples);
    context.bindForWriting("display-color");
    p.program.use();
    context.texture("display-color").bind(0);
    context.texture("velocity").bind(1);
    context.texture("gbuffer").bind(2);
    context.texture("motion-neighbors").bind(3);
    gl::Program::set(p.color, 0);
    gl::Program::set(p.velocity, 1);
    gl::Program::set(p.gbuffer, 2);
    gl::Program::set(p.neighborMax, 3);
    gl::Program::set(p.tilesSize, glm::vec2(context.size("motion-neighbors")));
    gl::Program::set(p.tile, tile);
    gl::Program::set(p.near, near);
    gl::Program::set(p.depthRange, depthRange);
    gl::Program::set(p.alphaIsOne, context.writesOutput("display-color") ? 1.0f : 0.0f);
    gl::Program::set(p.frameSize, frame);
    gl::Program::set(p.halfExposure, halfExposure);
    gl::Program::set(p.maxRadius, maxRadius);
    resources_.triangle.draw();
    gl::restoreBaselineState();
  };
  planner.add(std::move(blur));
}

}  // namespace obscura
