#pragma once
// The one geometry pass of the AO pipeline: scene -> one RGBA8 G-buffer (RG octahedral view-space normal, BA 16-bit
// linear depth) plus a depth renderbuffer for visibility. Cleared to depth code 65535, the background marker.
#include <vector>

#include "core/FrameContext.h"
#include "core/GpuScene.h"
#include "core/ShaderLibrary.h"
#include "gl/RenderTarget.h"

namespace obscura {

class GBufferPass {
 public:
  static std::vector<ProgramSpec> programSpecs();

  explicit GBufferPass(bool depth24);
  // (Re)allocates the target when the size changes.
  void resize(int width, int height);
  void render(const GpuScene& scene, const FrameCamera& camera);
  const gl::RenderTarget& target() const { return target_; }

 private:
  bool depth24_;
  gl::Program program_;
  gl::RenderTarget target_;
};

}  // namespace obscura
