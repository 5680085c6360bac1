#include "core/LightingPass.h"

#include <glm/geometric.hpp>

#include "gl/PipelineState.h"

namespace obscura {

std::vector<ProgramSpec> LightingPass::programSpecs() {
  return {ProgramSpec{"lighting", "geometry.vert", "lighting.frag", {}, {}}};
}

LightingPass::LightingPass() : program_(programSpecs().front().build()) {}

void LightingPass::render(const GpuScene& scene, const FrameCamera& camera, const Lighting& lighting,
                          const gl::Texture2D& ao, float aoSplitX) {
  glClearColor(lighting.background.r, lighting.background.g, lighting.background.b, 1.0f);
  glClearDepthf(1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);

  program_.use();
  program_.set("u_projection", camera.projection);
  const glm::mat3 viewRotation(camera.view);
  program_.set("u_lightDirection", glm::normalize(viewRotation * lighting.directionToLight));
  program_.set("u_viewUp", viewRotation * glm::vec3(0.0f, 1.0f, 0.0f));
  program_.set("u_lightColor", lighting.lightColor);
  program_.set("u_skyColor", lighting.skyColor);
  program_.set("u_groundColor", lighting.groundColor);
  program_.set("u_viewportSize", glm::vec2(camera.width, camera.height));
  program_.set("u_aoSplitX", aoSplitX);
  ao.bind(1);
  program_.set("u_ao", 1);
  scene.draw(program_, camera.view);
  gl::restoreBaselineState();
}

}  // namespace obscura
