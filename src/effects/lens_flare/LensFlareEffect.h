#pragma once
// Lens flare (shaders_es2/lens_flare/lens_flare.frag), after John Chapman's "Pseudo Lens Flare" (2013), the
// screen-space method of the lecture decks' lens flare ("all flares lie on the line between the light source and the
// image centre"): light inside a lens reflects between its elements and reaches the sensor again, mirrored through the
// optical axis and scaled.
//
//   input     bloom's bright pass, `bloom-bright` (1/4 of the frame, the light above bloom.threshold, twice
//             downsampled: effects/bloom/BloomEffect.h), so no full-resolution pass is added for it
//   ghosts    the image flipped through its centre, t = 1 - uv, sampled at fract(t + i (0.5 - t) dispersal) for
//             i = 0 .. ghosts - 1, each weighted by (1 - |0.5 - s| / |(0.5, 0.5)|)^10 at its sample s (light far
//             from the axis makes fainter ghosts): ghost i of a light at p lands where that sample is p,
//             uv = 1 - (p - i d / 2) / (1 - i d) (lensFlareGhostPosition)
//   halo      the light at halo-width (in frame heights) from the flipped pixel towards the centre, weighted by
//             (1 - |0.5 - s| / |(0.5, 0.5)|)^5: a ring of that radius round the centre for a light near it
//   dispersion  red sampled `distortion` (frame heights) nearer the centre than green, blue as far beyond it
//   dirt      optional: the flare times a lens-dirt image (a built-in one, or a PNG), as Chapman's composite does
// The result (RGB9E5, 1/4 of the frame) is the frame's `lens-light`, which the glare adds its streaks to and the tone
// mapping adds, upsampled, to the HDR colour before the exposure: no full-resolution pass of its own.
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "frame/EffectEntry.h"
#include "gl/RenderTarget.h"
#include "scene/Scene.h"

namespace obscura {

struct LensFlareSettings : ParameterAccess<LensFlareSettings> {
  bool enabled = false;
  float intensity = 0.05f;  // the flare's light per unit of bright light
  int ghosts = 5;           // Chapman's 4 .. 8
  float dispersal = 0.35f;  // Chapman's 0.3 .. 0.4
  float haloWidth = 0.4f;   // frame heights
  float distortion = 0.01f; // frame heights
  std::string dirt = "none";
  std::shared_ptr<const Image> dirtImage;  // a file's, read when the parameter is set (none for "none", "builtin")

  static const std::vector<Parameter<LensFlareSettings>>& parameters();
  void validate() const { validateParameters("lens flare"); }
};

// CPU mirror of the shader's geometry (uv: 0 .. 1 across the frame, y up).
// The source ghost i samples for the output pixel at uv.
glm::vec2 lensFlareGhostSample(glm::vec2 uv, int ghost, float dispersal);
// Where ghost i of a light at `source` lands (the output uv whose sample is `source`, before the wrap); ghost 0 is
// the light mirrored through the centre.
glm::vec2 lensFlareGhostPosition(glm::vec2 source, int ghost, float dispersal);
// Chapman's falloff at a sample: (1 - |0.5 - s| / |(0.5, 0.5)|)^power.
float lensFlareFalloff(glm::vec2 sample, float power);
// The flare at uv from a bright image (w x h linear colours, rows bottom to top), as the shader computes it.
glm::vec3 lensFlareAt(glm::vec2 uv, const std::vector<glm::vec3>& bright, glm::ivec2 size, float aspect,
                      const LensFlareSettings& settings);
// The built-in lens dirt: soft smudges and specks over a dim base, made the same on every run.
Image builtinLensDirt(int side = 256);

class LensFlareEffect : public Effect {
 public:
  using Settings = LensFlareSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit LensFlareEffect(const EffectResources& resources) : resources_(resources) {}
  void prepare(const FrameSettings& settings) override;  // the lens dirt's image
  void plan(FramePlanner& planner) override;

 private:
  struct Variant {
    gl::Program program;
    GLint bright = -1, brightSize = -1, ghosts = -1, dispersal = -1, haloWidth = -1, aspect = -1, distortion = -1,
          intensity = -1, dirt = -1;
  };
  const Variant& variant(bool dirt);
  const gl::Texture2D* dirtTexture(const LensFlareSettings& settings);

  const EffectResources& resources_;
  std::unique_ptr<Variant> variants_[2];
  std::string dirtName_;
  std::shared_ptr<const Image> dirtImage_;
  gl::Texture2D dirt_;
};

}  // namespace obscura
