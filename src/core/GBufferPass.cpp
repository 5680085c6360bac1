#include "core/GBufferPass.h"

#include "core/LinearDepthPacking.h"
#include "core/NormalEncoding.h"
#include "gl/PipelineState.h"

namespace obscura {

std::vector<ProgramSpec> GBufferPass::programSpecs() {
  return {ProgramSpec{"gbuffer", "geometry.vert", "gbuffer.frag", {}, {}}};
}

GBufferPass::GBufferPass(bool depth24) : depth24_(depth24), program_(programSpecs().front().build()) {}

void GBufferPass::resize(int width, int height) {
  if (target_ && target_.width() == width && target_.height() == height) return;
  // NEAREST: every reader fetches whole texels; filtering packed bytes would mix unrelated values.
  target_ = gl::RenderTarget("G-buffer", width, height, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer, depth24_);
}

void GBufferPass::render(const GpuScene& scene, const FrameCamera& camera) {
  target_.bindForDrawing();
  // Background: normal (0, 0, 1) and depth code 65535. A channel of 1.0 stores byte 255.
  const auto normal = encodeNormal(glm::vec3(0.0f, 0.0f, 1.0f));
  glClearColor(LinearDepthPacking::channelFromByte(normal[0]), LinearDepthPacking::channelFromByte(normal[1]), 1.0f,
               1.0f);
  glClearDepthf(1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);

  program_.use();
  program_.set("u_projection", camera.projection);
  program_.set("u_near", camera.near);
  program_.set("u_depthRange", camera.far - camera.near);
  scene.draw(program_, camera.view);
  gl::restoreBaselineState();
}

}  // namespace obscura
