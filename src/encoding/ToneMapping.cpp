#include "encoding/ToneMapping.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/matrix.hpp>

#include "base/Error.h"
#include "encoding/ColorSpaces.h"

namespace obscura {
namespace {

// HLSL prints matrices by rows and applies them as mul(M, v); glm's constructors take columns.
glm::mat3 fromRows(float a, float b, float c, float d, float e, float f, float g, float h, float i) {
  return glm::transpose(glm::mat3(a, b, c, d, e, f, g, h, i));
}

// Filament's nine-number mat3f constructor takes columns, like glm's (libs/math/include/math/mat3.h): these are the
// columns as printed in filament/src/ToneMapper.cpp. Both preserve grey (each row sums to 1).
constexpr glm::dmat3 kAgxInset(0.856627153315983, 0.137318972929847, 0.11189821299995,      //
                               0.0951212405381588, 0.761241990602591, 0.0767994186031903,  //
                               0.0482516061458583, 0.101439036467562, 0.811302368396859);
constexpr glm::dmat3 kAgxOutsetInverse(0.899796955911611, 0.11142098895748, 0.11142098895748,      //
                                       0.0871996192028351, 0.875575586156966, 0.0871996192028349,  //
                                       0.013003424885555, 0.0130034248855548, 0.801379391839686);

float clamp01(float v) { return std::min(std::max(v, 0.0f), 1.0f); }

}  // namespace

const char* toneMapOperatorName(ToneMapOperator op) {
  switch (op) {
    case ToneMapOperator::Linear: return "linear";
    case ToneMapOperator::Reinhard: return "reinhard";
    case ToneMapOperator::AcesFitted: return "aces";
    case ToneMapOperator::Neutral: return "neutral";
    case ToneMapOperator::AgX: return "agx";
  }
  return "?";
}

ToneMapOperator parseToneMapOperator(std::string_view name) {
  for (ToneMapOperator op : kToneMapOperators)
    if (name == toneMapOperatorName(op)) return op;
  throw InputError("unknown tone-mapping operator '" + std::string(name) +
                   "' (expected linear, reinhard, aces, neutral or agx)");
}

std::pair<std::string, std::string> toneMapShaderDefine(ToneMapOperator op) {
  return {"TONEMAP_OPERATOR", std::to_string(static_cast<int>(op))};
}

float exposureScale(float ev) { return std::exp2(ev); }

glm::mat3 acesInputMatrix() {
  // BakingLab ACES.hlsl: "sRGB => XYZ => D65_2_D60 => AP1 => RRT_SAT".
  return fromRows(0.59719f, 0.35458f, 0.04823f,  //
                  0.07600f, 0.90834f, 0.01566f,  //
                  0.02840f, 0.13383f, 0.83777f);
}

glm::mat3 acesOutputMatrix() {
  // BakingLab ACES.hlsl: "ODT_SAT => XYZ => D60_2_D65 => sRGB".
  return fromRows(1.60475f, -0.53108f, -0.07367f,  //
                  -0.10208f, 1.10813f, -0.00605f,  //
                  -0.00327f, -0.07276f, 1.07602f);
}

const AgxMatrices& agxMatrices() {
  static const AgxMatrices matrices = [] {
    const glm::dmat3 toRec2020 = ColorSpaces::srgbToRec2020();
    AgxMatrices m;
    m.input = glm::mat3(kAgxInset * toRec2020);
    m.outset = glm::mat3(glm::inverse(kAgxOutsetInverse));
    m.rec2020ToSrgb = glm::mat3(glm::inverse(toRec2020));
    return m;
  }();
  return matrices;
}

std::vector<GlslConstant> toneMapShaderConstants() {
  const AgxMatrices& agxM = agxMatrices();
  return {glslMat3("ACES_INPUT", acesInputMatrix()),
          glslMat3("ACES_OUTPUT", acesOutputMatrix()),
          glslFloat("ACES_EXPOSURE_GAIN", kAcesExposureGain),
          glslMat3("AGX_INPUT", agxM.input),
          glslMat3("AGX_OUTSET", agxM.outset),
          glslMat3("AGX_REC2020_TO_SRGB", agxM.rec2020ToSrgb),
          glslFloat("AGX_MIN_EV", kAgxMinEv),
          glslFloat("AGX_MAX_EV", kAgxMaxEv)};
}

// The operations below are written in the shader's order, in float, so that the CPU rounds where the GPU does.

glm::vec3 reinhard(const glm::vec3& x) { return x / (1.0f + x); }

glm::vec3 acesFitted(const glm::vec3& x) {
  glm::vec3 v = acesInputMatrix() * x;
  // RRTAndODTFit (BakingLab ACES.hlsl).
  const glm::vec3 a = v * (v + 0.0245786f) - 0.000090537f;
  const glm::vec3 b = v * (0.983729f * v + 0.4329510f) + 0.238081f;
  v = a / b;
  return glm::clamp(acesOutputMatrix() * v, 0.0f, 1.0f);
}

glm::vec3 pbrNeutral(const glm::vec3& input) {
  const float startCompression = 0.8f - 0.04f;
  const float desaturation = 0.15f;
  glm::vec3 color = input;
  const float x = std::min(color.r, std::min(color.g, color.b));
  const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
  color -= offset;
  const float peak = std::max(color.r, std::max(color.g, color.b));
  if (peak < startCompression) return color;
  const float d = 1.0f - startCompression;
  const float newPeak = 1.0f - d * d / (peak + d - startCompression);
  color *= newPeak / peak;
  const float g = 1.0f - 1.0f / (desaturation * (peak - newPeak) + 1.0f);
  return glm::mix(color, glm::vec3(newPeak), g);
}

float agxContrast(float x) {
  // iolite-engine.com "minimal AgX implementation", 6th order (three.js agxDefaultContrastApprox).
  const float x2 = x * x;
  const float x4 = x2 * x2;
  return 15.5f * x4 * x2 - 40.14f * x4 * x + 31.96f * x4 - 6.868f * x2 * x + 0.4298f * x2 + 0.1191f * x - 0.00232f;
}

glm::vec3 agx(const glm::vec3& x) {
  const AgxMatrices& m = agxMatrices();
  glm::vec3 c = m.input * x;
  c = glm::max(c, glm::vec3(1e-10f));  // log2 of 0 or of a negative number is undefined
  c = glm::log2(c);
  c = (c - kAgxMinEv) / (kAgxMaxEv - kAgxMinEv);
  c = glm::clamp(c, 0.0f, 1.0f);
  c = glm::vec3(agxContrast(c.r), agxContrast(c.g), agxContrast(c.b));
  c = m.outset * c;
  c = glm::pow(glm::max(c, glm::vec3(0.0f)), glm::vec3(2.2f));
  c = m.rec2020ToSrgb * c;
  return glm::clamp(c, 0.0f, 1.0f);
}

glm::vec3 toneMap(ToneMapOperator op, const glm::vec3& x) {
  switch (op) {
    case ToneMapOperator::Linear: return glm::clamp(x, 0.0f, 1.0f);
    case ToneMapOperator::Reinhard: return reinhard(x);
    case ToneMapOperator::AcesFitted: return acesFitted(x * kAcesExposureGain);
    case ToneMapOperator::Neutral: return pbrNeutral(x);
    case ToneMapOperator::AgX: return agx(x);
  }
  return x;
}

glm::vec3 toneMap(ToneMapOperator op, const glm::vec3& x, float exposureEv) {
  return toneMap(op, x * exposureScale(exposureEv));
}

float linearToSrgb(float linear) {
  const float c = clamp01(linear);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float srgbToLinear(float srgb) {
  const float c = clamp01(srgb);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

glm::vec3 linearToSrgb(const glm::vec3& c) { return {linearToSrgb(c.r), linearToSrgb(c.g), linearToSrgb(c.b)}; }
glm::vec3 srgbToLinear(const glm::vec3& c) { return {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)}; }

float fxaaLuma(const glm::vec3& srgb) { return srgb.r * 0.299f + srgb.g * 0.587f + srgb.b * 0.114f; }

}  // namespace obscura
