#pragma once
// Colour grading's arithmetic (shaders_es2/grading/grading.glsl; CPU mirror here, held together by
// tests/test_grading.cpp): what the grading stage does to a pixel of display colour, after the tone curve.
//
//   1. decode sRGB to display-linear RGB (Rec. 709 primaries, [0, 1]);
//   2. white balance: a von Kries adaptation in CAT02's cone space (CIECAM02, Moroney et al. 2002) from the white of
//      the illuminant the picture is corrected for to D65: M^-1 diag(LMS(D65) / LMS(white)) M, M = CAT02 x sRGB's
//      RGB-to-XYZ, one matrix derived on the CPU. The white: `temperature` in kelvin on the CIE daylight locus (CIE
//      015, the D illuminants) from 4000 K, where 6504 K is D65 itself (the identity), and on the Planckian locus
//      below (Kim et al. 2002's cubic fits), then its CIE y moved by `tint` x 0.0005 (positive: the illuminant
//      greener, the picture corrected towards magenta). A higher temperature makes the picture warmer, as a camera's
//      white-balance setting does;
//   3. ASC CDL (the American Society of Cinematographers' Color Decision List, v1.2): out = max(in slope + offset,
//      0)^power per channel, then its saturation: luma + s (out - luma), luma Rec. 709's;
//   4. contrast: a power about mid grey, 0.18 (c / 0.18)^contrast (a slope of `contrast` in log2 around 0.18);
//   5. clamp to [0, 1] and encode sRGB;
//   6. the 3D LUT (encoding/ColorLut.h: a .cube file, trilinear on its RGBA8 strip), mixed in by `lut-intensity`.
// Each part is skipped where its parameters are neutral (the identity to the byte): the stage's variants
// (GRADING_BALANCE for steps 1 to 5, GRADING_LUT for step 6), chosen by the plan.
//
// A per-pixel stage (frame/Stage.h) on the display colour, the first after the tone curve: it runs inside the
// tone-mapping pass, or inside the lighting where that absorbs the tone curve. The grade works on display-referred
// colour, after the curve, as a colourist grades a finished picture and as .cube files made for video and the web
// expect; the vignette, the grain and the dithering follow it (their order: effects/dither/Dither.h). The LUT's strip
// is a texture this effect owns, uploaded when the LUT changes (prepare), not every frame; a head binds it on a unit
// it has spare (the lighting's tenth, where the context has one: gpu/TextureUnits.h), else the stage runs in a stage
// pass of its own.
#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "encoding/ColorLut.h"
#include "frame/EffectEntry.h"
#include "gl/RenderTarget.h"

namespace obscura {

struct GradingSettings : ParameterAccess<GradingSettings> {
  bool enabled = false;
  float temperature = 6504.0f;  // kelvin: the illuminant corrected for (6504: D65, no change)
  float tint = 0.0f;            // -100 .. 100
  glm::vec3 slope{1.0f}, offset{0.0f}, power{1.0f};  // ASC CDL
  float saturation = 1.0f;
  float contrast = 1.0f;
  std::string lut = "none";                // a .cube file, or none
  std::shared_ptr<const ColorLut> lutData;  // read when the parameter is set (none for "none")
  float lutIntensity = 1.0f;

  static const std::vector<Parameter<GradingSettings>>& parameters();
  void validate() const { validateParameters("grading"); }
};

// The white balance's matrix on display-linear Rec. 709 RGB (the identity at 6504 K and no tint).
glm::mat3 whiteBalanceMatrix(float temperature, float tint);
// diag(slope) x the white balance: the one matrix the stage takes (u_gradingBalance), made once a frame.
glm::mat3 gradingBalance(const GradingSettings& settings);
// Whether steps 1 to 5 change anything (some parameter of theirs is not neutral): the stage's GRADING_BALANCE.
bool gradingBalances(const GradingSettings& settings);
// The CIE 1931 xy chromaticity of the white at `temperature` kelvin (1667 .. 25000).
glm::vec2 whiteChromaticity(float temperature);
// The stage on one display colour (sRGB-encoded, [0, 1]): steps 1 to 6 above.
glm::vec3 gradeDisplay(const glm::vec3& srgb, const GradingSettings& settings);

class GradingEffect : public Effect {
 public:
  using Settings = GradingSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs() { return {}; }  // its programs are the fused ones (stages())
  // Its stage in a variant (steps 1 to 5; the LUT), for `owner`'s LUT texture (none: the shader checks' stages).
  static StageDecl stage(bool balance, bool lut, const GradingEffect* owner = nullptr);
  static std::vector<StageDecl> stages();

  explicit GradingEffect(const EffectResources& resources) : resources_(resources) {}
  void prepare(const FrameSettings& settings) override;  // the LUT's strip, uploaded when the LUT changes
  void plan(FramePlanner& planner) override;

 private:
  const EffectResources& resources_;
  std::shared_ptr<const ColorLut> lutData_;  // the LUT the texture holds
  gl::Texture2D lut_;
  int slicesPerRow_ = 0;
};

}  // namespace obscura
