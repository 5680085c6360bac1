#pragma once
// Scalable Ambient Obscurance from the G-buffer into one RGBA8 target: R = ambient visibility, GB = the centre's
// 16-bit depth code (the blur's key, so the blur reads a single texture). Shader: shaders_es2/sao.frag; CPU mirror
// and equations: core/SaoKernel.h.
#include <map>
#include <tuple>
#include <vector>

#include "core/AoSettings.h"
#include "core/FrameContext.h"
#include "core/ShaderLibrary.h"
#include "gl/RenderTarget.h"

namespace obscura {

class SaoPass {
 public:
  // The program variant for a sample count, spiral turns and falloff (compile-time constants of the shader).
  static ProgramSpec programSpec(int samples, int spiralTurns, Falloff falloff);
  // Every variant the presets and the documented sample counts (4, 8, 11, 16, 24, 32) use.
  static std::vector<ProgramSpec> programSpecs();

  explicit SaoPass(const FullscreenTriangle& triangle) : triangle_(triangle) {}
  void resize(int width, int height);
  void render(const gl::Texture2D& gbuffer, const FrameCamera& camera, const AoSettings& settings);
  const gl::RenderTarget& target() const { return target_; }

 private:
  const gl::Program& program(const AoSettings& settings);

  const FullscreenTriangle& triangle_;
  gl::RenderTarget target_;
  std::map<std::tuple<int, int, Falloff>, gl::Program> programs_;
};

}  // namespace obscura
