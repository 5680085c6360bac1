#include "effects/ao/BilateralBlurPass.h"

#include "frame/FullscreenPass.h"

namespace obscura {
namespace {

// The blur's spatial width is at most this fraction of the AO radius projected at the centre (blur.frag): measured
// against the ray-traced reference over the 72 tuning cases, 1, 0.5, 0.25, 0.15, 0.1 and 0.05 gave a mean MAE at
// 0.1 object size of 0.0127, 0.0115, 0.0095, 0.0101, 0.0109 and 0.0114 against 0.0128 without the limit
// (docs/accuracy.md, "Blur width").
constexpr float kBlurWidthPerRadius = 0.25f;

}  // namespace

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

void BilateralBlurPass::render(Direction direction, const gl::Texture2D& ao, const gl::Texture2D& gbuffer,
                               const FrameCamera& camera, const AoSettings& settings, int aoScale) const {
  FullscreenDraw blur(resources_.program(programSpec(settings.blurRadius, settings.blurNormalAware)),
                      resources_.triangle);
  blur.texture("u_ao", ao);
  blur.set("u_aoSize", glm::vec2(ao.width(), ao.height()));
  const float stride = static_cast<float>(settings.blurStride);
  blur.set("u_stepPixels", direction == Direction::Horizontal ? glm::vec2(stride, 0.0f) : glm::vec2(0.0f, stride));
  // Spatial Gaussian with s = (radius + 1) / 2 taps: the outermost tap keeps exp(-2 R^2 / (R + 1)^2), 0.28 at R = 4.
  const float s = 0.5f * static_cast<float>(settings.blurRadius + 1);
  blur.set("u_gaussianK", 1.0f / (2.0f * s * s));
  blur.set("u_widthScale", camera.projScale(gbuffer.height()) *
                               (kBlurWidthPerRadius * settings.radius / (static_cast<float>(aoScale) * stride)));
  blur.set("u_invSigma2", 1.0f / (settings.blurDepthSigmaDistance() * settings.blurDepthSigmaDistance()));
  if (settings.blurNormalAware) {
    // The tap's surface point and normal, rebuilt at the G-buffer pixel it stands for.
    setReconstruction(blur.program(), camera.reconstruction);
    blur.set("u_gbufferSize", glm::vec2(gbuffer.width(), gbuffer.height()));
    blur.set("u_aoScale", static_cast<float>(aoScale));
    blur.texture("u_gbuffer", gbuffer);
  } else {
    // Plain depth: z from the depth code alone.
    blur.set("u_near", camera.near);
    blur.set("u_depthRange", camera.far - camera.near);
  }
  blur.draw();
}

}  // namespace obscura
