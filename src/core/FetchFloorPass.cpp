#include "core/FetchFloorPass.h"

#include <string>

#include "core/SaoKernel.h"
#include "gl/PipelineState.h"

namespace obscura {

ProgramSpec FetchFloorPass::programSpec(int samples) {
  return ProgramSpec{"fetch-floor[samples=" + std::to_string(samples) + "]",
                     "fullscreen.vert",
                     "fetch_floor.frag",
                     {{"NUM_SAMPLES", std::to_string(samples)}},
                     {}};
}

std::vector<ProgramSpec> FetchFloorPass::programSpecs() {
  std::vector<ProgramSpec> specs;
  for (int samples : {4, 8, 11, 16, 24, 32}) specs.push_back(programSpec(samples));
  return specs;
}

void FetchFloorPass::render(const gl::Texture2D& gbuffer, int samples, int spiralTurns, float diskRadiusPixels) {
  if (!target_ || target_.width() != gbuffer.width() || target_.height() != gbuffer.height())
    target_ = gl::RenderTarget("fetch floor", gbuffer.width(), gbuffer.height(), GL_NEAREST,
                               gl::RenderTarget::Depth::None, false);
  auto it = programs_.find(samples);
  if (it == programs_.end()) it = programs_.emplace(samples, programSpec(samples).build()).first;
  const gl::Program& program = it->second;

  std::vector<float> offsets;
  for (int i = 0; i < samples; ++i) {
    float alpha = 0.0f;
    const glm::vec2 direction = SaoKernel::tapDirection(i, samples, spiralTurns, 0.0f, &alpha);
    const glm::vec2 pixels = glm::floor(alpha * diskRadiusPixels * direction + 0.5f);
    offsets.push_back(pixels.x / static_cast<float>(gbuffer.width()));
    offsets.push_back(pixels.y / static_cast<float>(gbuffer.height()));
  }
  target_.bindForDrawing();
  program.use();
  gbuffer.bind(0);
  program.set("u_gbuffer", 0);
  glUniform2fv(program.uniform("u_offsets[0]"), samples, offsets.data());
  triangle_.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
