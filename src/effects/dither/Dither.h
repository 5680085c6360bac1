#pragma once
// Dithering before 8-bit quantisation (shaders_es2/dither/dither.glsl), on by default. A smooth gradient darker than a
// few codes per hundred pixels (a dim sky, a fog ramp) quantises into visible bands; noise added before the
// quantisation turns them into grain that the eye averages. Triangular noise (the sum of two uniform ones, minus 1)
// of one 8-bit step's amplitude is the least that makes the quantisation error's mean and variance independent of the
// signal (Lipshitz, Wannamaker and Vanderkooy 1992, "Quantization and dither: a theoretical survey"), the dither
// Filament's and Babylon's post-processing add; the same noise on the three channels keeps it grey. Within a step of
// black or white its amplitude shrinks to the distance (none at 0 and 1): the target would clamp noise beyond them,
// which moves the mean (an eighth of a step at black) and puts specks on black and white. The pattern is
// the pixel's alone, the same in every frame: a frame is the same bytes however often it is drawn (a still view, a
// screenshot, the tests that hold two frames equal byte for byte), and at one step the noise is below what the eye
// sees whether or not it moves (Filament and Babylon move theirs; the film grain, which is meant to be seen, moves).
//
// A per-pixel stage (frame/Stage.h) on the display colour, the last of the chain that turns the HDR colour into the
// 8-bit display target: it must see the colour the target will quantise, after everything else the chain does to it.
// The order of the display stages: grading first (it grades the display-referred picture the tone curve made, and a
// LUT expects that picture), then the vignette (light the lens loses, on the graded picture), the grain (in the film),
// and the dithering last, right before the quantisation it is there for. Its pixel is gl_FragCoord.
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "frame/EffectEntry.h"

namespace obscura {

struct DitherSettings : ParameterAccess<DitherSettings> {
  bool enabled = true;

  static const std::vector<Parameter<DitherSettings>>& parameters();
  void validate() const { validateParameters("dither"); }
};

// The offset added at a pixel (its gl_FragCoord; CPU mirror): in (-1, 1) / 255, and the dithered display colour.
float ditherOffset(glm::vec2 pixel);
glm::vec3 dithered(const glm::vec3& srgb, glm::vec2 pixel);

class DitherEffect : public Effect {
 public:
  using Settings = DitherSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs() { return {}; }  // its programs are the fused ones (stages())
  static StageDecl stage();
  static std::vector<StageDecl> stages() { return {stage()}; }

  explicit DitherEffect(const EffectResources& resources) : resources_(resources) {}
  void plan(FramePlanner& planner) override;

 private:
  const EffectResources& resources_;
};

}  // namespace obscura
