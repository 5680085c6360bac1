#pragma once
// Glare streaks, the star effect (shaders_es2/glare/glare.frag): Masaki Kawase's streak filter ("Frame Buffer
// Postprocessing Effects in DOUBLE-S.T.E.A.L (Wreckless)", GDC 2003; the lecture decks' glare: "filter in u and v
// separately"), on bloom's bright pass at 1/4 of the frame (`bloom-bright`: effects/bloom/BloomEffect.h).
//
// A star of 4 or 6 streaks is 4 or 6 rays from every bright pixel, at `angle` and every 360 / streaks degrees from
// it. Each ray is filtered in three passes: pass n (0, 1, 2) takes 4 taps at s 4^n steps (s = 0 .. 3) along the
// ray, tap s weighing a^(s 4^n) with a = e^(-1 / L), normalised to 1. The passes compose: the offsets sum(s_n 4^n)
// are the numbers 0 .. 63 written in base 4, each once, so the ray's weights are exactly a^D / sum(a^D) for
// D = 0 .. 63, and one pass with taps 4^n apart does the work of 4^n taps: 63 steps for 12 fetches a pixel. (A
// symmetric filter would do both rays of a line at once, but signed digits reach some offsets twice and the streak
// gets bumps at multiples of 4: measured in tests/test_lens_flare.cpp.) A step is 1/320 of the frame's width, so a
// streak covers the same part of any frame; L = length x 320 steps.
//
// The last pass of each ray scales it by the intensity and adds what is gathered so far (the rays before, and the
// lens flare's `lens-light`, if it ran); the last ray's is the frame's `lens-light`, which the tone mapping adds. Each
// pass's filter sums to 1, so each streak carries `intensity` times the bright light.
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "frame/EffectEntry.h"

namespace obscura {

struct GlareSettings : ParameterAccess<GlareSettings> {
  bool enabled = false;
  int streaks = 4;          // 4 or 6
  float length = 0.05f;     // the distance at which a streak falls to 1/e, as a fraction of the frame's width
  float intensity = 0.05f;  // per streak, per unit of the bright light
  float angle = 0.0f;       // degrees, of the first streak from the frame's x axis (counter-clockwise)

  static const std::vector<Parameter<GlareSettings>>& parameters();
  void validate() const;
};

// CPU mirror: the taps' weights of pass n (at 0, 1, 2, 3 steps of 4^n), and each ray's direction (a unit vector in
// pixels, y up, from a pixel towards the light that streaks onto it).
constexpr int kGlarePasses = 3;
constexpr float kGlareStepsPerWidth = 320.0f;
glm::vec4 glareWeights(int pass, float length);
std::vector<glm::vec2> glareRays(const GlareSettings& settings);

class GlareEffect : public Effect {
 public:
  using Settings = GlareSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit GlareEffect(const EffectResources&) {}
  void plan(FramePlanner& planner) override;

 private:
  // The streaks' draws (spec(false) for each ray's first passes, spec(true) for its last, which adds the sum).
  static void render(const PassContext& context, const GlareSettings& settings, bool flare);
};

}  // namespace obscura
