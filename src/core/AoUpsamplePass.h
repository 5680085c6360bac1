#pragma once
// Depth- and normal-aware upsampling of half-resolution AO to the G-buffer's resolution
// (shaders_es2/ao_upsample.frag). Output has the AO + depth key layout of the other AO targets.
#include <vector>

#include "core/AoSettings.h"
#include "core/FrameContext.h"
#include "core/ShaderLibrary.h"
#include "gl/RenderTarget.h"

namespace obscura {

class AoUpsamplePass {
 public:
  static std::vector<ProgramSpec> programSpecs();

  explicit AoUpsamplePass(const FullscreenTriangle& triangle);
  void resize(int width, int height);
  void render(const gl::Texture2D& halfResolutionAo, const gl::Texture2D& gbuffer, const FrameCamera& camera,
              const AoSettings& settings);
  const gl::RenderTarget& target() const { return target_; }

 private:
  const FullscreenTriangle& triangle_;
  gl::Program program_;
  gl::RenderTarget target_;
};

}  // namespace obscura
