#pragma once
// Scalable Ambient Obscurance from the G-buffer into the bound RGBA8 target: R = ambient visibility, GB = the
// centre's 16-bit depth code (the blur's key, so the blur reads a single texture). Shader: shaders_es2/sao.frag; CPU
// mirror and equations: core/SaoKernel.h. Far taps read the depth hierarchy when one is given.
#include <map>
#include <optional>
#include <tuple>
#include <vector>

#include "core/AoSettings.h"
#include "core/DepthHierarchyPass.h"
#include "core/EffectTable.h"
#include "core/FrameContext.h"

namespace obscura {

class SaoPass {
 public:
  using Storage = DepthHierarchyPass::Storage;
  // The program variant for a sample count, spiral turns, falloff and depth source (compile-time constants):
  // no hierarchy (every tap reads the G-buffer), or the hierarchy in the given storage.
  static ProgramSpec programSpec(int samples, int spiralTurns, Falloff falloff, std::optional<Storage> hierarchy);
  // Every variant the presets and the documented sample counts (4, 8, 11, 16, 24, 32) use.
  static std::vector<ProgramSpec> programSpecs();

  SaoPass(const EffectResources& resources) : resources_(resources) {}
  // Draws into the bound framebuffer, whose size is `aoSize`: the G-buffer's, or floor(size / 2) at half
  // resolution (`aoScale` 2). `hierarchy` null: every tap reads the G-buffer.
  void render(const gl::Texture2D& gbuffer, const DepthHierarchyPass* hierarchy, const FrameCamera& camera,
              const AoSettings& settings, int aoScale, glm::ivec2 aoSize);

 private:
  struct Variant {
    explicit Variant(gl::Program built, std::optional<Storage> hierarchy);
    gl::Program program;
    ReconstructionUniforms reconstruction;
    DepthHierarchyPass::SamplingUniforms hierarchy;
    GLint gbuffer, gbufferSize, aoSize, aoScale, projScale, radius, bias, intensityScale, contrast, maxRadiusPixels;
  };
  const Variant& variant(const AoSettings& settings, std::optional<Storage> hierarchy);

  const EffectResources& resources_;
  std::map<std::tuple<int, int, Falloff, int>, Variant> variants_;
};

}  // namespace obscura
