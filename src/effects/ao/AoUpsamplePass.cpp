#include "effects/ao/AoUpsamplePass.h"

#include "frame/FullscreenPass.h"

namespace obscura {

std::vector<ProgramSpec> AoUpsamplePass::programSpecs() {
  return {ProgramSpec{"ao-upsample", "lib/fullscreen.vert", "ao/ao_upsample.frag", {}, {}}};
}

void AoUpsamplePass::render(const gl::Texture2D& halfResolutionAo, const gl::Texture2D& gbuffer,
                            const FrameCamera& camera, const AoSettings& settings) const {
  FullscreenDraw upsample(resources_.program(programSpecs().front()), resources_.triangle);
  upsample.texture("u_ao", halfResolutionAo);
  upsample.set("u_aoSize", glm::vec2(halfResolutionAo.width(), halfResolutionAo.height()));
  upsample.texture("u_gbuffer", gbuffer);
  upsample.set("u_gbufferSize", glm::vec2(gbuffer.width(), gbuffer.height()));
  upsample.set("u_aoScale", 2.0f);
  upsample.set("u_invSigma2", 1.0f / (settings.blurDepthSigmaDistance() * settings.blurDepthSigmaDistance()));
  setReconstruction(upsample.program(), camera.reconstruction);
  upsample.draw();
}

}  // namespace obscura
