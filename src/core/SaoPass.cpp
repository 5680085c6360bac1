#include "core/SaoPass.h"

#include <algorithm>
#include <array>

#include "core/SaoKernel.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

int hierarchyDefine(std::optional<DepthHierarchyPass::Storage> hierarchy) {
  return hierarchy ? static_cast<int>(*hierarchy) : 0;
}

}  // namespace

SaoPass::GtaoSampling SaoPass::gtaoSampling(int samples) {
  // One slice up to 15 taps (the blur averages the per-pixel slice angles), two up to 31, four from 32; the steps
  // use what the slices leave, rounded, so "11 samples" costs 10 taps and "32" costs 32.
  const int slices = samples >= 32 ? 4 : samples >= 16 ? 2 : 1;
  return {slices, std::max(1, (samples + slices) / (2 * slices))};
}

float SaoPass::intensityScale(const AoSettings& settings, float intensity) {
  return settings.estimator == AoEstimator::Gtao ? intensity
                                                 : SaoKernel::intensityScale(settings.falloff, intensity, settings.samples);
}

ProgramSpec SaoPass::programSpec(AoEstimator estimator, int samples, int spiralTurns, Falloff falloff,
                                 std::optional<Storage> hierarchy) {
  ProgramSpec spec;
  const std::string depth = hierarchy ? DepthHierarchyPass::storageName(*hierarchy) : "gbuffer";
  spec.vertexFile = "fullscreen.vert";
  spec.defines = {{"DEPTH_HIERARCHY", std::to_string(hierarchyDefine(hierarchy))},
                  {"MAX_MIP_LEVEL", std::to_string(SaoKernel::kMaxMipLevel)},
                  {"LOG_MAX_OFFSET", std::to_string(SaoKernel::kLogMaxOffset)},
                  {"ESTIMATOR_KNOTS", std::to_string(kEstimatorKnots)},
                  {"FIRST_KNOT_PIXELS", std::to_string(static_cast<int>(kFirstKnotPixels))}};
  if (estimator == AoEstimator::Gtao) {
    const GtaoSampling sampling = gtaoSampling(samples);
    spec.name = "gtao[slices=" + std::to_string(sampling.slices) + ",steps=" + std::to_string(sampling.steps) +
                ",depth=" + depth + "]";
    spec.fragmentFile = "gtao.frag";
    spec.defines.push_back({"GTAO_SLICES", std::to_string(sampling.slices)});
    spec.defines.push_back({"GTAO_STEPS", std::to_string(sampling.steps)});
    spec.defines.push_back({"THIN_OCCLUDER_BLEND", "0.0"});
  } else {
    spec.name = "sao[samples=" + std::to_string(samples) + ",turns=" + std::to_string(spiralTurns) +
                ",falloff=" + falloffName(falloff) + ",depth=" + depth + "]";
    spec.fragmentFile = "sao.frag";
    spec.defines.push_back({"NUM_SAMPLES", std::to_string(samples)});
    spec.defines.push_back({"NUM_SPIRAL_TURNS", std::to_string(spiralTurns)});
    spec.defines.push_back({"FALLOFF_SAO2012", falloff == Falloff::Sao2012 ? "1" : "0"});
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
      for (Falloff falloff : {Falloff::Sao2012, Falloff::Alchemy2011})
        specs.push_back(
            programSpec(AoEstimator::Sao, samples, SaoKernel::bestSpiralTurns(samples), falloff, hierarchy));
      specs.push_back(programSpec(AoEstimator::Gtao, samples, 1, Falloff::Sao2012, hierarchy));
    }
  }
  return specs;
}

SaoPass::Variant::Variant(gl::Program built, std::optional<Storage> storage)
    : program(std::move(built)),
      reconstruction(program),
      hierarchy(storage ? DepthHierarchyPass::SamplingUniforms(program, *storage)
                        : DepthHierarchyPass::SamplingUniforms()),
      gbuffer(program.uniform("u_gbuffer")),
      gbufferSize(program.uniform("u_gbufferSize")),
      aoSize(program.uniform("u_aoSize")),
      aoScale(program.uniform("u_aoScale")),
      projScale(program.uniform("u_projScale")),
      radius(program.uniform("u_radius")),
      invRadius(program.uniform("u_invRadius")),
      estimatorKnots(program.uniform("u_estimatorKnots[0]")),
      maxRadiusPixels(program.uniform("u_maxRadiusPixels")) {}

const SaoPass::Variant& SaoPass::variant(const AoSettings& settings, std::optional<Storage> hierarchy) {
  // GTAO's programs depend on neither the spiral nor the falloff.
  const bool gtao = settings.estimator == AoEstimator::Gtao;
  const auto key = std::make_tuple(settings.estimator, settings.samples, gtao ? 1 : settings.spiralTurns,
                                   gtao ? Falloff::Sao2012 : settings.falloff, hierarchyDefine(hierarchy));
  auto it = variants_.find(key);
  if (it == variants_.end())
    it = variants_
             .emplace(key, Variant(resources_.build(programSpec(settings.estimator, settings.samples,
                                                                std::get<2>(key), std::get<3>(key), hierarchy)),
                                   hierarchy))
             .first;
  return it->second;
}

void SaoPass::render(const gl::Texture2D& gbuffer, const DepthHierarchyPass* hierarchy, const FrameCamera& camera,
                     const AoSettings& settings, int aoScale, glm::ivec2 aoSize) {
  using gl::Program;
  const std::optional<Storage> storage = hierarchy ? std::optional<Storage>(hierarchy->storage()) : std::nullopt;
  const Variant& sao = variant(settings, storage);
  sao.program.use();
  gbuffer.bind(0);
  Program::set(sao.gbuffer, 0);
  if (hierarchy) hierarchy->bindForSampling(sao.hierarchy, 1);
  Program::set(sao.gbufferSize, glm::vec2(gbuffer.width(), gbuffer.height()));
  Program::set(sao.aoSize, glm::vec2(aoSize));
  Program::set(sao.aoScale, static_cast<float>(aoScale));
  sao.reconstruction.set(camera.reconstruction);
  Program::set(sao.projScale, camera.projScale(gbuffer.height()));
  Program::set(sao.radius, settings.radius);
  Program::set(sao.invRadius, 1.0f / settings.radius);
  const EstimatorKnots knots = settings.estimatorKnots();
  std::array<glm::vec3, kEstimatorKnots> packed;
  for (int j = 0; j < kEstimatorKnots; ++j)
    packed[static_cast<size_t>(j)] = {intensityScale(settings, knots.at[j].intensity), knots.at[j].bias,
                                      knots.at[j].contrast};
  Program::set(sao.estimatorKnots, packed.data(), kEstimatorKnots);
  Program::set(sao.maxRadiusPixels, settings.maxScreenRadius * static_cast<float>(gbuffer.height()));
  resources_.triangle.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
