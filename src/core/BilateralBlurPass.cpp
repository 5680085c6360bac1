#include "core/BilateralBlurPass.h"

#include "gl/PipelineState.h"

namespace obscura {

ProgramSpec BilateralBlurPass::programSpec(int radius, bool normalAware) {
  ProgramSpec spec;
  spec.name = "blur[radius=" + std::to_string(radius) + ",normals=" + (normalAware ? "on" : "off") + "]";
  spec.vertexFile = "fullscreen.vert";
  spec.fragmentFile = "blur.frag";
  spec.defines = {{"BLUR_RADIUS", std::to_string(radius)}, {"NORMAL_AWARE", normalAware ? "1" : "0"}};
  return spec;
}

std::vector<ProgramSpec> BilateralBlurPass::programSpecs() {
  std::vector<ProgramSpec> specs;
  for (int radius = 1; radius <= 8; ++radius)
    for (bool normals : {true, false}) specs.push_back(programSpec(radius, normals));
  return specs;
}

void BilateralBlurPass::resize(int width, int height) {
  if (vertical_ && vertical_.width() == width && vertical_.height() == height) return;
  horizontal_ = gl::RenderTarget("blur (horizontal)", width, height, GL_NEAREST, gl::RenderTarget::Depth::None, false);
  vertical_ = gl::RenderTarget("blur (vertical)", width, height, GL_NEAREST, gl::RenderTarget::Depth::None, false);
}

const gl::Program& BilateralBlurPass::program(int radius, bool normalAware) {
  const auto key = std::make_pair(radius, normalAware);
  auto it = programs_.find(key);
  if (it == programs_.end()) it = programs_.emplace(key, programSpec(radius, normalAware).build()).first;
  return it->second;
}

void BilateralBlurPass::render(Direction direction, const gl::Texture2D& ao, const gl::Texture2D& gbuffer,
                               const FrameCamera& camera, const AoSettings& settings, int aoScale) {
  const gl::Program& blur = program(settings.blurRadius, settings.blurNormalAware);
  const bool horizontal = direction == Direction::Horizontal;
  const gl::Texture2D& input = horizontal ? ao : horizontal_.color();
  (horizontal ? horizontal_ : vertical_).bindForDrawing();
  blur.use();
  input.bind(0);
  blur.set("u_ao", 0);
  blur.set("u_aoSize", glm::vec2(input.width(), input.height()));
  const float stride = static_cast<float>(settings.blurStride);
  blur.set("u_stepPixels", horizontal ? glm::vec2(stride, 0.0f) : glm::vec2(0.0f, stride));
  // Spatial Gaussian with s = (radius + 1) / 2 taps: the outermost tap keeps exp(-2 R^2 / (R + 1)^2), 0.28 at R = 4.
  const float s = 0.5f * static_cast<float>(settings.blurRadius + 1);
  blur.set("u_gaussianK", 1.0f / (2.0f * s * s));
  blur.set("u_invSigma2", 1.0f / (settings.blurDepthSigma * settings.blurDepthSigma));
  setReconstructionUniforms(blur, camera.reconstruction);
  blur.set("u_gbufferSize", glm::vec2(gbuffer.width(), gbuffer.height()));
  blur.set("u_aoScale", static_cast<float>(aoScale));
  if (settings.blurNormalAware) {
    gbuffer.bind(1);
    blur.set("u_gbuffer", 1);
  } else {
    blur.set("u_near", camera.near);
    blur.set("u_depthRange", camera.far - camera.near);
  }
  triangle_.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
