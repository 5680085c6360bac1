#include "renderer/RenderSettings.h"

#include <map>

namespace obscura {
namespace {

const char* const kPreset = "preset";

// Every parameter binding of the table, with its row, by full name and by alias.
struct Bindings {
  std::vector<const ParameterBinding*> ordered;
  std::map<std::string, const ParameterBinding*> byName;
  std::vector<ParameterBinding> storage;
};

const Bindings& bindings() {
  static const Bindings table = [] {
    Bindings b;
    const std::vector<EffectEntry>& rows = effectTable();
    for (size_t row = 0; row < rows.size(); ++row)
      for (ParameterBinding binding : rows[row].parameters) {
        binding.row = row;
        b.storage.push_back(std::move(binding));
      }
    for (const ParameterBinding& binding : b.storage) {
      b.ordered.push_back(&binding);
      for (const std::string& name : {binding.info.name, binding.info.alias}) {
        if (name.empty()) continue;
        if (name == kPreset || !b.byName.emplace(name, &binding).second)
          throw PipelineError("parameter name '" + name + "' is used twice in the effect table");
      }
    }
    return b;
  }();
  return table;
}

const ParameterBinding& binding(const std::string& name) {
  const auto it = bindings().byName.find(name);
  if (it == bindings().byName.end()) throw InputError("unknown parameter '" + name + "'");
  return *it->second;
}

// Messages name the parameter as the user wrote it.
template <typename Body>
auto naming(const std::string& written, const ParameterBinding& b, Body&& body) {
  try {
    return body();
  } catch (const InputError& e) {
    const std::string message = e.what();
    // The effects' own messages start with the local name ("radius: ..."): show the name that was used.
    const std::string local = b.info.name == b.info.effect ? b.info.effect
                                                           : b.info.name.substr(b.info.effect.size() + 1);
    if (written != local && message.rfind(local + ":", 0) == 0)
      throw InputError(written + message.substr(local.size()));
    throw;
  }
}

}  // namespace

RenderSettings::RenderSettings() {
  for (const EffectEntry& row : effectTable()) addRow(row.settingsType, row.defaultSettings());
}

RenderSettings::RenderSettings(const AoSettings& ao) : RenderSettings() { this->ao() = ao; }

RenderSettings RenderSettings::everyEffectOn() {
  RenderSettings settings;
  for (const EffectEntry& row : effectTable())
    if (row.info.hasSwitch) settings.set(row.info.name, "on");
  return settings;
}

bool RenderSettings::enabled(const std::string& effect) const {
  const std::vector<EffectEntry>& rows = effectTable();
  for (size_t row = 0; row < rows.size(); ++row)
    if (rows[row].info.name == effect) return enabled(row);
  throw InputError("unknown effect '" + effect + "'");
}

const EffectSettingsBase& RenderSettings::row(const std::string& effect) const {
  const std::vector<EffectEntry>& rows = effectTable();
  for (size_t row = 0; row < rows.size(); ++row)
    if (rows[row].info.name == effect) return *rows_[row];
  throw InputError("unknown effect '" + effect + "'");
}

bool RenderSettings::enabled(size_t row) const { return effectTable()[row].enabled(*rows_[row]); }

void RenderSettings::set(const std::string& name, const std::string& value) {
  if (name == kPreset) {
    applyPreset(parsePreset(value));
    return;
  }
  const ParameterBinding& b = binding(name);
  naming(name, b, [&] {
    // On a copy: a refused value leaves these settings as they were.
    std::unique_ptr<EffectSettingsBase> changed = rows_[b.row]->clone();
    b.set(*changed, value);
    rows_[b.row] = std::move(changed);
  });
}

std::string RenderSettings::get(const std::string& name) const {
  if (name == kPreset) {
    const std::optional<QualityPreset> p = preset();
    return p ? presetName(*p) : "";
  }
  const ParameterBinding& b = binding(name);
  return b.get(*rows_[b.row]);
}

std::string RenderSettings::effective(const std::string& name) const {
  if (name == kPreset) return get(name);
  const ParameterBinding& b = binding(name);
  return b.effective(*rows_[b.row]);
}

void RenderSettings::validate() const {
  const std::vector<EffectEntry>& rows = effectTable();
  for (size_t row = 0; row < rows.size(); ++row) rows[row].validate(*rows_[row]);
}

void RenderSettings::applyPreset(QualityPreset preset) {
  const std::vector<EffectEntry>& rows = effectTable();
  for (size_t row = 0; row < rows.size(); ++row)
    if (rows[row].applyPreset) rows[row].applyPreset(*rows_[row], preset);
}

std::optional<QualityPreset> RenderSettings::preset() const {
  const std::vector<EffectEntry>& rows = effectTable();
  for (QualityPreset candidate : allQualityPresets()) {
    bool all = true;
    for (size_t row = 0; row < rows.size(); ++row)
      if (rows[row].matchesPreset && !rows[row].matchesPreset(*rows_[row], candidate)) all = false;
    if (all) return candidate;
  }
  return std::nullopt;
}

const std::vector<ParameterInfo>& RenderSettings::parameters() {
  static const std::vector<ParameterInfo> infos = [] {
    std::vector<std::string> names;
    for (QualityPreset p : allQualityPresets()) names.push_back(presetName(p));
    std::string effects;
    for (const EffectEntry& row : effectTable())
      if (row.applyPreset) effects += (effects.empty() ? "" : ", ") + row.info.name;
    std::vector<ParameterInfo> out;
    ParameterInfo preset{kPreset, parse::joinChoices(names, " | "), "quality preset of every effect that has one (" +
                         effects + ")", ParameterKind::Choice, 0.0, 0.0, names};
    preset.primary = true;
    out.push_back(preset);
    for (const ParameterBinding* b : bindings().ordered) out.push_back(b->info);
    return out;
  }();
  return infos;
}

const ParameterInfo* RenderSettings::find(const std::string& name) {
  if (name == kPreset) return &parameters().front();
  const auto it = bindings().byName.find(name);
  return it == bindings().byName.end() ? nullptr : &it->second->info;
}

std::string RenderSettings::canonicalName(const std::string& name) {
  if (name == kPreset) return name;
  return binding(name).info.name;
}

}  // namespace obscura
