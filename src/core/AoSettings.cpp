#include "core/AoSettings.h"

#include <cmath>
#include <cstdlib>
#include <cstdio>
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

int parseInteger(const std::string& name, const std::string& text, double min, double max, const char* unit) {
  const float value = parseNumber(name, text, min, max, unit);
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

std::string numericRange(double min, double max, const char* unit, const char* constraint) {
  char text[160];
  std::snprintf(text, sizeof text, "%g .. %g%s%s%s%s%s", min, max, *unit ? " (" : "", unit, *unit ? ")" : "",
                *constraint ? ", " : "", constraint);
  return text;
}

// One row of the parameter table: its documentation, how text becomes a value (range-checked), how the value
// becomes text again, and the check validate() applies to settings built in code.
struct Parameter {
  ParameterInfo info;
  std::function<void(AoSettings&, const std::string& value)> set;
  std::function<std::string(const AoSettings&)> get;
  std::function<bool(const AoSettings&)> valid;
};

Parameter switchParameter(const char* name, const char* help, bool AoSettings::*field) {
  Parameter p{{name, "on | off", help, ParameterKind::Switch, 0.0, 0.0, {"on", "off"}}, {}, {}, {}};
  p.set = [name, field](AoSettings& s, const std::string& v) { s.*field = parseSwitch(name, v); };
  p.get = [field](const AoSettings& s) { return std::string(s.*field ? "on" : "off"); };
  p.valid = [](const AoSettings&) { return true; };
  return p;
}

Parameter numberParameter(const char* name, double min, double max, const char* unit, const char* help,
                          float AoSettings::*field) {
  Parameter p{{name, numericRange(min, max, unit, ""), help, ParameterKind::Number, min, max, {}}, {}, {}, {}};
  p.set = [=](AoSettings& s, const std::string& v) { s.*field = parseNumber(name, v, min, max, unit); };
  p.get = [field](const AoSettings& s) { return formatShortest(s.*field); };
  p.valid = [=](const AoSettings& s) {
    return s.*field >= static_cast<float>(min) && s.*field <= static_cast<float>(max);
  };
  return p;
}

// An estimator parameter that defaults to the value fitted to the reference (AoSettings::estimator): a number in
// range, or "auto" to return to the fitted value.
Parameter tunableParameter(const char* name, double min, double max, const char* unit, const char* help,
                           std::optional<float> AoSettings::*field) {
  Parameter p{{name, numericRange(min, max, unit, "or auto"), help, ParameterKind::Number, min, max, {"auto"}},
              {}, {}, {}};
  p.set = [=](AoSettings& s, const std::string& v) { s.*field = parseTunable(name, v, min, max, unit); };
  p.get = [field](const AoSettings& s) { return (s.*field) ? formatShortest(*(s.*field)) : std::string("auto"); };
  p.valid = [=](const AoSettings& s) {
    return !(s.*field) || (*(s.*field) >= static_cast<float>(min) && *(s.*field) <= static_cast<float>(max));
  };
  return p;
}

// `constraint` documents a rule beyond the range; `also` applies a consequence of the new value (or throws).
Parameter integerParameter(const char* name, int min, int max, const char* unit, const char* constraint,
                           const char* help, int AoSettings::*field,
                           std::function<void(AoSettings&, const std::string& value)> also = {}) {
  Parameter p{{name, numericRange(min, max, unit, constraint), help, ParameterKind::Integer, double(min), double(max),
               {}},
              {}, {}, {}};
  p.set = [=](AoSettings& s, const std::string& v) {
    const int value = parseInteger(name, v, min, max, unit);
    AoSettings changed = s;
    changed.*field = value;
    if (also) also(changed, v);
    s = changed;
  };
  p.get = [field](const AoSettings& s) { return std::to_string(s.*field); };
  p.valid = [=](const AoSettings& s) { return s.*field >= min && s.*field <= max; };
  return p;
}

std::string joinChoices(const std::vector<std::string>& choices, const char* separator) {
  std::string out;
  for (const std::string& c : choices) out += (out.empty() ? "" : separator) + c;
  return out;
}

const std::vector<Parameter>& parameterTable() {
  static const std::vector<Parameter> table = [] {
    std::vector<Parameter> t;
    t.push_back(switchParameter("ao", "ambient obscurance on or off", &AoSettings::enabled));

    std::vector<std::string> presetNames;
    for (const PresetInfo& preset : qualityPresets()) presetNames.push_back(preset.name);
    Parameter preset{{"preset", joinChoices(presetNames, " | "),
                      "quality preset: samples, spiral turns, blur, resolution", ParameterKind::Choice, 0.0, 0.0,
                      presetNames},
                     {}, {}, {}};
    preset.set = [](AoSettings& s, const std::string& v) { s.applyPreset(parsePreset(v)); };
    // The preset the settings came from, while they still hold its values ("" once they differ).
    preset.get = [](const AoSettings& s) {
      for (const PresetInfo& p : qualityPresets())
        if (p.preset == s.preset && s.samples == p.samples && s.spiralTurns == p.spiralTurns &&
            s.blurRadius == p.blurRadius && s.blurStride == p.blurStride && s.halfResolution == p.halfResolution)
          return std::string(p.name);
      return std::string();
    };
    preset.valid = [](const AoSettings&) { return true; };
    t.push_back(preset);

    t.push_back(numberParameter("radius", 0.01, 100, "metres", "world-space obscurance radius r", &AoSettings::radius));
    t.push_back(tunableParameter("bias", 0, 1, "metres",
                                 "tangent-plane bias beta against self-occlusion (auto: fitted to the reference)",
                                 &AoSettings::bias));
    t.push_back(tunableParameter("intensity", 0, 20, "", "intensity sigma (auto: fitted to the reference)",
                                 &AoSettings::intensity));
    t.push_back(tunableParameter("contrast", 0.1, 10, "", "contrast exponent k (auto: fitted to the reference)",
                                 &AoSettings::contrast));
    t.push_back(integerParameter("samples", 1, 64, "", "", "taps per pixel (also picks the best spiral turns)",
                                 &AoSettings::samples, [](AoSettings& s, const std::string&) {
                                   s.spiralTurns = SaoKernel::bestSpiralTurns(s.samples);
                                 }));
    Parameter turns = integerParameter(
        "turns", 1, 63, "", "coprime with samples", "spiral turns tau", &AoSettings::spiralTurns,
        [](AoSettings& s, const std::string& v) {
          if (SaoKernel::greatestCommonDivisor(s.spiralTurns, s.samples) != 1)
            throw InputError("turns: " + v + " shares a factor with samples = " + std::to_string(s.samples) +
                             "; taps would line up");
        });
    turns.valid = [](const AoSettings& s) {
      return s.spiralTurns >= 1 && SaoKernel::greatestCommonDivisor(s.spiralTurns, s.samples) == 1;
    };
    t.push_back(turns);

    Parameter falloff{{"falloff", "sao2012 | alchemy2011", "distance falloff of the estimator", ParameterKind::Choice,
                       0.0, 0.0, {"sao2012", "alchemy2011"}}, {}, {}, {}};
    falloff.set = [](AoSettings& s, const std::string& v) {
      if (v == "sao2012") s.falloff = Falloff::Sao2012;
      else if (v == "alchemy2011") s.falloff = Falloff::Alchemy2011;
      else throw InputError("falloff: expected sao2012 or alchemy2011, got '" + v + "'");
    };
    falloff.get = [](const AoSettings& s) { return std::string(falloffName(s.falloff)); };
    falloff.valid = [](const AoSettings&) { return true; };
    t.push_back(falloff);

    t.push_back(numberParameter("max-screen-radius", 0.01, 1, "fraction of height", "clamp of the projected radius",
                                &AoSettings::maxScreenRadius));
    t.push_back(switchParameter("hierarchy", "depth hierarchy for far taps", &AoSettings::depthHierarchy));
    t.push_back(switchParameter("half-res", "AO at half resolution, upsampled depth-aware",
                                &AoSettings::halfResolution));
    t.push_back(switchParameter("blur", "bilateral blur", &AoSettings::blur));
    t.push_back(integerParameter("blur-radius", 0, 8, "taps each side", "", "blur radius; 0 turns the blur off",
                                 &AoSettings::blurRadius));
    t.push_back(integerParameter("blur-stride", 1, 8, "pixels", "", "pixels between blur taps",
                                 &AoSettings::blurStride));
    t.push_back(switchParameter("blur-normals", "normal-aware blur weights", &AoSettings::blurNormalAware));
    t.push_back(numberParameter("blur-depth-sigma", 0.001, 10, "metres",
                                "depth difference at which blur weights fall to 1/e", &AoSettings::blurDepthSigma));
    return t;
  }();
  return table;
}

const Parameter& findParameter(const std::string& name) {
  for (const Parameter& p : parameterTable())
    if (name == p.info.name) return p;
  throw InputError("unknown parameter '" + name + "'");
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

const char* presetName(QualityPreset preset) {
  for (const PresetInfo& p : qualityPresets())
    if (p.preset == preset) return p.name;
  return "medium";  // unreachable: the table lists every preset
}

QualityPreset parsePreset(const std::string& name) {
  for (const PresetInfo& p : qualityPresets())
    if (name == p.name) return p.preset;
  throw InputError("preset: expected low, medium, high or ultra, got '" + name + "'");
}

std::string formatShortest(float value) {
  char text[48];
  // Plain decimals where they are short ("50", "0.012"), else the shortest exponent form.
  if (std::fabs(value) < 1e7f) {
    for (int decimals = 0; decimals <= 9; ++decimals) {
      std::snprintf(text, sizeof text, "%.*f", decimals, static_cast<double>(value));
      if (std::strtof(text, nullptr) == value) return text;
    }
  }
  for (int digits = 1; digits <= 9; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, static_cast<double>(value));
    if (std::strtof(text, nullptr) == value) break;
  }
  return text;
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

void AoSettings::set(const std::string& name, const std::string& value) { findParameter(name).set(*this, value); }

std::string AoSettings::get(const std::string& name) const { return findParameter(name).get(*this); }

std::string AoSettings::effective(const std::string& name) const {
  const EstimatorParameters e = estimator();
  if (name == "bias") return formatShortest(e.bias);
  if (name == "intensity") return formatShortest(e.intensity);
  if (name == "contrast") return formatShortest(e.contrast);
  return get(name);
}

void AoSettings::validate() const {
  for (const Parameter& p : parameterTable())
    if (!p.valid(*this))
      throw InputError(std::string("invalid AO settings: ") + p.info.name + " = " + p.get(*this) + " is outside " +
                       p.info.range);
  // The estimator parameters are also checked as resolved, so a tuned table entry out of range is caught too.
  const EstimatorParameters e = estimator();
  if (!(e.bias >= 0.0f && e.bias <= 1.0f && e.intensity >= 0.0f && e.intensity <= 20.0f && e.contrast >= 0.1f &&
        e.contrast <= 10.0f))
    throw InputError("invalid AO settings: the tuned estimator parameters for this preset and radius are out of range");
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
