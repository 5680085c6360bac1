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
#include <map>
#include <tuple>

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
  struct CameraProgram {
    gl::Program program;
    ReconstructionUniforms reconstruction;
    GLint gbuffer = -1, unjitteredProjection = -1, viewToPreviousClip = -1;
  };
  struct GeometryVariant {
    explicit GeometryVariant(gl::Program built);
    gl::Program program;
    GeometryUniforms geometry;
    GLint projection = -1, unjitteredProjection = -1, previousViewProjection = -1;
  };
  void render(const PassContext& context);
  const GeometryVariant& variant(MaterialKind material, VertexKind vertex);

  const EffectResources& resources_;
  CameraProgram camera_;
  std::map<std::tuple<MaterialKind, VertexKind>, GeometryVariant> variants_;
};

}  // namespace obscura
