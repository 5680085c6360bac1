#include "frame/Parameters.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "encoding/ToneMapping.h"

namespace obscura {

const char* parameterKindName(ParameterKind kind) {
  switch (kind) {
    case ParameterKind::Switch: return "switch";
    case ParameterKind::Number: return "number";
    case ParameterKind::Integer: return "integer";
    case ParameterKind::Choice: return "choice";
    case ParameterKind::Color: return "color";
    case ParameterKind::Text: return "text";
  }
  return "?";
}

const std::vector<QualityPreset>& allQualityPresets() {
  static const std::vector<QualityPreset> presets = {QualityPreset::Low, QualityPreset::Medium, QualityPreset::High,
                                                     QualityPreset::Ultra};
  return presets;
}

const char* presetName(QualityPreset preset) {
  switch (preset) {
    case QualityPreset::Low: return "low";
    case QualityPreset::Medium: return "medium";
    case QualityPreset::High: return "high";
    case QualityPreset::Ultra: return "ultra";
  }
  return "medium";
}

QualityPreset parsePreset(const std::string& name) {
  for (QualityPreset preset : allQualityPresets())
    if (name == presetName(preset)) return preset;
  throw InputError("preset: expected low, medium, high or ultra, got '" + name + "'");
}

namespace parse {

float number(const std::string& name, const std::string& text, double min, double max, const char* unit) {
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

int integer(const std::string& name, const std::string& text, double min, double max, const char* unit) {
  const float value = number(name, text, min, max, unit);
  if (value != std::floor(value)) throw InputError(name + ": expected a whole number, got '" + text + "'");
  return static_cast<int>(value);
}

bool onOff(const std::string& name, const std::string& text) {
  if (text == "on" || text == "1" || text == "true") return true;
  if (text == "off" || text == "0" || text == "false") return false;
  throw InputError(name + ": expected on or off, got '" + text + "'");
}

glm::vec3 color(const std::string& name, const std::string& text, double min, double max) {
  const std::string expected = name + ": expected r,g,b or #rrggbb, got '" + text + "'";
  glm::vec3 value(0.0f);
  if (!text.empty() && text[0] == '#') {
    if (text.size() != 7) throw InputError(expected);
    for (int c = 0; c < 3; ++c) {
      const std::string hex = text.substr(1 + 2 * static_cast<size_t>(c), 2);
      char* end = nullptr;
      const long byte = std::strtol(hex.c_str(), &end, 16);
      if (end != hex.c_str() + 2 || hex[0] == '-' || hex[0] == '+') throw InputError(expected);
      value[c] = srgbToLinear(static_cast<float>(byte) / 255.0f);
    }
  } else {
    size_t from = 0;
    for (int c = 0; c < 3; ++c) {
      const size_t comma = text.find(',', from);
      if ((c < 2) != (comma != std::string::npos)) throw InputError(expected);
      value[c] = number(name, text.substr(from, c < 2 ? comma - from : std::string::npos), min, max, "");
      from = comma + 1;
    }
  }
  for (int c = 0; c < 3; ++c)
    if (value[c] < min || value[c] > max) throw InputError(name + ": " + text + " is outside " +
                                                           numericRange(min, max, "", "") + " per channel");
  return value;
}

std::string formatColor(const glm::vec3& linear) {
  return formatShortest(linear.r) + "," + formatShortest(linear.g) + "," + formatShortest(linear.b);
}

std::string numericRange(double min, double max, const char* unit, const char* constraint) {
  char text[160];
  std::snprintf(text, sizeof text, "%g .. %g%s%s%s%s%s", min, max, *unit ? " (" : "", unit, *unit ? ")" : "",
                *constraint ? ", " : "", constraint);
  return text;
}

std::string joinChoices(const std::vector<std::string>& choices, const char* separator) {
  std::string out;
  for (const std::string& c : choices) out += (out.empty() ? "" : separator) + c;
  return out;
}

std::string oneOf(const std::vector<std::string>& choices) {
  std::string out;
  for (size_t i = 0; i < choices.size(); ++i)
    out += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
  return out;
}

}  // namespace parse
}  // namespace obscura
