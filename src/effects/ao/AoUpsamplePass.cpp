#include "effects/ao/AoUpsamplePass.h"

#include "gl/PipelineState.h"

namespace obscura {

std::vector<ProgramSpec> AoUpsamplePass::programSpecs() {
  return {ProgramSpec{"ao-upsample", "lib/fullscreen.vert", "ao/ao_upsample.frag", {}, {}}};
}

AoUpsamplePass::AoUpsamplePass(const EffectResources& resources)
    : resources_(resources),
      program_(resources.build(programSpecs().front())),
      reconstruction_(program_),
      ao_(program_.uniform("u_ao")),
      aoSize_(program_.uniform("u_aoSize")),
      gbuffer_(program_.uniform("u_gbuffer")),
      gbufferSize_(program_.uniform("u_gbufferSize")),
      aoScale_(program_.uniform("u_aoScale")),
      invSigma2_(program_.uniform("u_invSigma2")) {}

void AoUpsamplePass::render(const gl::Texture2D& halfResolutionAo, const gl::Texture2D& gbuffer,
                            const FrameCamera& camera, const AoSettings& settings) {
  using gl::Program;
  program_.use();
  halfResolutionAo.bind(0);
  Program::set(ao_, 0);
  Program::set(aoSize_, glm::vec2(halfResolutionAo.width(), halfResolutionAo.height()));
  gbuffer.bind(1);
  Program::set(gbuffer_, 1);
  Program::set(gbufferSize_, glm::vec2(gbuffer.width(), gbuffer.height()));
  Program::set(aoScale_, 2.0f);
  Program::set(invSigma2_, 1.0f / (settings.blurDepthSigmaDistance() * settings.blurDepthSigmaDistance()));
  reconstruction_.set(camera.reconstruction);
  resources_.triangle.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
