#pragma once
// The diagnostic views (shaders_es2/debug_view.frag): AO as grey, G-buffer normals as colour, linear depth as grey,
// and the geometry mask (which pixels hold geometry; what obscura-compare measures over).
#include <map>
#include <vector>

#include "core/FrameContext.h"
#include "core/ShaderLibrary.h"
#include "gl/RenderTarget.h"

namespace obscura {

class DebugViewPass {
 public:
  enum class Mode { Ao = 0, Normals = 1, Depth = 2, Mask = 3 };

  static std::vector<ProgramSpec> programSpecs();

  explicit DebugViewPass(const FullscreenTriangle& triangle) : triangle_(triangle) {}
  // Draws into the bound framebuffer. `source`: the AO texture (Mode::Ao) or the G-buffer (the others).
  void render(Mode mode, const gl::Texture2D& source, const FrameCamera& camera);

 private:
  const FullscreenTriangle& triangle_;
  std::map<Mode, gl::Program> programs_;
};

}  // namespace obscura
