#pragma once
// Separable depth- and normal-aware bilateral blur of the AO (shaders_es2/ao/blur.frag, weights documented there).
// One direction per call, drawn into the bound target, in the AO + depth key layout of the SAO output.
#include <map>
#include <utility>
#include <vector>

#include "effects/ao/AoSettings.h"
#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"
#include "gl/RenderTarget.h"

namespace obscura {

class BilateralBlurPass {
 public:
  enum class Direction { Horizontal, Vertical };

  static ProgramSpec programSpec(int radius, bool normalAware);
  static std::vector<ProgramSpec> programSpecs();  // radius 1 .. 8, with and without normals

  explicit BilateralBlurPass(const EffectResources& resources) : resources_(resources) {}
  // Blurs `ao` (R = AO, GB = depth key) along `direction` into the bound framebuffer, of ao's size.
  // `aoScale`: 1, or 2 when the AO is at half the G-buffer's resolution.
  void render(Direction direction, const gl::Texture2D& ao, const gl::Texture2D& gbuffer, const FrameCamera& camera,
              const AoSettings& settings, int aoScale);

 private:
  struct Variant {
    Variant(gl::Program built, bool normalAware);
    gl::Program program;
    GLint ao, aoSize, stepPixels, gaussianK, invSigma2;
    // Normal-aware: the tap's surface point and normal, rebuilt at the G-buffer pixel it stands for.
    ReconstructionUniforms reconstruction;
    GLint gbuffer = -1, gbufferSize = -1, aoScale = -1;
    GLint near = -1, depthRange = -1;  // plain depth: z from the depth code alone
  };
  const Variant& variant(int radius, bool normalAware);

  const EffectResources& resources_;
  std::map<std::pair<int, bool>, Variant> variants_;
};

}  // namespace obscura
