#pragma once
// Parameters: every user-facing knob of every effect, with its kind, range and help, set and read as text. The
// command line, the viewers' state text (the page's URL), the desktop keys and the page's controls all go through
// them, so they accept the same names and ranges, and an out-of-range value never reaches a shader.
//
// Each effect's settings struct S lists its parameters (S::parameters(), built with the helpers below) under local
// names: the switch is named after the effect ("ao"), the others plainly ("radius"). RenderSettings
// (renderer/RenderSettings.h) prefixes them with the effect's name ("ao.radius") for the whole frame.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "base/Error.h"
#include "base/Text.h"

namespace obscura {

// What kind of value a parameter takes, so a user interface can offer the right control.
enum class ParameterKind {
  Switch,   // "on" | "off"
  Number,   // a real number in min .. max
  Integer,  // a whole number in min .. max
  Choice,   // one of `choices`
  Color,    // a linear RGB colour, each channel in min .. max: "r,g,b" (linear) or "#rrggbb" (sRGB-encoded)
  Text,     // any non-empty text: one of `choices` (named built-ins) or a name of the caller's (a file path)
};
const char* parameterKindName(ParameterKind kind);  // "switch", "number", "integer", "choice", "color", "text"

// The quality presets every effect with presets shares by name; the global "preset" parameter sets them all.
enum class QualityPreset { Low, Medium, High, Ultra };
const std::vector<QualityPreset>& allQualityPresets();
const char* presetName(QualityPreset preset);
QualityPreset parsePreset(const std::string& name);  // throws InputError

struct ParameterInfo {
  ParameterInfo() = default;
  ParameterInfo(std::string name_, std::string range_, std::string help_, ParameterKind kind_, double min_ = 0.0,
                double max_ = 0.0, std::vector<std::string> choices_ = {})
      : name(std::move(name_)), range(std::move(range_)), help(std::move(help_)), kind(kind_), min(min_), max(max_),
        choices(std::move(choices_)) {}

  std::string name;    // local to its effect ("radius", or the effect's name for its switch) or full ("ao.radius")
  std::string range;   // human-readable, made from the fields below, e.g. "0.01 .. 100 (metres)"
  std::string help;
  ParameterKind kind = ParameterKind::Number;
  double min = 0.0, max = 0.0;       // Number and Integer
  std::vector<std::string> choices;  // Switch and Choice, in the order to offer them; for a Number, words accepted
                                     // besides numbers ("auto": the AO estimator's fitted values)
  bool primary = false;              // user interfaces show it up front (the rest under "more")
  // A change takes a noticeable time (lighting.sun-elevation makes and prefilters the sky again): a slider applies it
  // when the drag ends, not at every step.
  bool slow = false;
  // A change changes the frame's plan (frame/FramePlan.h): which passes run, their targets' sizes or their programs
  // (a switch, a choice of variant, a loop bound). The Renderer keys its cached plans on these parameters' values;
  // the others (numbers and colours, unless marked) reach the passes each frame through their PassContext.
  // Plan.ACachedPlanDrawsWhatAFreshOneDraws (tests/test_pipeline.cpp) holds every unmarked parameter to it.
  bool shapesPlan = true;
  std::string effect;                // the effect it belongs to; "" for the frame's own ("preset")
  std::string alias;                 // an older name still accepted everywhere ("radius" for "ao.radius"), or ""
};

// One parameter of settings struct S: how text becomes a value (range-checked, throwing InputError), how the value
// becomes text again, the check validate() applies to settings built in code, and the value in use where it
// differs from the value set ("auto" resolved).
template <typename S>
struct Parameter {
  ParameterInfo info;
  std::function<void(S&, const std::string&)> set;
  std::function<std::string(const S&)> get;
  std::function<bool(const S&)> valid;
  std::function<std::string(const S&)> effective;  // empty: get
  // Whether two settings hold the same value (the cached plan's key compares by it each frame, not by the text);
  // empty: compare get()'s text.
  std::function<bool(const S&, const S&)> same;

  // Marks it as shown up front by user interfaces.
  Parameter primary() && {
    info.primary = true;
    return std::move(*this);
  }
  // Marks it as slow to change (ParameterInfo::slow).
  Parameter slow() && {
    info.slow = true;
    return std::move(*this);
  }
  // Marks a number as one that changes the plan (ParameterInfo::shapesPlan: a threshold that turns a pass on, a size
  // that sets a loop bound or a target's size).
  Parameter shapesPlan() && {
    info.shapesPlan = true;
    return std::move(*this);
  }
};

// Parameter::same for a parameter that is one field of its settings.
template <typename S, typename T>
std::function<bool(const S&, const S&)> sameField(T S::*field) {
  return [field](const S& a, const S& b) { return a.*field == b.*field; };
}

namespace parse {
float number(const std::string& name, const std::string& text, double min, double max, const char* unit);
int integer(const std::string& name, const std::string& text, double min, double max, const char* unit);
bool onOff(const std::string& name, const std::string& text);
// "r,g,b" (linear, each in min .. max) or "#rrggbb" (sRGB-encoded bytes, decoded to linear: a colour picker's value).
glm::vec3 color(const std::string& name, const std::string& text, double min, double max);
std::string formatColor(const glm::vec3& linear);  // "r,g,b", each number in its shortest exact form
std::string numericRange(double min, double max, const char* unit, const char* constraint);
std::string joinChoices(const std::vector<std::string>& choices, const char* separator);
std::string oneOf(const std::vector<std::string>& choices);  // "a, b or c"
}  // namespace parse

template <typename S>
Parameter<S> switchParameter(const char* name, const char* help, bool S::*field) {
  Parameter<S> p{{name, "on | off", help, ParameterKind::Switch, 0.0, 0.0, {"on", "off"}}, {}, {}, {}, {}, {}};
  p.set = [name, field](S& s, const std::string& v) { s.*field = parse::onOff(name, v); };
  p.get = [field](const S& s) { return std::string(s.*field ? "on" : "off"); };
  p.same = sameField(field);
  p.valid = [](const S&) { return true; };
  return p;
}

template <typename S>
Parameter<S> numberParameter(const char* name, double min, double max, const char* unit, const char* help,
                             float S::*field) {
  Parameter<S> p{{name, parse::numericRange(min, max, unit, ""), help, ParameterKind::Number, min, max, {}},
                 {}, {}, {}, {}, {}};
  p.info.shapesPlan = false;  // a value the passes read each frame, unless marked
  p.set = [=](S& s, const std::string& v) { s.*field = parse::number(name, v, min, max, unit); };
  p.get = [field](const S& s) { return formatShortest(s.*field); };
  p.same = sameField(field);
  p.valid = [=](const S& s) { return s.*field >= static_cast<float>(min) && s.*field <= static_cast<float>(max); };
  return p;
}

// A number that may also be "auto": unset, the settings resolve it themselves (`resolved`, for effective()).
template <typename S>
Parameter<S> autoNumberParameter(const char* name, double min, double max, const char* unit, const char* help,
                                 std::optional<float> S::*field, std::function<float(const S&)> resolved) {
  Parameter<S> p{{name, parse::numericRange(min, max, unit, "or auto"), help, ParameterKind::Number, min, max,
                  {"auto"}},
                 {}, {}, {}, {}, {}};
  p.info.shapesPlan = false;  // a value the passes read each frame, unless marked
  p.set = [=](S& s, const std::string& v) {
    if (v == "auto") s.*field = std::nullopt;
    else s.*field = parse::number(name, v, min, max, unit);
  };
  p.get = [field](const S& s) { return (s.*field) ? formatShortest(*(s.*field)) : std::string("auto"); };
  p.same = sameField(field);
  p.valid = [=](const S& s) {
    return !(s.*field) || (*(s.*field) >= static_cast<float>(min) && *(s.*field) <= static_cast<float>(max));
  };
  p.effective = [resolved](const S& s) { return formatShortest(resolved(s)); };
  return p;
}

// `constraint` documents a rule beyond the range; `also` applies a consequence of the new value (or throws).
template <typename S>
Parameter<S> integerParameter(const char* name, int min, int max, const char* unit, const char* constraint,
                              const char* help, int S::*field,
                              std::function<void(S&, const std::string& value)> also = {}) {
  Parameter<S> p{{name, parse::numericRange(min, max, unit, constraint), help, ParameterKind::Integer, double(min),
                  double(max), {}},
                 {}, {}, {}, {}, {}};
  p.set = [=](S& s, const std::string& v) {
    S changed = s;
    changed.*field = parse::integer(name, v, min, max, unit);
    if (also) also(changed, v);
    s = changed;
  };
  p.get = [field](const S& s) { return std::to_string(s.*field); };
  p.same = sameField(field);
  p.valid = [=](const S& s) { return s.*field >= min && s.*field <= max; };
  return p;
}

// An effect's `preset` (EFFECT.preset), for settings with applyPreset(QualityPreset), matchesPreset(QualityPreset)
// and the QualityPreset `preset` they came from: one of the presets' names, read back as "" once the settings no
// longer hold its values. `shapesPlan`: whether the values it sets shape the plan (ParameterInfo::shapesPlan).
template <typename S>
Parameter<S> presetParameter(const char* help, bool shapesPlan = true) {
  std::vector<std::string> names;
  for (QualityPreset preset : allQualityPresets()) names.push_back(presetName(preset));
  Parameter<S> p{{"preset", parse::joinChoices(names, " | "), help, ParameterKind::Choice, 0.0, 0.0, names},
                 {}, {}, {}, {}, {}};
  p.set = [](S& s, const std::string& v) { s.applyPreset(parsePreset(v)); };
  p.get = [](const S& s) { return s.matchesPreset(s.preset) ? std::string(presetName(s.preset)) : ""; };
  p.valid = [](const S&) { return true; };
  p.info.shapesPlan = shapesPlan;
  return p;
}

// A linear RGB colour (parse::color's forms; get() gives "r,g,b").
template <typename S>
Parameter<S> colorParameter(const char* name, double min, double max, const char* help, glm::vec3 S::*field) {
  Parameter<S> p{{name, "r,g,b (linear, each " + parse::numericRange(min, max, "", "") + ") or #rrggbb (sRGB)", help,
                  ParameterKind::Color, min, max, {}},
                 {}, {}, {}, {}, {}};
  p.info.shapesPlan = false;  // a value the passes read each frame
  p.set = [=](S& s, const std::string& v) { s.*field = parse::color(name, v, min, max); };
  p.get = [field](const S& s) { return parse::formatColor(s.*field); };
  p.same = sameField(field);
  p.valid = [=](const S& s) {
    for (int c = 0; c < 3; ++c)
      if (!((s.*field)[c] >= static_cast<float>(min) && (s.*field)[c] <= static_cast<float>(max))) return false;
    return true;
  };
  return p;
}

// Text: one of `builtIns` or any other non-empty text the effect interprets (a file path); `range` documents it.
template <typename S>
Parameter<S> textParameter(const char* name, const char* range, const char* help, std::string S::*field,
                           std::vector<std::string> builtIns) {
  Parameter<S> p{{name, range, help, ParameterKind::Text, 0.0, 0.0, std::move(builtIns)}, {}, {}, {}, {}, {}};
  p.set = [name, field](S& s, const std::string& v) {
    if (v.empty()) throw InputError(std::string(name) + ": expected a name, got nothing");
    s.*field = v;
  };
  p.get = [field](const S& s) { return s.*field; };
  p.same = sameField(field);
  p.valid = [field](const S& s) { return !(s.*field).empty(); };
  return p;
}

// One of a list of named values of an enum field.
template <typename S, typename E>
Parameter<S> choiceParameter(const char* name, const char* help, E S::*field,
                             std::vector<std::pair<std::string, E>> values) {
  std::vector<std::string> names;
  for (const auto& value : values) names.push_back(value.first);
  Parameter<S> p{{name, parse::joinChoices(names, " | "), help, ParameterKind::Choice, 0.0, 0.0, names},
                 {}, {}, {}, {}, {}};
  p.set = [=](S& s, const std::string& v) {
    for (const auto& [text, value] : values)
      if (v == text) {
        s.*field = value;
        return;
      }
    throw InputError(std::string(name) + ": expected " + parse::oneOf(names) + ", got '" + v + "'");
  };
  p.get = [=](const S& s) {
    for (const auto& [text, value] : values)
      if (s.*field == value) return text;
    return std::string("?");
  };
  p.same = sameField(field);
  p.valid = [=](const S& s) {
    for (const auto& value : values)
      if (s.*field == value.second) return true;
    return false;
  };
  return p;
}

// Text access to a settings struct by its parameters' local names (S::parameters()): what each effect's settings
// offer on their own (AoSettings::set("radius", "2")), and what RenderSettings calls with the prefix removed.
template <typename S>
class ParameterAccess {
 public:
  // Throws InputError naming the parameter, the value and the accepted range when the name is unknown or the value
  // is out of range; the settings are unchanged then.
  void set(const std::string& name, const std::string& value) { find(name).set(self(), value); }
  // The value as text that set() accepts (numbers in their shortest exact form).
  std::string get(const std::string& name) const { return find(name).get(self()); }
  // The value in use: get(name), except where the settings resolve it ("auto" reads as what it resolves to).
  std::string effective(const std::string& name) const {
    const Parameter<S>& p = find(name);
    return p.effective ? p.effective(self()) : p.get(self());
  }
  // Throws InputError if a field is out of range (for settings built in code).
  void validateParameters(const char* what) const {
    for (const Parameter<S>& p : S::parameters())
      if (!p.valid(self()))
        throw InputError(std::string("invalid ") + what + " settings: " + p.info.name + " = " + p.get(self()) +
                         " is outside " + p.info.range);
  }

 private:
  static const Parameter<S>& find(const std::string& name) {
    for (const Parameter<S>& p : S::parameters())
      if (name == p.info.name) return p;
    throw InputError("unknown parameter '" + name + "'");
  }
  S& self() { return static_cast<S&>(*this); }
  const S& self() const { return static_cast<const S&>(*this); }
};

}  // namespace obscura
