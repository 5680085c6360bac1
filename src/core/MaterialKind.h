#pragma once
// What a material asks of a geometry pass's fragment stage, which picks the program variant: the defines of
// lib/material.glsl. A program per kind, not a branch per fragment: a material without a texture then neither
// samples one nor decodes its sRGB (on a CPU rasteriser, which runs both sides of a branch, that is a fifth of the
// lighting pass), and an opaque one has no discard, so depth and stencil tests may run before the fragment stage.
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace obscura {

struct MaterialKind {
  bool masked = false;    // alphaMode MASK: cut-out fragments are discarded (ALPHA_MASK 1)
  bool textured = false;  // a base-colour texture to sample (BASE_COLOR_TEXTURE 1); without one, the factor alone

  bool operator<(const MaterialKind& o) const { return std::tie(masked, textured) < std::tie(o.masked, o.textured); }
  bool operator==(const MaterialKind& o) const { return masked == o.masked && textured == o.textured; }

  // The kind as far as a fragment stage that reads the base colour only for the alpha test sees it: an opaque
  // material's texture makes no difference there (one program serves both).
  MaterialKind forAlphaOnly() const { return {masked, masked && textured}; }

  // ",opaque" / ",mask", then ",texture" where textured: for program names.
  std::string nameSuffix() const {
    return std::string(masked ? ",mask" : ",opaque") + (textured ? ",texture" : "");
  }
  std::vector<std::pair<std::string, std::string>> defines() const {
    return {{"ALPHA_MASK", masked ? "1" : "0"}, {"BASE_COLOR_TEXTURE", textured ? "1" : "0"}};
  }
  static std::vector<MaterialKind> all() { return {{false, false}, {false, true}, {true, false}, {true, true}}; }
};

}  // namespace obscura
