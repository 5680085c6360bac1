#pragma once
// FXAA 3.11, quality path (Lottes 2011; shaders_es2/fxaa.frag): the frame's antialiasing, last in the chain. It
// reads "display-color" (sRGB, luma in alpha; NEAREST, filtered by hand where FXAA reads between texels) and writes
// it again, straight into the output framebuffer when it is the frame's result.
//
// Why FXAA and not multisampling: WebGL 1 cannot resolve a multisampled buffer into a texture, and every frame reads
// the lit image again (the tone-mapping pass decodes its HDR encoding), so Obscura draws no geometry into the back
// buffer, where multisampling would act. Canvas and window are made without it (measured: docs/benchmarks.md).
#include <map>
#include <vector>

#include "core/EffectTable.h"

namespace obscura {

struct FxaaSettings : ParameterAccess<FxaaSettings> {
  bool enabled = true;
  QualityPreset preset = QualityPreset::Medium;
  int quality = 12;              // Lottes' FXAA_QUALITY__PRESET: 10 .. 15, 20 .. 29 or 39 (the search's steps)
  float subpix = 0.75f;          // Lottes' default: amount of subpixel aliasing removal
  float edgeThreshold = 0.166f;  // Lottes' default: minimum local contrast to process, relative to the max luma
  float edgeThresholdMin = 0.0833f;  // Lottes' default: skip darks below this absolute contrast

  static const std::vector<Parameter<FxaaSettings>>& parameters();
  void applyPreset(QualityPreset which);
  bool matchesPreset(QualityPreset which) const;
  void validate() const { validateParameters("FXAA"); }
};

// The search's step lengths of one of Lottes' quality presets (FXAA_QUALITY__P0 ..), in pixels.
const std::vector<float>& fxaaSearchSteps(int quality);

class FxaaEffect : public Effect {
 public:
  using Settings = FxaaSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit FxaaEffect(const EffectResources& resources) : resources_(resources) {}
  void plan(FramePlanner& planner) override;

 private:
  struct Variant {
    Variant(gl::Program built, int quality);
    gl::Program program;
    GLint color, size, texel, subpix, edgeThreshold, edgeThresholdMin;
  };
  const Variant& variant(int quality);

  const EffectResources& resources_;
  std::map<int, Variant> variants_;
};

}  // namespace obscura
