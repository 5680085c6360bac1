#include "core/SaoPass.h"

#include "core/SaoKernel.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

int hierarchyDefine(std::optional<DepthHierarchyPass::Storage> hierarchy) {
  return hierarchy ? static_cast<int>(*hierarchy) : 0;
}

}  // namespace

ProgramSpec SaoPass::programSpec(int samples, int spiralTurns, Falloff falloff, std::optional<Storage> hierarchy) {
  ProgramSpec spec;
  spec.name = "sao[samples=" + std::to_string(samples) + ",turns=" + std::to_string(spiralTurns) +
              ",falloff=" + falloffName(falloff) + ",depth=" +
              (hierarchy ? DepthHierarchyPass::storageName(*hierarchy) : "gbuffer") + "]";
  spec.vertexFile = "fullscreen.vert";
  spec.fragmentFile = "sao.frag";
  spec.defines = {{"NUM_SAMPLES", std::to_string(samples)},
                  {"NUM_SPIRAL_TURNS", std::to_string(spiralTurns)},
                  {"FALLOFF_SAO2012", falloff == Falloff::Sao2012 ? "1" : "0"},
                  {"DEPTH_HIERARCHY", std::to_string(hierarchyDefine(hierarchy))},
                  {"MAX_MIP_LEVEL", std::to_string(SaoKernel::kMaxMipLevel)},
                  {"LOG_MAX_OFFSET", std::to_string(SaoKernel::kLogMaxOffset)}};
  if (hierarchy == Storage::MipChain) spec.extensions = {"GL_EXT_shader_texture_lod"};
  return spec;
}

std::vector<ProgramSpec> SaoPass::programSpecs() {
  std::vector<ProgramSpec> specs;
  for (int samples : {4, 8, 11, 16, 24, 32})
    for (Falloff falloff : {Falloff::Sao2012, Falloff::Alchemy2011})
      for (std::optional<Storage> hierarchy :
           {std::optional<Storage>(), std::optional<Storage>(Storage::SeparateTextures),
            std::optional<Storage>(Storage::MipChain), std::optional<Storage>(Storage::Atlas)})
        specs.push_back(programSpec(samples, SaoKernel::bestSpiralTurns(samples), falloff, hierarchy));
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
      bias(program.uniform("u_bias")),
      intensityScale(program.uniform("u_intensityScale")),
      contrast(program.uniform("u_contrast")),
      maxRadiusPixels(program.uniform("u_maxRadiusPixels")) {}

const SaoPass::Variant& SaoPass::variant(const AoSettings& settings, std::optional<Storage> hierarchy) {
  const auto key = std::make_tuple(settings.samples, settings.spiralTurns, settings.falloff, hierarchyDefine(hierarchy));
  auto it = variants_.find(key);
  if (it == variants_.end())
    it = variants_
             .emplace(key, Variant(resources_.build(programSpec(settings.samples, settings.spiralTurns,
                                                                settings.falloff, hierarchy)),
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
  const EstimatorParameters estimator = settings.estimator();
  Program::set(sao.bias, estimator.bias);
  Program::set(sao.intensityScale, SaoKernel::intensityScale(settings.falloff, estimator.intensity, settings.samples));
  Program::set(sao.contrast, estimator.contrast);
  Program::set(sao.maxRadiusPixels, settings.maxScreenRadius * static_cast<float>(gbuffer.height()));
  resources_.triangle.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
