#pragma once
// Depth- and normal-aware upsampling of half-resolution AO to the G-buffer's resolution
// (shaders_es2/ao/ao_upsample.frag), drawn into the bound target in the AO + depth key layout of the other AO targets.
#include <vector>

#include "effects/ao/AoSettings.h"
#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"
#include "gl/RenderTarget.h"

namespace obscura {

class AoUpsamplePass {
 public:
  static std::vector<ProgramSpec> programSpecs();

  explicit AoUpsamplePass(const EffectResources& resources) : resources_(resources) {}
  void render(const gl::Texture2D& halfResolutionAo, const gl::Texture2D& gbuffer, const FrameCamera& camera,
              const AoSettings& settings) const;

 private:
  const EffectResources& resources_;
};

}  // namespace obscura
