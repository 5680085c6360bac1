#pragma once
// The benchmark's floor for the SAO pass: as many G-buffer fetches per pixel as SAO makes, with no arithmetic.
// obscura-bench's own program (its shader text lives in FetchFloorPass.cpp, not in the renderer's shaders_es2/), so
// neither the core library nor the web module carries it; obscura-shaders lists it for the GLSL checks.
#include <map>
#include <vector>

#include "frame/FullscreenTriangle.h"
#include "gl/RenderTarget.h"
#include "gl/ShaderLibrary.h"

namespace obscura {

class FetchFloorPass {
 public:
  static ProgramSpec programSpec(int samples);
  static std::vector<ProgramSpec> programSpecs();  // the sample counts SaoPass::programSpecs() covers

  explicit FetchFloorPass(const FullscreenTriangle& triangle) : triangle_(triangle) {}
  // Fetches at the spiral offsets of a `diskRadiusPixels` disk (SaoKernel::tapDirection, rotation 0).
  void render(const gl::Texture2D& gbuffer, int samples, int spiralTurns, float diskRadiusPixels);

 private:
  const FullscreenTriangle& triangle_;
  gl::RenderTarget target_;
  std::map<int, gl::Program> programs_;
};

}  // namespace obscura
