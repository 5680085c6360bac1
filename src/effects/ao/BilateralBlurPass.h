#pragma once
// Separable depth- and normal-aware bilateral blur of the AO (shaders_es2/ao/blur.frag, weights documented there).
// One direction per call, drawn into the bound target, in the AO + depth key layout of the SAO output.
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
              const AoSettings& settings, int aoScale) const;

 private:
  const EffectResources& resources_;
};

}  // namespace obscura
