#pragma once
// Chromatic aberration (shaders_es2/chromatic_aberration/chromatic_aberration.frag): lateral colour fringes, red
// further out and blue further in than green, in proportion to the distance from the image's centre: the red image
// is the green one magnified by 1 + k, the blue one by 1 - k, k = `intensity` (read at 1/2 + (uv - 1/2) / (1 + k)
// and / (1 - k)); at a pixel d from the centre red and blue lie about k d from green.
//
// A pass of its own, on the display colour before FXAA: unlike the per-pixel stages (grading, vignette, grain,
// dithering), it reads its neighbours, up to k x the half-diagonal away, and a fused program has no neighbours of its
// input to read (the lighting computes its colour per pixel). It is the one effect of the camera's finish that adds a
// full-screen pass, and only while it is on (docs/camera-finish.md).
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "frame/EffectEntry.h"

namespace obscura {

struct ChromaticAberrationSettings : ParameterAccess<ChromaticAberrationSettings> {
  bool enabled = false;
  float intensity = 0.006f;

  static const std::vector<Parameter<ChromaticAberrationSettings>>& parameters();
  void validate() const { validateParameters("chromatic aberration"); }
};

// CPU mirror: where red (channel 0) and blue (2) are read for the pixel at uv, and the shader's u_shift.
glm::vec2 aberrationSource(glm::vec2 uv, int channel, float intensity);
glm::vec2 aberrationScales(float intensity);

class ChromaticAberrationEffect : public Effect {
 public:
  using Settings = ChromaticAberrationSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit ChromaticAberrationEffect(const EffectResources&) {}
  void plan(FramePlanner& planner) override;
};

}  // namespace obscura
