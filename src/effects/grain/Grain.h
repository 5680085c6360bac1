#pragma once
// Film grain (shaders_es2/grain/grain.glsl): smooth value noise of cells `size` pixels wide (lib/hash.glsl's hash at
// the cells' corners, blended by smoothstep), a new pattern each frame (the frame index moves the noise by a hash of
// itself), added to the display colour with the weight intensity x (1 - sqrt(luma)): more in the shadows and
// mid-tones than in the highlights (Unity's post-processing stack's luminance response). The noise has mean 0, so it
// changes no brightness on average.
//
// A per-pixel stage (frame/Stage.h) on the display colour, after the grade and the vignette (grain is in the film,
// not in the light the lens lets through), before the dithering. Its pixel is gl_FragCoord, the frame's pixel in
// every pass it fuses into.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "frame/EffectEntry.h"

namespace obscura {

struct GrainSettings : ParameterAccess<GrainSettings> {
  bool enabled = false;
  float intensity = 0.12f;
  float size = 1.5f;  // pixels

  static const std::vector<Parameter<GrainSettings>>& parameters();
  void validate() const { validateParameters("grain"); }
};

// The shader's u_grain for frame `index`, the noise at a pixel (CPU mirror), and the grained display colour.
glm::vec4 grainUniform(const GrainSettings& settings, std::uint64_t frameIndex);
float grainNoise(glm::vec2 p);
glm::vec3 grained(const glm::vec3& srgb, glm::vec2 pixel, const glm::vec4& uniform);

class GrainEffect : public Effect {
 public:
  using Settings = GrainSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs() { return {}; }  // its programs are the fused ones (stages())
  static StageDecl stage();
  static std::vector<StageDecl> stages() { return {stage()}; }

  explicit GrainEffect(const EffectResources& resources) : resources_(resources) {}
  void plan(FramePlanner& planner) override;

 private:
  const EffectResources& resources_;
};

}  // namespace obscura
