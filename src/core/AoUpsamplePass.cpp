#include "core/AoUpsamplePass.h"

#include "gl/PipelineState.h"

namespace obscura {

std::vector<ProgramSpec> AoUpsamplePass::programSpecs() {
  return {ProgramSpec{"ao-upsample", "fullscreen.vert", "ao_upsample.frag", {}, {}}};
}

AoUpsamplePass::AoUpsamplePass(const FullscreenTriangle& triangle)
    : triangle_(triangle), program_(programSpecs().front().build()) {}

void AoUpsamplePass::resize(int width, int height) {
  if (target_ && target_.width() == width && target_.height() == height) return;
  target_ = gl::RenderTarget("AO upsample", width, height, GL_NEAREST, gl::RenderTarget::Depth::None, false);
}

void AoUpsamplePass::render(const gl::Texture2D& halfResolutionAo, const gl::Texture2D& gbuffer,
                            const FrameCamera& camera, const AoSettings& settings) {
  target_.bindForDrawing();
  program_.use();
  halfResolutionAo.bind(0);
  program_.set("u_ao", 0);
  program_.set("u_aoSize", glm::vec2(halfResolutionAo.width(), halfResolutionAo.height()));
  gbuffer.bind(1);
  program_.set("u_gbuffer", 1);
  program_.set("u_gbufferSize", glm::vec2(gbuffer.width(), gbuffer.height()));
  program_.set("u_aoScale", 2.0f);
  program_.set("u_invSigma2", 1.0f / (settings.blurDepthSigma * settings.blurDepthSigma));
  setReconstructionUniforms(program_, camera.reconstruction);
  triangle_.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
