#pragma once
// Scalable Ambient Obscurance from the G-buffer into one RGBA8 target: R = ambient visibility, GB = the centre's
// 16-bit depth code (the blur's key, so the blur reads a single texture). Shader: shaders_es2/sao.frag; CPU mirror
// and equations: core/SaoKernel.h. Far taps read the depth hierarchy when one is given.
#include <map>
#include <tuple>
#include <vector>

#include "core/AoSettings.h"
#include "core/DepthHierarchyPass.h"
#include "core/FrameContext.h"
#include "core/ShaderLibrary.h"
#include "gl/RenderTarget.h"

namespace obscura {

class SaoPass {
 public:
  // How far taps reach their depth: the G-buffer only, or the hierarchy in one of its two storages.
  enum class DepthSource { GBufferOnly = 0, SeparateTextures = 1, MipChain = 2, Atlas = 3 };

  // The program variant for a sample count, spiral turns, falloff and depth source (compile-time constants).
  static ProgramSpec programSpec(int samples, int spiralTurns, Falloff falloff, DepthSource source);
  // Every variant the presets and the documented sample counts (4, 8, 11, 16, 24, 32) use.
  static std::vector<ProgramSpec> programSpecs();

  explicit SaoPass(const FullscreenTriangle& triangle) : triangle_(triangle) {}
  // The AO target: the G-buffer's size, or floor(size / 2) at half resolution.
  void resize(int width, int height);
  // `hierarchy` null: every tap reads the G-buffer. `aoScale`: 1, or 2 for half resolution (target must match).
  void render(const gl::Texture2D& gbuffer, const DepthHierarchyPass* hierarchy, const FrameCamera& camera,
              const AoSettings& settings, int aoScale);
  const gl::RenderTarget& target() const { return target_; }

 private:
  const gl::Program& program(const AoSettings& settings, DepthSource source);

  const FullscreenTriangle& triangle_;
  gl::RenderTarget target_;
  std::map<std::tuple<int, int, Falloff, DepthSource>, gl::Program> programs_;
};

}  // namespace obscura
