#pragma once
// Tone mapping: the lit HDR colour ("scene-color") decoded (lib/hdr.glsl), multiplied by the exposure 2^EV, mapped
// to display values by a curve (lib/tonemap.glsl: ACES fitted, Khronos PBR Neutral, AgX, Reinhard), and encoded sRGB
// into "display-color", with the luma FXAA wants in alpha. CPU mirror: encoding/ToneMapping.h.
//
// The pass always runs: it is what turns the HDR encoding into displayable colour. Switched off ("tonemap off"),
// it applies neither the exposure nor a curve: colour is clamped to [0, 1] and encoded sRGB.
#include <map>
#include <tuple>
#include <vector>

#include "encoding/ToneMapping.h"
#include "frame/EffectEntry.h"

namespace obscura {

struct TonemapSettings : ParameterAccess<TonemapSettings> {
  bool enabled = true;
  float exposure = 0.0f;  // EV: the HDR colour is multiplied by 2^exposure
  // Khronos PBR Neutral by default: it keeps base colours as authored (up to its 0.04 offset) and compresses only
  // highlights, what glTF viewers aim for (Khronos' own Sample Viewer and model-viewer offer it for this reason).
  ToneMapOperator op = ToneMapOperator::Neutral;

  static const std::vector<Parameter<TonemapSettings>>& parameters();
  void validate() const { validateParameters("tone mapping"); }
};

// The tone mapping a frame applies: its curve and exposure multiplier, with "off" meaning neither (the linear curve,
// 2^0). The tone-mapping pass applies it, and so does the lighting pass where it takes that pass's place
// (LightingEffect.h).
struct ToneMapInUse {
  ToneMapOperator op = ToneMapOperator::Linear;
  float exposureScale = 1.0f;
  static ToneMapInUse of(const TonemapSettings& settings);
  // A linear HDR colour as the pass writes it: sRGB display colour, and luma in alpha (or 1, for the output).
  glm::vec4 displayColor(const glm::vec3& linearHdr, bool lumaInAlpha) const;
};

class TonemapEffect : public Effect {
 public:
  using Settings = TonemapSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit TonemapEffect(const EffectResources& resources) : resources_(resources) {}
  void plan(FramePlanner& planner) override;

 private:
  struct Variant {
    Variant(gl::Program built, bool autoExposure, bool addsLensLight);
    gl::Program program;
    GLint color, exposure, lumaInAlpha, exposureTarget, lensLight, lensLightSize;
  };
  const Variant& variant(ToneMapOperator op, bool autoExposure, bool lensLight);

  const EffectResources& resources_;
  std::map<std::tuple<ToneMapOperator, bool, bool>, Variant> variants_;
};

}  // namespace obscura
