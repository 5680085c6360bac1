#include "effects/ao/BilateralBlurPass.h"

#include "gl/PipelineState.h"

namespace obscura {

ProgramSpec BilateralBlurPass::programSpec(int radius, bool normalAware) {
  ProgramSpec spec;
  spec.name = "blur[radius=" + std::to_string(radius) + ",normals=" + (normalAware ? "on" : "off") + "]";
  spec.vertexFile = "lib/fullscreen.vert";
  spec.fragmentFile = "ao/blur.frag";
  spec.defines = {{"BLUR_RADIUS", std::to_string(radius)}, {"NORMAL_AWARE", normalAware ? "1" : "0"}};
  return spec;
}

std::vector<ProgramSpec> BilateralBlurPass::programSpecs() {
  std::vector<ProgramSpec> specs;
  for (int radius = 1; radius <= 8; ++radius)
    for (bool normals : {true, false}) specs.push_back(programSpec(radius, normals));
  return specs;
}

BilateralBlurPass::Variant::Variant(gl::Program built, bool normalAware)
    : program(std::move(built)),
      ao(program.uniform("u_ao")),
      aoSize(program.uniform("u_aoSize")),
      stepPixels(program.uniform("u_stepPixels")),
      gaussianK(program.uniform("u_gaussianK")),
      invSigma2(program.uniform("u_invSigma2")) {
  if (normalAware) {
    reconstruction = ReconstructionUniforms(program);
    gbuffer = program.uniform("u_gbuffer");
    gbufferSize = program.uniform("u_gbufferSize");
    aoScale = program.uniform("u_aoScale");
  } else {
    near = program.uniform("u_near");
    depthRange = program.uniform("u_depthRange");
  }
}

const BilateralBlurPass::Variant& BilateralBlurPass::variant(int radius, bool normalAware) {
  const auto key = std::make_pair(radius, normalAware);
  auto it = variants_.find(key);
  if (it == variants_.end())
    it = variants_.emplace(key, Variant(resources_.build(programSpec(radius, normalAware)), normalAware)).first;
  return it->second;
}

void BilateralBlurPass::render(Direction direction, const gl::Texture2D& ao, const gl::Texture2D& gbuffer,
                               const FrameCamera& camera, const AoSettings& settings, int aoScale) {
  using gl::Program;
  const Variant& blur = variant(settings.blurRadius, settings.blurNormalAware);
  blur.program.use();
  ao.bind(0);
  Program::set(blur.ao, 0);
  Program::set(blur.aoSize, glm::vec2(ao.width(), ao.height()));
  const float stride = static_cast<float>(settings.blurStride);
  Program::set(blur.stepPixels,
               direction == Direction::Horizontal ? glm::vec2(stride, 0.0f) : glm::vec2(0.0f, stride));
  // Spatial Gaussian with s = (radius + 1) / 2 taps: the outermost tap keeps exp(-2 R^2 / (R + 1)^2), 0.28 at R = 4.
  const float s = 0.5f * static_cast<float>(settings.blurRadius + 1);
  Program::set(blur.gaussianK, 1.0f / (2.0f * s * s));
  Program::set(blur.invSigma2, 1.0f / (settings.blurDepthSigmaDistance() * settings.blurDepthSigmaDistance()));
  if (settings.blurNormalAware) {
    blur.reconstruction.set(camera.reconstruction);
    Program::set(blur.gbufferSize, glm::vec2(gbuffer.width(), gbuffer.height()));
    Program::set(blur.aoScale, static_cast<float>(aoScale));
    gbuffer.bind(1);
    Program::set(blur.gbuffer, 1);
  } else {
    Program::set(blur.near, camera.near);
    Program::set(blur.depthRange, camera.far - camera.near);
  }
  resources_.triangle.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
