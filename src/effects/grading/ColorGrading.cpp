#include "effects/grading/ColorGrading.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "encoding/ColorSpaces.h"
#include "encoding/ToneMapping.h"
#include "frame/PassContext.h"
#include "frame/Stage.h"

namespace obscura {
namespace {

constexpr float kReferenceTemperature = 6504.0f;  // D65 on the daylight locus
constexpr float kTintScale = 0.0005f;             // CIE y per unit of tint

// CAT02 (CIECAM02's chromatic adaptation transform), XYZ to sharpened cone space, as rows.
glm::dmat3 cat02() {
  return glm::transpose(glm::dmat3(0.7328, 0.4296, -0.1624, -0.7036, 1.6975, 0.0061, 0.0030, 0.0136, 0.9834));
}

glm::dvec3 xyzOf(glm::dvec2 xy) { return {xy.x / xy.y, 1.0, (1.0 - xy.x - xy.y) / xy.y}; }

// The ASC CDL's luma weights are Rec. 709's.
float luma709(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

std::shared_ptr<const ColorLut> readLut(const std::string& name) {
  if (name == "none") return nullptr;
  return std::make_shared<const ColorLut>(readCubeLut(name));
}

}  // namespace

const std::vector<Parameter<GradingSettings>>& GradingSettings::parameters() {
  using S = GradingSettings;
  static const std::vector<Parameter<S>> table = [] {
    Parameter<S> lutParameter = textParameter<S>("lut", "none | a .cube file",
                                        "a 3D LUT (Adobe / Resolve .cube) applied to the display colour", &S::lut,
                                        {"none"});
    // The file is read now: a malformed one is refused with its line, and the grade in use stays.
    lutParameter.set = [](S& s, const std::string& v) {
      if (v.empty()) throw InputError("lut: expected none or a .cube file, got nothing");
      std::shared_ptr<const ColorLut> data = readLut(v);
      s.lut = v;
      s.lutData = std::move(data);
    };
    return std::vector<Parameter<S>>{
        switchParameter<S>("grading", "colour grading on or off (white balance, ASC CDL, saturation, contrast, a "
                           ".cube LUT; on the display colour)",
                           &S::enabled)
            .primary(),
        std::move(lutParameter).primary(),
        numberParameter<S>("lut-intensity", 0, 1, "", "how much of the LUT's result is mixed in", &S::lutIntensity)
            .primary(),
        numberParameter<S>("temperature", 1667, 25000, "K",
                           "white balance: the light's colour temperature corrected for (6504: none; higher: warmer)",
                           &S::temperature)
            .primary()
            .shapesPlan(),  // neutral or not: the stage's variant (gradingBalances), as each of steps 1 to 5's
        numberParameter<S>("tint", -100, 100, "", "white balance: positive towards magenta, negative towards green",
                           &S::tint)
            .primary()
            .shapesPlan(),
        numberParameter<S>("saturation", 0, 4, "", "ASC CDL saturation (0: grey, 1: none)", &S::saturation)
            .primary()
            .shapesPlan(),
        numberParameter<S>("contrast", 0.25, 4, "", "a power about mid grey (1: none)", &S::contrast)
            .primary()
            .shapesPlan(),
        colorParameter<S>("slope", 0, 16, "ASC CDL slope per channel", &S::slope).shapesPlan(),
        colorParameter<S>("offset", -1, 1, "ASC CDL offset per channel", &S::offset).shapesPlan(),
        colorParameter<S>("power", 0.1, 10, "ASC CDL power per channel", &S::power).shapesPlan()};
  }();
  return table;
}

glm::vec2 whiteChromaticity(float temperature) {
  const double t = std::clamp(static_cast<double>(temperature), 1667.0, 25000.0);
  const double t2 = t * t, t3 = t2 * t;
  double x = 0.0, y = 0.0;
  if (t >= 4000.0) {
    // CIE 015:2018 eq. 4.7 / 4.8: the daylight locus (the D illuminants; D65 at 6504 K).
    x = t <= 7000.0 ? -4.6070e9 / t3 + 2.9678e6 / t2 + 0.09911e3 / t + 0.244063
                    : -2.0064e9 / t3 + 1.9018e6 / t2 + 0.24748e3 / t + 0.237040;
    y = -3.0 * x * x + 2.870 * x - 0.275;
  } else {
    // Kim et al. 2002 (US patent 7,024,034): cubic fits of the Planckian locus.
    x = -0.2661239e9 / t3 - 0.2343589e6 / t2 + 0.8776956e3 / t + 0.179910;
    y = t <= 2222.0 ? -1.1063814 * x * x * x - 1.34811020 * x * x + 2.18555832 * x - 0.20219683
                    : -0.9549476 * x * x * x - 1.37418593 * x * x + 2.09137015 * x - 0.16748867;
  }
  return {static_cast<float>(x), static_cast<float>(y)};
}

glm::mat3 whiteBalanceMatrix(float temperature, float tint) {
  const glm::dmat3 toLms = cat02() * ColorSpaces::rgbToXyz(ColorSpaces::kBt709);
  glm::dvec2 white(whiteChromaticity(temperature));
  white.y += static_cast<double>(tint * kTintScale);
  // The reference white is the same formula's at 6504 K, so the neutral setting is the identity.
  const glm::dvec3 from = cat02() * xyzOf(glm::dvec2(whiteChromaticity(kReferenceTemperature)));
  const glm::dvec3 to = cat02() * xyzOf(white);
  glm::dmat3 scale(1.0);
  for (int i = 0; i < 3; ++i) scale[i][i] = from[i] / to[i];
  return glm::mat3(glm::inverse(toLms) * scale * toLms);
}

glm::mat3 gradingBalance(const GradingSettings& s) {
  glm::mat3 slope(1.0f);
  for (int i = 0; i < 3; ++i) slope[i][i] = s.slope[i];
  return slope * whiteBalanceMatrix(s.temperature, s.tint);
}

bool gradingBalances(const GradingSettings& s) {
  return s.temperature != 6504.0f || s.tint != 0.0f || s.slope != glm::vec3(1.0f) || s.offset != glm::vec3(0.0f) ||
         s.power != glm::vec3(1.0f) || s.saturation != 1.0f || s.contrast != 1.0f;
}

glm::vec3 gradeDisplay(const glm::vec3& srgb, const GradingSettings& s) {
  glm::vec3 c = glm::pow(glm::max(gradingBalance(s) * srgbToLinear(srgb) + s.offset, glm::vec3(0.0f)), s.power);
  const float luma = luma709(c);
  c = glm::vec3(luma) + s.saturation * (c - glm::vec3(luma));
  c = 0.18f * glm::pow(glm::max(c, glm::vec3(0.0f)) / 0.18f, glm::vec3(s.contrast));
  glm::vec3 out = linearToSrgb(glm::clamp(c, 0.0f, 1.0f));
  if (s.lutData) out = glm::mix(out, s.lutData->apply(out), s.lutIntensity);
  return out;
}

EffectInfo GradingEffect::info() { return {"grading", "Colour grading", true, false, {"grading"}, {}}; }

StageDecl GradingEffect::stage(bool balance, bool lut, const GradingEffect* owner) {
  // The balance: the matrix's three rows, the offset's and the power's, and one for the saturation and contrast;
  // the LUT: its layout's row, the domain's two vec3 rows, whose spare column takes the intensity.
  StageDecl stage = displayStage("grading", (balance ? 6 : 0) + (lut ? 3 : 0));
  stage.variant = std::string(balance ? "balance" : "") + (balance && lut ? "," : "") + (lut ? "lut" : "");
  stage.defines = {{"GRADING_BALANCE", balance ? "1" : "0"}, {"GRADING_LUT", lut ? "1" : "0"}};
  if (lut) {
    stage.ownTextures.push_back({"u_gradingLut", [owner]() -> GLuint { return owner ? owner->lut_.id() : 0; }});
  }
  stage.uniforms = [balance, lut, owner](const gl::Program& program, const PassContext& context) {
    const GradingSettings& s = context.settings().of<GradingSettings>();
    if (balance) {
      program.set("u_gradingBalance", gradingBalance(s));  // once a frame, not per pixel
      program.set("u_gradingOffset", s.offset);
      program.set("u_gradingPower", s.power);
      program.set("u_gradingSaturationContrast", glm::vec2(s.saturation, s.contrast));
    }
    if (lut && owner && owner->lutData_) {
      const ColorLut& data = *owner->lutData_;
      program.set("u_gradingLutLayout",
                  glm::vec4(static_cast<float>(data.size), static_cast<float>(owner->slicesPerRow_),
                            static_cast<float>(owner->lut_.width()), static_cast<float>(owner->lut_.height())));
      program.set("u_gradingLutDomainMin", data.domainMin);
      program.set("u_gradingLutDomainScale", 1.0f / (data.domainMax - data.domainMin));
      program.set("u_gradingLutIntensity", s.lutIntensity);
    }
  };
  return stage;
}

std::vector<StageDecl> GradingEffect::stages() {
  return {stage(true, false), stage(false, true), stage(true, true)};
}

void GradingEffect::prepare(const FrameSettings& settings) {
  // The strip is uploaded when the LUT changes, whether grading is on or not (a LUT set while it is off is ready when
  // it is switched on), and kept until then.
  const GradingSettings& s = settings.of<GradingSettings>();
  if (s.lutData == lutData_) return;
  lutData_ = s.lutData;
  if (!lutData_) {
    lut_ = gl::Texture2D();
    return;
  }
  const LutStrip strip = lutStrip(*lutData_, resources_.caps.maxTextureSize);
  lut_ = gl::Texture2D(strip.width, strip.height, GL_LINEAR, strip.rgba.data());
  slicesPerRow_ = strip.slicesPerRow;
}

void GradingEffect::plan(FramePlanner& planner) {
  // A per-pixel stage on the display colour, after the tone curve: inside the tone-mapping pass (or the lighting).
  // A grade with neither part does nothing and plans nothing.
  const GradingSettings& s = planner.settings().of<GradingSettings>();
  const bool balance = gradingBalances(s), lut = s.lutData != nullptr;
  if (!s.enabled || (!balance && !lut)) return;
  planner.add(stagePass(resources_, stage(balance, lut, this), "display-color"));
}

}  // namespace obscura
