#include "effects/ao/SaoPass.h"

#include <algorithm>
#include <array>

#include "effects/ao/SaoKernel.h"
#include "frame/FullscreenPass.h"

namespace obscura {
namespace {

int hierarchyDefine(std::optional<DepthHierarchyPass::Storage> hierarchy) {
  return hierarchy ? static_cast<int>(*hierarchy) : 0;
}

}  // namespace

SaoPass::GtaoSampling SaoPass::gtaoSampling(int samples) {
  // Two slices from 8 samples, four from 32; the steps use what the slices leave, rounded: "8 samples" is 2 x 2 x 2
  // taps, "11" 2 x 2 x 3 = 12, "16" 2 x 2 x 4, "32" 4 x 2 x 4. Measured at 11 (docs/accuracy.md): one slice of 5 steps
  // a side is a little more accurate than two of 3, but costs 40 % more on llvmpipe (93 against 65 ms at 1280x720).
  // Below 8 samples one side of one slice takes every tap (gtao.frag, GTAO_SIDES): at 4 samples 1 x 1 x 4 against
  // 1 x 2 x 2, whose two-tap horizons miss occluders (the built-in scene at 480x270 against the reference, 8
  // frames of ao.temporal: docs/temporal-effects.md, "Temporal AO").
  if (samples < 8) return {1, std::max(1, samples), 1};
  const int slices = samples >= 32 ? 4 : 2;
  return {slices, std::max(1, (samples + slices) / (2 * slices)), 2};
}

SaoPass::HbaoSampling SaoPass::hbaoSampling(int samples) {
  // Four directions (the HBAO talk's per-pixel rotated directions; four keeps opposite pairs, so a surface is seen
  // from both sides) and the steps the budget leaves, rounded down: "8 samples" is 4 x 2, "11" 4 x 2 = 8, "16" 4 x 4,
  // "24" 4 x 6. From 32 on, eight directions of samples / 8 steps, HBAO+'s 8 x 4 at 32. Below 4 samples, as many
  // directions as samples (one step each), two opposite ones from 2 and 3.
  const int directions = samples >= 32 ? 8 : samples >= 4 ? 4 : samples >= 2 ? 2 : 1;
  return {directions, std::max(1, samples / directions)};
}

int SaoPass::mirroredPairs(int samples) { return std::max(1, samples / 2); }

float SaoPass::intensityScale(const AoSettings& settings, float intensity) {
  return settings.estimator == AoEstimator::Sao
             ? SaoKernel::intensityScale(settings.falloff, intensity, settings.samples)
             : intensity;
}

ProgramSpec SaoPass::programSpec(AoEstimator estimator, int samples, int spiralTurns, Falloff falloff,
                                 std::optional<Storage> hierarchy, int layers, bool normalsFromDepth) {
  ProgramSpec spec;
  const std::string depth = hierarchy ? DepthHierarchyPass::storageName(*hierarchy) : "gbuffer";
  spec.vertexFile = "lib/fullscreen.vert";
  spec.defines = {{"DEPTH_HIERARCHY", std::to_string(hierarchyDefine(hierarchy))},
                  {"MAX_MIP_LEVEL", std::to_string(SaoKernel::kMaxMipLevel)},
                  {"LOG_MAX_OFFSET", std::to_string(SaoKernel::kLogMaxOffset)},
                  {"ESTIMATOR_KNOTS", std::to_string(kEstimatorKnots)},
                  {"FIRST_KNOT_PIXELS", std::to_string(static_cast<int>(kFirstKnotPixels))},
                  {"AO_LAYERS", std::to_string(layers)},
                  {"NORMALS_FROM_DEPTH", normalsFromDepth ? "1" : "0"}};
  // The estimator's shader and its compile-time constants; the program's name lists them as label=value.
  struct Constant {
    const char* define;
    const char* label;
    int value;
  };
  auto use = [&](const std::string& shader, std::initializer_list<Constant> constants, const std::string& extra = "") {
    spec.fragmentFile = "ao/" + shader + ".frag";
    spec.name = shader + "[";
    for (const Constant& c : constants) {
      spec.defines.push_back({c.define, std::to_string(c.value)});
      spec.name += std::string(c.label) + "=" + std::to_string(c.value) + ",";
    }
    spec.name += extra + (layers == 2 ? "layers=2," : "") + (normalsFromDepth ? "normals=depth," : "") +
                 "depth=" + depth + "]";
  };
  switch (estimator) {
    case AoEstimator::Gtao: {
      const GtaoSampling sampling = gtaoSampling(samples);
      use("gtao", {{"GTAO_SLICES", "slices", sampling.slices},
                   {"GTAO_STEPS", "steps", sampling.steps},
                   {"GTAO_SIDES", "sides", sampling.sides}});
      break;
    }
    case AoEstimator::Hbao: {
      const HbaoSampling sampling = hbaoSampling(samples);
      use("hbao", {{"HBAO_DIRECTIONS", "directions", sampling.directions}, {"HBAO_STEPS", "steps", sampling.steps}});
      break;
    }
    case AoEstimator::Vo: use("vo", {{"VO_PAIRS", "pairs", mirroredPairs(samples)}}); break;
    case AoEstimator::Crytek: use("crytek", {{"CRYTEK_PAIRS", "pairs", mirroredPairs(samples)}}); break;
    case AoEstimator::Sao:
      use("sao", {{"NUM_SAMPLES", "samples", samples}, {"NUM_SPIRAL_TURNS", "turns", spiralTurns}},
          std::string("falloff=") + falloffName(falloff) + ",");
      spec.defines.push_back({"FALLOFF_SAO2012", falloff == Falloff::Sao2012 ? "1" : "0"});
      break;
  }
  if (hierarchy == Storage::MipChain) spec.extensions = {"GL_EXT_shader_texture_lod"};
  return spec;
}

std::vector<ProgramSpec> SaoPass::programSpecs() {
  std::vector<ProgramSpec> specs;
  const std::optional<Storage> depthSources[] = {std::nullopt, Storage::SeparateTextures, Storage::MipChain,
                                                 Storage::Atlas};
  for (int samples : {4, 8, 11, 16, 24, 32}) {
    for (std::optional<Storage> hierarchy : depthSources) {
      for (bool normalsFromDepth : {false, true}) {
        for (Falloff falloff : {Falloff::Sao2012, Falloff::Alchemy2011})
          specs.push_back(programSpec(AoEstimator::Sao, samples, SaoKernel::bestSpiralTurns(samples), falloff,
                                      hierarchy, 1, normalsFromDepth));
        for (AoEstimator other : {AoEstimator::Gtao, AoEstimator::Hbao, AoEstimator::Vo, AoEstimator::Crytek}) {
          for (int layers = 1; layers <= (estimatorReadsSecondLayer(other) ? 2 : 1); ++layers) {
            ProgramSpec spec = programSpec(other, samples, 1, Falloff::Sao2012, hierarchy, layers, normalsFromDepth);
            // Sample counts that split alike (HBAO's 8 and 11: 4 x 2) share a program: listed once.
            if (std::none_of(specs.begin(), specs.end(), [&](const ProgramSpec& s) { return s.name == spec.name; }))
              specs.push_back(std::move(spec));
          }
        }
      }
    }
  }
  return specs;
}

void SaoPass::render(const gl::Texture2D& gbuffer, const DepthHierarchyPass* hierarchy,
                     const gl::Texture2D* secondLayer, const FrameCamera& camera, const AoSettings& settings,
                     bool normalsFromDepth, int aoScale, glm::ivec2 aoSize, glm::vec2 frameOffset) const {
  const std::optional<Storage> storage = hierarchy ? std::optional<Storage>(hierarchy->storage()) : std::nullopt;
  // Only SAO's programs depend on the spiral and the falloff.
  const bool sao = settings.estimator == AoEstimator::Sao;
  FullscreenDraw draw(resources_.program(programSpec(settings.estimator, settings.samples,
                                                     sao ? settings.spiralTurns : 1,
                                                     sao ? settings.falloff : Falloff::Sao2012, storage,
                                                     secondLayer ? 2 : 1, normalsFromDepth)),
                      resources_.triangle);
  draw.texture("u_gbuffer", gbuffer);
  if (hierarchy) hierarchy->bindForSampling(draw);
  // The atlas holds the second layer itself; the other storages read its target.
  if (secondLayer && draw.program().has("u_secondLayer")) draw.texture("u_secondLayer", *secondLayer);
  draw.set("u_gbufferSize", glm::vec2(gbuffer.width(), gbuffer.height()));
  draw.set("u_aoSize", glm::vec2(aoSize));
  draw.set("u_aoScale", static_cast<float>(aoScale));
  setReconstruction(draw.program(), camera.reconstruction);
  draw.set("u_projScale", camera.projScale(gbuffer.height()));
  draw.set("u_radius", settings.radius);
  draw.set("u_invRadius", 1.0f / settings.radius);
  const EstimatorKnots knots = settings.estimatorKnots();
  std::array<glm::vec4, kEstimatorKnots> packed;
  for (int j = 0; j < kEstimatorKnots; ++j)
    packed[static_cast<size_t>(j)] = {intensityScale(settings, knots.at[j].intensity), knots.at[j].bias,
                                      knots.at[j].contrast, knots.at[j].thickness};
  draw.set("u_estimatorKnots", packed.data(), kEstimatorKnots);
  draw.set("u_maxRadiusPixels", settings.maxScreenRadius * static_cast<float>(gbuffer.height()));
  draw.set("u_frameOffset", frameOffset);
  // GTAO's joining of taps into one occluder (its variants alone; its thickness is the knots' w).
  if (draw.program().has("u_surfaceGap")) draw.set("u_surfaceGap", settings.surfaceGap);
  draw.draw();
}

}  // namespace obscura
