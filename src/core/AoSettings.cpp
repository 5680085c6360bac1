#include "core/AoSettings.h"

#include <cmath>
#include <cstdlib>
#include <functional>

#include "core/Error.h"
#include "core/SaoKernel.h"

namespace obscura {
namespace {

float parseNumber(const std::string& name, const std::string& text, double min, double max, const char* unit) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || *end != '\0' || !std::isfinite(value))
    throw InputError(name + ": expected a number, got '" + text + "'");
  if (value < min || value > max) {
    char range[160];
    std::snprintf(range, sizeof range, "%s: %s is out of range (%g .. %g%s%s)", name.c_str(), text.c_str(), min, max,
                  *unit ? " " : "", unit);
    throw InputError(range);
  }
  return static_cast<float>(value);
}

int parseInteger(const std::string& name, const std::string& text, int min, int max) {
  const float value = parseNumber(name, text, min, max, "");
  if (value != std::floor(value)) throw InputError(name + ": expected a whole number, got '" + text + "'");
  return static_cast<int>(value);
}

// An estimator parameter that defaults to its tuned value: a number in range, or "auto" for the tuned value.
std::optional<float> parseTunable(const std::string& name, const std::string& text, double min, double max,
                                  const char* unit) {
  if (text == "auto") return std::nullopt;
  return parseNumber(name, text, min, max, unit);
}

bool parseSwitch(const std::string& name, const std::string& text) {
  if (text == "on" || text == "1" || text == "true") return true;
  if (text == "off" || text == "0" || text == "false") return false;
  throw InputError(name + ": expected on or off, got '" + text + "'");
}

struct Parameter {
  ParameterInfo info;
  std::function<void(AoSettings&, const std::string& name, const std::string& value)> apply;
};

const std::vector<Parameter>& parameterTable() {
  static const std::vector<Parameter> table = {
      {{"ao", "on | off", "ambient obscurance on or off"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.enabled = parseSwitch(n, v); }},
      {{"preset", "low | medium | high | ultra", "quality preset: samples, spiral turns, blur, resolution"},
       [](AoSettings& s, const std::string&, const std::string& v) { s.applyPreset(parsePreset(v)); }},
      {{"radius", "0.01 .. 100 (metres)", "world-space obscurance radius r"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.radius = parseNumber(n, v, 0.01, 100, "metres"); }},
      {{"bias", "0 .. 1 (metres)", "tangent-plane bias beta against self-occlusion (default: tuned; auto)"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.bias = parseTunable(n, v, 0, 1, "metres"); }},
      {{"intensity", "0 .. 20", "intensity sigma (default: tuned to the reference for preset and radius; auto)"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.intensity = parseTunable(n, v, 0, 20, ""); }},
      {{"contrast", "0.1 .. 10", "contrast exponent k (default: tuned; auto)"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.contrast = parseTunable(n, v, 0.1, 10, ""); }},
      {{"samples", "1 .. 64", "taps per pixel (also picks the best spiral turns)"},
       [](AoSettings& s, const std::string& n, const std::string& v) {
         s.samples = parseInteger(n, v, 1, 64);
         s.spiralTurns = SaoKernel::bestSpiralTurns(s.samples);
       }},
      {{"turns", "1 .. 63, coprime with samples", "spiral turns tau"},
       [](AoSettings& s, const std::string& n, const std::string& v) {
         const int turns = parseInteger(n, v, 1, 63);
         if (SaoKernel::greatestCommonDivisor(turns, s.samples) != 1)
           throw InputError(n + ": " + v + " shares a factor with samples = " + std::to_string(s.samples) +
                            "; taps would line up");
         s.spiralTurns = turns;
       }},
      {{"falloff", "sao2012 | alchemy2011", "distance falloff of the estimator"},
       [](AoSettings& s, const std::string& n, const std::string& v) {
         if (v == "sao2012") s.falloff = Falloff::Sao2012;
         else if (v == "alchemy2011") s.falloff = Falloff::Alchemy2011;
         else throw InputError(n + ": expected sao2012 or alchemy2011, got '" + v + "'");
       }},
      {{"max-screen-radius", "0.01 .. 1 (fraction of height)", "clamp of the projected radius"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.maxScreenRadius = parseNumber(n, v, 0.01, 1, ""); }},
      {{"hierarchy", "on | off", "depth hierarchy for far taps"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.depthHierarchy = parseSwitch(n, v); }},
      {{"half-res", "on | off", "AO at half resolution, upsampled depth-aware"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.halfResolution = parseSwitch(n, v); }},
      {{"blur", "on | off", "bilateral blur"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.blur = parseSwitch(n, v); }},
      {{"blur-radius", "0 .. 8 (taps each side)", "blur radius; 0 turns the blur off"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.blurRadius = parseInteger(n, v, 0, 8); }},
      {{"blur-stride", "1 .. 8 (pixels)", "pixels between blur taps"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.blurStride = parseInteger(n, v, 1, 8); }},
      {{"blur-normals", "on | off", "normal-aware blur weights"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.blurNormalAware = parseSwitch(n, v); }},
      {{"blur-depth-sigma", "0.001 .. 10 (metres)", "depth difference at which blur weights fall to 1/e"},
       [](AoSettings& s, const std::string& n, const std::string& v) { s.blurDepthSigma = parseNumber(n, v, 0.001, 10, "metres"); }},
  };
  return table;
}

}  // namespace

const std::vector<PresetInfo>& qualityPresets() {
  // samples / spiral turns / blur radius / blur stride / half resolution. Turns are bestSpiralTurns(samples) (a test
  // holds them equal). The blur stride stays 1: a stride of 2 aliases with the interleaved-gradient rotation and
  // leaves a regular pattern. Costs measured by obscura-bench are in docs/benchmarks.md.
  static const std::vector<PresetInfo> presets = {
      {QualityPreset::Low, "low", 8, 3, 3, 1, true},
      {QualityPreset::Medium, "medium", 11, 3, 4, 1, false},
      {QualityPreset::High, "high", 16, 3, 5, 1, false},
      {QualityPreset::Ultra, "ultra", 32, 7, 6, 1, false},
  };
  return presets;
}

QualityPreset parsePreset(const std::string& name) {
  for (const PresetInfo& p : qualityPresets())
    if (name == p.name) return p.preset;
  throw InputError("preset: expected low, medium, high or ultra, got '" + name + "'");
}

const char* falloffName(Falloff falloff) { return falloff == Falloff::Sao2012 ? "sao2012" : "alchemy2011"; }

void AoSettings::applyPreset(QualityPreset which) {
  for (const PresetInfo& p : qualityPresets()) {
    if (p.preset != which) continue;
    preset = which;
    samples = p.samples;
    spiralTurns = p.spiralTurns;
    blurRadius = p.blurRadius;
    blurStride = p.blurStride;
    halfResolution = p.halfResolution;
  }
}

void AoSettings::set(const std::string& name, const std::string& value) {
  for (const Parameter& p : parameterTable()) {
    if (name == p.info.name) {
      p.apply(*this, name, value);
      return;
    }
  }
  throw InputError("unknown parameter '" + name + "'");
}

void AoSettings::validate() const {
  auto check = [](bool ok, const std::string& what) {
    if (!ok) throw InputError("invalid AO settings: " + what);
  };
  check(radius >= 0.01f && radius <= 100.0f, "radius must be in 0.01 .. 100 m");
  // Checked as resolved, so a tuned table entry out of range is caught as well.
  const EstimatorParameters e = estimator();
  check(e.bias >= 0.0f && e.bias <= 1.0f, "bias must be in 0 .. 1 m");
  check(e.intensity >= 0.0f && e.intensity <= 20.0f, "intensity must be in 0 .. 20");
  check(e.contrast >= 0.1f && e.contrast <= 10.0f, "contrast must be in 0.1 .. 10");
  check(samples >= 1 && samples <= 64, "samples must be in 1 .. 64");
  check(spiralTurns >= 1 && SaoKernel::greatestCommonDivisor(spiralTurns, samples) == 1,
        "spiral turns must be coprime with samples");
  check(maxScreenRadius >= 0.01f && maxScreenRadius <= 1.0f, "max screen radius must be in 0.01 .. 1");
  check(blurRadius >= 0 && blurRadius <= 8, "blur radius must be in 0 .. 8");
  check(blurStride >= 1 && blurStride <= 8, "blur stride must be in 1 .. 8");
  check(blurDepthSigma >= 0.001f && blurDepthSigma <= 10.0f, "blur depth sigma must be in 0.001 .. 10 m");
}

namespace {

struct TunedEntry {
  QualityPreset preset;
  float radius;
  EstimatorParameters parameters;
};

// Rows ordered by preset, then by increasing radius.
constexpr TunedEntry kTunedTable[] = {
#include "core/TunedDefaults.inc"
};

}  // namespace

EstimatorParameters tunedEstimatorParameters(QualityPreset preset, float radius) {
  const TunedEntry* first = nullptr;
  const TunedEntry* last = nullptr;
  for (const TunedEntry& entry : kTunedTable) {
    if (entry.preset != preset) continue;
    if (!first) first = &entry;
    last = &entry;
  }
  if (!first) return kPaperEstimatorParameters;
  if (radius <= first->radius) return first->parameters;
  if (radius >= last->radius) return last->parameters;
  const TunedEntry* upper = first + 1;
  while (upper->radius < radius) ++upper;
  const TunedEntry& lower = *(upper - 1);
  // The fitted radii are spaced by factors of two, so interpolate in log(radius).
  const float t = std::log(radius / lower.radius) / std::log(upper->radius / lower.radius);
  auto mix = [t](float a, float b) { return a + (b - a) * t; };
  return {mix(lower.parameters.intensity, upper->parameters.intensity),
          mix(lower.parameters.bias, upper->parameters.bias),
          mix(lower.parameters.contrast, upper->parameters.contrast)};
}

EstimatorParameters AoSettings::estimator() const {
  EstimatorParameters e = tunedEstimatorParameters(preset, radius);
  if (intensity) e.intensity = *intensity;
  if (bias) e.bias = *bias;
  if (contrast) e.contrast = *contrast;
  return e;
}

const std::vector<ParameterInfo>& aoParameters() {
  static const std::vector<ParameterInfo> infos = [] {
    std::vector<ParameterInfo> out;
    for (const Parameter& p : parameterTable()) out.push_back(p.info);
    return out;
  }();
  return infos;
}

}  // namespace obscura
