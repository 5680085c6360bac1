#pragma once
// What a row of the effect table is made of (renderer/EffectTable.h lists the rows): the resources an effect is
// lent, its settings type-erased, its parameters under their full names, and EffectEntry::of<E>(), which turns an
// effect class into a row. Names no effect.
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <typeindex>
#include <vector>

#include "frame/Effect.h"
#include "frame/FullscreenTriangle.h"
#include "frame/Parameters.h"
#include "frame/ProgramCache.h"
#include "frame/RendererOptions.h"
#include "frame/SurfaceShading.h"
#include "gl/GlCaps.h"
#include "gl/ShaderLibrary.h"

namespace obscura {

// What an effect may use, lent by the Renderer that creates it.
struct EffectResources {
  const gl::GlCaps& caps;
  const RendererOptions& options;
  const FullscreenTriangle& triangle;
  ProgramCache& programs;  // every program of the frame, built on first use (strict with options.checkGlErrors)
  const gl::Program& program(const ProgramSpec& spec) const { return programs.get(spec); }
  // This frame's light and fog for surfaces drawn after the lighting pass (frame/SurfaceShading.h).
  SurfaceShading& surfaces;
  // Builds a program of the effect's own (strict with options.checkGlErrors on).
  gl::Program build(const ProgramSpec& spec) const { return spec.build(options.checkGlErrors); }
};

// One effect's settings, type-erased so RenderSettings can hold every row's.
class EffectSettingsBase {
 public:
  virtual ~EffectSettingsBase() = default;
  virtual std::unique_ptr<EffectSettingsBase> clone() const = 0;
};
template <typename S>
class EffectSettingsOf : public EffectSettingsBase {
 public:
  S value;
  std::unique_ptr<EffectSettingsBase> clone() const override { return std::make_unique<EffectSettingsOf>(*this); }
};

// A parameter of the frame: its documentation under its full name ("ao.radius") and access to its row's settings.
struct ParameterBinding {
  ParameterInfo info;
  size_t row = 0;  // index in effectTable(): set in RenderSettings::parameters() (0 in the table's own entries)
  std::function<void(EffectSettingsBase&, const std::string&)> set;
  std::function<std::string(const EffectSettingsBase&)> get;
  std::function<std::string(const EffectSettingsBase&)> effective;
  std::function<bool(const EffectSettingsBase&, const EffectSettingsBase&)> same;  // Parameter::same, or the texts
};

namespace detail {
template <typename S, typename = void>
struct HasPresets : std::false_type {};
template <typename S>
struct HasPresets<S, std::void_t<decltype(std::declval<S&>().applyPreset(QualityPreset::Medium))>> : std::true_type {};
template <typename E, typename = void>
struct HasStages : std::false_type {};
template <typename E>
struct HasStages<E, std::void_t<decltype(E::stages())>> : std::true_type {};
template <typename E, typename = void>
struct HasStageHeads : std::false_type {};
template <typename E>
struct HasStageHeads<E, std::void_t<decltype(E::stageHeads())>> : std::true_type {};
}  // namespace detail

// A program per-pixel stages fuse into (frame/Stage.h), as fusedProgram takes it, for the shader checks: its fragment
// file's main calls finishPixel; `space`, the colour it hands on; `uniformVectors`, the fragment uniform vectors the
// head keeps for itself (the stages take the rest).
struct StageHeadSpec {
  ProgramSpec program;
  ColorSpace space = ColorSpace::Hdr;
  int uniformVectors = 0;
};

struct EffectEntry {
  EffectInfo info;
  std::type_index settingsType = typeid(void);
  std::function<std::unique_ptr<Effect>(const EffectResources&)> create;
  std::function<std::vector<ProgramSpec>()> programSpecs;  // every program variant it may build
  std::function<std::unique_ptr<EffectSettingsBase>()> defaultSettings;
  std::function<bool(const EffectSettingsBase&)> enabled;  // its switch; always on without one
  std::function<void(const EffectSettingsBase&)> validate;
  std::function<void(EffectSettingsBase&, QualityPreset)> applyPreset;          // empty: no presets
  std::function<bool(const EffectSettingsBase&, QualityPreset)> matchesPreset;  // empty: no presets
  std::function<QualityPreset(const EffectSettingsBase&)> presetOf;             // the preset they came from
  std::vector<ParameterBinding> parameters;                                     // full names, `row` unset
  // Per-pixel stages (frame/Stage.h), for the shader checks: every variant of the stage it declares, and the
  // programs stages fuse into that it runs (a fragment file whose main calls finishPixel, and its colour's space).
  std::function<std::vector<StageDecl>()> stages;
  std::function<std::vector<StageHeadSpec>()> stageHeads;

  // The row of effect class E: E::info(), E::programSpecs(), E(const EffectResources&), and E::Settings with
  // parameters() (local names), validate(), a bool `enabled` when E::kHasSwitch, and optionally presets:
  // applyPreset(QualityPreset), matchesPreset(QualityPreset) and the QualityPreset `preset` they came from; and
  // optionally E::stages() (its stage's variants) and E::stageHeads() (the programs stages fuse into).
  template <typename E>
  static EffectEntry of() {
    using S = typename E::Settings;
    EffectEntry entry;
    entry.info = E::info();
    entry.settingsType = typeid(S);
    entry.create = [](const EffectResources& resources) -> std::unique_ptr<Effect> {
      return std::make_unique<E>(resources);
    };
    entry.programSpecs = [] { return E::programSpecs(); };
    entry.defaultSettings = [] { return std::make_unique<EffectSettingsOf<S>>(); };
    if constexpr (E::kHasSwitch)
      entry.enabled = [](const EffectSettingsBase& s) { return cast<S>(s).enabled; };
    else
      entry.enabled = [](const EffectSettingsBase&) { return true; };
    entry.validate = [](const EffectSettingsBase& s) { cast<S>(s).validate(); };
    if constexpr (detail::HasPresets<S>::value) {
      entry.applyPreset = [](EffectSettingsBase& s, QualityPreset p) { cast<S>(s).applyPreset(p); };
      entry.matchesPreset = [](const EffectSettingsBase& s, QualityPreset p) { return cast<S>(s).matchesPreset(p); };
      entry.presetOf = [](const EffectSettingsBase& s) { return cast<S>(s).preset; };
    }
    if constexpr (detail::HasStages<E>::value) entry.stages = [] { return E::stages(); };
    else entry.stages = [] { return std::vector<StageDecl>{}; };
    if constexpr (detail::HasStageHeads<E>::value) {
      entry.stageHeads = [] { return E::stageHeads(); };
    } else {
      entry.stageHeads = [] { return std::vector<StageHeadSpec>{}; };
    }
    const std::string& effect = entry.info.name;
    for (const Parameter<S>& p : S::parameters()) {
      ParameterBinding binding;
      binding.info = p.info;
      binding.info.effect = effect;
      binding.info.name = p.info.name == effect ? effect : effect + "." + p.info.name;
      binding.set = [p](EffectSettingsBase& s, const std::string& v) { p.set(cast<S>(s), v); };
      binding.get = [p](const EffectSettingsBase& s) { return p.get(cast<S>(s)); };
      binding.effective = [p](const EffectSettingsBase& s) {
        return p.effective ? p.effective(cast<S>(s)) : p.get(cast<S>(s));
      };
      binding.same = [p](const EffectSettingsBase& a, const EffectSettingsBase& b) {
        return p.same ? p.same(cast<S>(a), cast<S>(b)) : p.get(cast<S>(a)) == p.get(cast<S>(b));
      };
      entry.parameters.push_back(std::move(binding));
    }
    return entry;
  }

  template <typename S>
  static S& cast(EffectSettingsBase& s) { return static_cast<EffectSettingsOf<S>&>(s).value; }
  template <typename S>
  static const S& cast(const EffectSettingsBase& s) { return static_cast<const EffectSettingsOf<S>&>(s).value; }
};

// An effect's settings without a parameter: the lines and the velocity, for now.
struct NoSettings : ParameterAccess<NoSettings> {
  static const std::vector<Parameter<NoSettings>>& parameters() {
    static const std::vector<Parameter<NoSettings>> none;
    return none;
  }
  void validate() const {}
};

}  // namespace obscura
