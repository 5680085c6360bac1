#pragma once
// Every effect's settings for one frame, found by the type of their struct: what effects read while they plan
// (`planner.settings().of<FogSettings>()`). renderer/RenderSettings fills one row per row of the effect table and
// adds access by name (parameters, presets, validation), which needs the table; the frame needs only this.
#include <memory>
#include <string>
#include <typeindex>
#include <vector>

#include "base/Error.h"
#include "frame/EffectEntry.h"

namespace obscura {

class FrameSettings {
 public:
  // One effect's settings struct, by type (the type of its table row's settings).
  template <typename S>
  S& of() {
    return EffectEntry::cast<S>(*rows_[rowOf(typeid(S))]);
  }
  template <typename S>
  const S& of() const {
    return EffectEntry::cast<S>(*rows_[rowOf(typeid(S))]);
  }
  // The settings of the table's row `index`, type-erased (EffectEntry's functions take them).
  const EffectSettingsBase& rowAt(size_t index) const { return *rows_[index]; }

 protected:
  FrameSettings() = default;
  FrameSettings(const FrameSettings& other) : types_(other.types_) {
    for (const auto& row : other.rows_) rows_.push_back(row->clone());
  }
  FrameSettings& operator=(const FrameSettings& other) {
    if (this != &other) {
      FrameSettings copy(other);
      *this = std::move(copy);
    }
    return *this;
  }
  FrameSettings(FrameSettings&&) noexcept = default;
  FrameSettings& operator=(FrameSettings&&) noexcept = default;
  ~FrameSettings() = default;

  void addRow(std::type_index type, std::unique_ptr<EffectSettingsBase> settings) {
    types_.push_back(type);
    rows_.push_back(std::move(settings));
  }
  size_t rowOf(std::type_index type) const {
    for (size_t row = 0; row < types_.size(); ++row)
      if (types_[row] == type) return row;
    throw PipelineError(std::string("no effect of the frame has settings of type ") + type.name());
  }

  std::vector<std::type_index> types_;                      // one per table row
  std::vector<std::unique_ptr<EffectSettingsBase>> rows_;  // one per table row
};

}  // namespace obscura
