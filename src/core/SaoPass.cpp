#include "core/SaoPass.h"

#include "core/SaoKernel.h"
#include "gl/PipelineState.h"

namespace obscura {

ProgramSpec SaoPass::programSpec(int samples, int spiralTurns, Falloff falloff, DepthSource source) {
  static const char* sourceNames[] = {"gbuffer", "separate", "mipchain", "atlas"};
  ProgramSpec spec;
  spec.name = "sao[samples=" + std::to_string(samples) + ",turns=" + std::to_string(spiralTurns) +
              ",falloff=" + falloffName(falloff) + ",depth=" + sourceNames[static_cast<int>(source)] + "]";
  spec.vertexFile = "fullscreen.vert";
  spec.fragmentFile = "sao.frag";
  spec.defines = {{"NUM_SAMPLES", std::to_string(samples)},
                  {"NUM_SPIRAL_TURNS", std::to_string(spiralTurns)},
                  {"FALLOFF_SAO2012", falloff == Falloff::Sao2012 ? "1" : "0"},
                  {"DEPTH_HIERARCHY", std::to_string(static_cast<int>(source))},
                  {"MAX_MIP_LEVEL", std::to_string(SaoKernel::kMaxMipLevel)},
                  {"LOG_MAX_OFFSET", std::to_string(SaoKernel::kLogMaxOffset)}};
  if (source == DepthSource::MipChain) spec.extensions = {"GL_EXT_shader_texture_lod"};
  return spec;
}

std::vector<ProgramSpec> SaoPass::programSpecs() {
  std::vector<ProgramSpec> specs;
  for (int samples : {4, 8, 11, 16, 24, 32})
    for (Falloff falloff : {Falloff::Sao2012, Falloff::Alchemy2011})
      for (DepthSource source : {DepthSource::GBufferOnly, DepthSource::SeparateTextures, DepthSource::MipChain,
                                 DepthSource::Atlas})
        specs.push_back(programSpec(samples, SaoKernel::bestSpiralTurns(samples), falloff, source));
  return specs;
}

void SaoPass::resize(int width, int height) {
  if (target_ && target_.width() == width && target_.height() == height) return;
  target_ = gl::RenderTarget("SAO", width, height, GL_NEAREST, gl::RenderTarget::Depth::None, false);
}

const gl::Program& SaoPass::program(const AoSettings& settings, DepthSource source) {
  const auto key = std::make_tuple(settings.samples, settings.spiralTurns, settings.falloff, source);
  auto it = programs_.find(key);
  if (it == programs_.end())
    it = programs_.emplace(key, programSpec(settings.samples, settings.spiralTurns, settings.falloff, source).build())
             .first;
  return it->second;
}

void SaoPass::render(const gl::Texture2D& gbuffer, const DepthHierarchyPass* hierarchy, const FrameCamera& camera,
                     const AoSettings& settings, int aoScale) {
  DepthSource source = DepthSource::GBufferOnly;
  if (hierarchy) {
    switch (hierarchy->storage()) {
      case DepthHierarchyPass::Storage::SeparateTextures: source = DepthSource::SeparateTextures; break;
      case DepthHierarchyPass::Storage::Atlas: source = DepthSource::Atlas; break;
      case DepthHierarchyPass::Storage::MipChain: source = DepthSource::MipChain; break;
    }
  }
  const gl::Program& sao = program(settings, source);
  target_.bindForDrawing();
  sao.use();
  gbuffer.bind(0);
  sao.set("u_gbuffer", 0);
  if (hierarchy) hierarchy->bindForSampling(sao, 1);
  sao.set("u_gbufferSize", glm::vec2(gbuffer.width(), gbuffer.height()));
  sao.set("u_aoSize", glm::vec2(target_.width(), target_.height()));
  sao.set("u_aoScale", static_cast<float>(aoScale));
  setReconstructionUniforms(sao, camera.reconstruction);
  sao.set("u_projScale", camera.projScale(gbuffer.height()));
  sao.set("u_radius", settings.radius);
  const EstimatorParameters estimator = settings.estimator();
  sao.set("u_bias", estimator.bias);
  sao.set("u_intensityScale", SaoKernel::intensityScale(settings.falloff, estimator.intensity, settings.samples));
  sao.set("u_contrast", estimator.contrast);
  sao.set("u_maxRadiusPixels", settings.maxScreenRadius * static_cast<float>(gbuffer.height()));
  triangle_.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
