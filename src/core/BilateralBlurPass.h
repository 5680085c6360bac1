#pragma once
// Separable depth- and normal-aware bilateral blur of the AO (shaders_es2/blur.frag, weights documented there).
// Horizontal then vertical, each into its own RGBA8 target with the AO + depth key layout of the SAO output.
#include <map>
#include <utility>
#include <vector>

#include "core/AoSettings.h"
#include "core/FrameContext.h"
#include "core/ShaderLibrary.h"
#include "gl/RenderTarget.h"

namespace obscura {

class BilateralBlurPass {
 public:
  enum class Direction { Horizontal, Vertical };

  static ProgramSpec programSpec(int radius, bool normalAware);
  static std::vector<ProgramSpec> programSpecs();  // radius 1 .. 8, with and without normals

  explicit BilateralBlurPass(const FullscreenTriangle& triangle) : triangle_(triangle) {}
  void resize(int width, int height);
  // Horizontal reads `ao` and writes the intermediate target; vertical reads that and writes output().
  // `aoScale`: 1, or 2 when the AO is at half the G-buffer's resolution.
  void render(Direction direction, const gl::Texture2D& ao, const gl::Texture2D& gbuffer, const FrameCamera& camera,
              const AoSettings& settings, int aoScale);
  const gl::RenderTarget& intermediate() const { return horizontal_; }
  const gl::RenderTarget& output() const { return vertical_; }

 private:
  const gl::Program& program(int radius, bool normalAware);

  const FullscreenTriangle& triangle_;
  gl::RenderTarget horizontal_, vertical_;
  std::map<std::pair<int, bool>, gl::Program> programs_;
};

}  // namespace obscura
