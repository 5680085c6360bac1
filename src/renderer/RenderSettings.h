#pragma once
// What a frame draws: the settings of every effect of the table (renderer/EffectTable.h), set and read by name.
//
// Names: an effect's switch is its name ("ao", "tonemap", "fxaa"), its parameters are "NAME.PARAM" ("ao.radius",
// "tonemap.exposure"). "preset" is the frame's quality preset: it sets the preset of every effect that has presets
// ("ao.preset", "fxaa.preset"). Older names stay accepted as aliases wherever a name is taken (the AO's parameters
// from before effects had prefixes: "radius", "samples", ...), so existing URLs, scripts and tests keep working.
#include <memory>
#include <optional>
#include <string>
#include <typeindex>
#include <vector>

#include "effects/ao/AoSettings.h"
#include "frame/FrameSettings.h"
#include "renderer/EffectTable.h"

namespace obscura {

class RenderSettings : public FrameSettings {
 public:
  RenderSettings();  // every effect at its defaults
  // Every effect at its defaults, with these AO settings (the tests' and tools' common case: an AoSettings converts
  // where RenderSettings are expected).
  RenderSettings(const AoSettings& ao);  // NOLINT(google-explicit-constructor)
  // Every effect that has a switch turned on, each at its defaults (the frame the table must plan, the tests' and
  // benchmarks' "every effect on").
  static RenderSettings everyEffectOn();
  RenderSettings(const RenderSettings&) = default;
  RenderSettings& operator=(const RenderSettings&) = default;
  RenderSettings(RenderSettings&&) noexcept = default;
  RenderSettings& operator=(RenderSettings&&) noexcept = default;

  AoSettings& ao() { return of<AoSettings>(); }
  const AoSettings& ao() const { return of<AoSettings>(); }
  // One effect's settings by the effect's name, type-erased (EffectEntry's functions take them).
  const EffectSettingsBase& row(const std::string& effect) const;

  // Whether the effect of that name is on (effects without a switch always are). Throws InputError if unknown.
  bool enabled(const std::string& effect) const;
  bool enabled(size_t row) const;

  // Sets a parameter from text (full name, alias, or "preset"). Throws InputError naming the parameter, the value
  // and the accepted range when the name is unknown or the value is out of range; the settings are unchanged then.
  void set(const std::string& name, const std::string& value);
  // The value as text that set() accepts. For "preset" (and "ao.preset", ...): the preset whose values the
  // settings hold, or "" when they match none.
  std::string get(const std::string& name) const;
  // The value in use: get(name), except where the settings resolve it (the AO's "auto" estimator parameters).
  std::string effective(const std::string& name) const;
  // Throws InputError if any effect's settings are out of range (settings built in code).
  void validate() const;

  // Applies a preset to every effect that has presets.
  void applyPreset(QualityPreset preset);
  // The preset every effect with presets holds the values of, if they agree.
  std::optional<QualityPreset> preset() const;

  // Every parameter of the frame, full names: "preset", then each effect's in table order.
  static const std::vector<ParameterInfo>& parameters();
  // The full name for a full name or an alias ("radius" -> "ao.radius"); throws InputError if neither.
  static std::string canonicalName(const std::string& name);
  // The parameter of that name or alias, or null.
  static const ParameterInfo* find(const std::string& name);

};

}  // namespace obscura
