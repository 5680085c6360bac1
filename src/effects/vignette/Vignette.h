#pragma once
// The vignette (shaders_es2/vignette/vignette.glsl): the picture darkened towards the frame's edges, as a lens's light
// falls off towards the edge of its field, after Unity's post-processing stack (v2, the "classic" vignette):
// d = 3 intensity |uv - 1/2|, its x scaled by the aspect ratio as far as `roundness` asks (1: a circle on screen, 0:
// the frame's own shape), factor = (1 - d.d)^(5 smoothness), clamped to [0, 1].
//
// A per-pixel stage (frame/Stage.h) on the display colour, after the grade: the factor multiplies display-referred
// light (the sRGB colour decoded, multiplied, encoded again), so a LUT graded on the unvignetted picture sees the
// picture it was made for, and the darkening is a fraction of what the viewer sees whatever the tone curve did.
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "frame/EffectEntry.h"

namespace obscura {

struct VignetteSettings : ParameterAccess<VignetteSettings> {
  bool enabled = false;
  float intensity = 0.35f;
  float smoothness = 0.25f;
  float roundness = 1.0f;

  static const std::vector<Parameter<VignetteSettings>>& parameters();
  void validate() const { validateParameters("vignette"); }
};

// The shader's u_vignetteShape for a frame of `aspect` (width / height), and the factor at uv (CPU mirror).
glm::vec3 vignetteShape(const VignetteSettings& settings, float aspect);
float vignetteFactor(glm::vec2 uv, const glm::vec3& shape);
// The stage on one display colour (sRGB-encoded) at uv (CPU mirror).
glm::vec3 vignetted(const glm::vec3& srgb, glm::vec2 uv, const glm::vec3& shape);

class VignetteEffect : public Effect {
 public:
  using Settings = VignetteSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs() { return {}; }  // its programs are the fused ones (stages())
  static StageDecl stage();
  static std::vector<StageDecl> stages() { return {stage()}; }

  explicit VignetteEffect(const EffectResources& resources) : resources_(resources) {}
  void plan(FramePlanner& planner) override;

 private:
  const EffectResources& resources_;
};

}  // namespace obscura
