#include "frame/GBufferSettings.h"

namespace obscura {

const std::vector<Parameter<GBufferSettings>>& GBufferSettings::parameters() {
  using S = GBufferSettings;
  static const std::vector<Parameter<S>> table = {
      presetParameter<S>("quality preset: the level of detail (low: gbuffer.lod 0.5, medium: 0.35, high and ultra: 0, "
                         "full detail)",
                         false),  // it sets a number the passes read each frame
      choiceParameter<S, GBufferNormals>(
          "normals", "the AO's surface normal: the G-buffer's, or reconstructed from its depth (docs/accuracy.md)",
          &S::normals, {{"stored", GBufferNormals::Stored}, {"reconstructed", GBufferNormals::Reconstructed}})
          .primary(),  // up front, not under "more"
      numberParameter<S>("lod", 0, 16, "pixels",
                         "level of detail: the largest error of the simplified meshes drawn, in pixels (0: full "
                         "detail)",
                         &S::lod)};
  return table;
}

namespace {
float lodOf(QualityPreset preset) {
  switch (preset) {
    case QualityPreset::Low: return GBufferSettings::kLowPresetLod;
    case QualityPreset::Medium: return GBufferSettings::kMediumPresetLod;
    default: return 0.0f;
  }
}
}  // namespace

void GBufferSettings::applyPreset(QualityPreset which) {
  preset = which;
  lod = lodOf(which);
}

bool GBufferSettings::matchesPreset(QualityPreset which) const { return lod == lodOf(which); }

}  // namespace obscura
