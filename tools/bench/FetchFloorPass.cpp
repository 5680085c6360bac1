#include "FetchFloorPass.h"

#include <string>

#include "effects/ao/SaoKernel.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

// The same number of G-buffer fetches per pixel as SAO (1 + NUM_SAMPLES), at the spiral's offsets for a typical
// disk (precomputed on the CPU, identical for every pixel so access is perfectly coherent), and no arithmetic beyond
// summing. SAO cost / this cost is how much the estimator's maths and its scattered taps add over bare bandwidth.
constexpr const char* kFloorShader = R"(
#include "lib/precision.glsl"

uniform sampler2D u_gbuffer;
uniform vec2 u_offsets[NUM_SAMPLES];  // uv offsets

varying vec2 v_uv;

void main() {
  vec4 sum = texture2D(u_gbuffer, v_uv);
  for (int i = 0; i < NUM_SAMPLES; i++) sum += texture2D(u_gbuffer, v_uv + u_offsets[i]);
  gl_FragColor = sum;
}
)";

}  // namespace

ProgramSpec FetchFloorPass::programSpec(int samples) {
  ProgramSpec spec{"fetch-floor[samples=" + std::to_string(samples) + "]",
                   "lib/fullscreen.vert",
                   "",
                   {{"NUM_SAMPLES", std::to_string(samples)}, {"FAR_RAY", "0"}},
                   {},
                   kFloorShader};
  return spec;
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
  gl::Program::set(program.uniform("u_gbuffer"), 0);
  glUniform2fv(program.uniform("u_offsets[0]"), samples, offsets.data());
  triangle_.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
