#include "frame/GBufferSettings.h"

namespace obscura {

const std::vector<Parameter<GBufferSettings>>& GBufferSettings::parameters() {
  using S = GBufferSettings;
  static const std::vector<Parameter<S>> table = {
      choiceParameter<S, GBufferNormals>(
          "normals", "the AO's surface normal: the G-buffer's, or reconstructed from its depth (docs/accuracy.md)",
          &S::normals, {{"stored", GBufferNormals::Stored}, {"reconstructed", GBufferNormals::Reconstructed}})
          .primary()};  // the section's one parameter: up front, not under "more"
  return table;
}

}  // namespace obscura
