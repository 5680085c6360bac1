#pragma once
// Motion vectors: the "velocity" target, each pixel's screen-space motion since the previous frame (uv units, 16 bits
// per component: encoding/VelocityPacking.h), from the camera and every transform (node animation, skinning, morph
// targets), for motion blur and temporal antialiasing. No switch: the pass runs when a later pass or the debug view
// `velocity` reads the target.
//
// One pass, in two draws into the target, with the G-buffer's depth attached (shaders_es2/velocity/velocity.frag):
//   1. full screen: the motion the camera alone gives each pixel, reconstructed from the G-buffer's depth (no
//      geometry drawn): what a still scene needs;
//   2. the instances whose pose changed since the previous frame (GpuScene::DrawOptions::onlyMoving) drawn with
//      geometry.vert's PREVIOUS variant, depth-tested against the G-buffer (GL_LEQUAL, no depth writes: the same
//      invariant positions), so only their visible fragments overwrite the camera's motion.
// RendererOptions::velocityDrawsEverything draws every instance in step 2 instead: the measured alternative
// (docs/benchmarks.md, section 7), and the check that both give the same vectors.

#include <utility>

#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"
#include "gpu/GpuScene.h"

namespace obscura {

class VelocityEffect : public Effect {
 public:
  using Settings = NoSettings;
  static constexpr bool kHasSwitch = false;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit VelocityEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;

 private:
  void render(const PassContext& context);

  const EffectResources& resources_;
  ProgramVariants<std::pair<MaterialKind, VertexKind>> geometry_;  // the moving instances' programs
};

}  // namespace obscura
