#pragma once
// The G-buffer: the scene drawn once into one RGBA8 target (RG octahedral view-space normal, BA 16-bit linear depth;
// shaders_es2/gbuffer.frag) with its own depth renderbuffer, which the lighting pass then shares. Cleared to depth
// code 65535, the background marker. Always part of the frame; the plan drops it when no running pass reads it
// (the AO off: the lighting then depth-tests on its own).
#include <vector>

#include "core/EffectTable.h"
#include "core/GpuScene.h"

namespace obscura {

class GBufferEffect : public Effect {
 public:
  using Settings = NoSettings;
  static constexpr bool kHasSwitch = false;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit GBufferEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;

 private:
  void render(const PassContext& context) const;

  gl::Program program_;
  GeometryUniforms geometry_;
  GLint projection_ = -1, near_ = -1, depthRange_ = -1;
};

}  // namespace obscura
