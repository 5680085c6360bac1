#pragma once
// Tone mapping: the lit HDR colour ("scene-color") decoded (lib/hdr.glsl), multiplied by the exposure 2^EV, mapped
// to display values by a curve (lib/tonemap.glsl: ACES fitted, Khronos PBR Neutral, AgX, Reinhard), and encoded sRGB
// into "display-color", with the luma FXAA wants in alpha. CPU mirror: encoding/ToneMapping.h.
//
// A per-pixel stage (frame/Stage.h, shaders_es2/tonemap/tonemap.glsl): it runs inside the lighting's pass (or the
// fog's) where nothing else reads the HDR colour in between, and as a pass of its own after TAA or bloom. It always
// runs: it is what turns the HDR encoding into displayable colour. Switched off ("tonemap off"), it applies neither
// the exposure nor a curve: colour is clamped to [0, 1] and encoded sRGB.
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
// 2^0), wherever the stage runs.
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
  static std::vector<ProgramSpec> programSpecs() { return {}; }  // its programs are the fused ones (stages())
  // Its stage for a curve, and every curve's, for the shader checks.
  static StageDecl stage(ToneMapOperator op, bool autoExposure = false, bool lensLight = false);
  static std::vector<StageDecl> stages();

  explicit TonemapEffect(const EffectResources& resources) : resources_(resources) {}
  void plan(FramePlanner& planner) override;

 private:
  const EffectResources& resources_;
};

}  // namespace obscura
