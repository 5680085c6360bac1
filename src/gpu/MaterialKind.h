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
  // Metallic-roughness, normal, occlusion or emissive textures to sample (PBR_TEXTURES 1: all four, a missing one
  // bound to a neutral texel; the vertex stage adds the tangent frame and each slot's transformed coordinates).
  bool pbr = false;
  bool unlit = false;         // KHR_materials_unlit: the base colour is the colour (UNLIT 1)
  bool layered = false;       // KHR_materials_ior, _specular, _clearcoat (MATERIAL_LAYERS 1: Material::layered)
  bool transmission = false;  // KHR_materials_transmission (TRANSMISSION 1: effects/transparency draws it)

  auto key() const { return std::tie(masked, textured, pbr, unlit, layered, transmission); }
  bool operator<(const MaterialKind& o) const { return key() < o.key(); }
  bool operator==(const MaterialKind& o) const { return key() == o.key(); }

  // The kind as far as a fragment stage that reads the base colour only for the alpha test sees it: an opaque
  // material's texture makes no difference there (one program serves both), nor do the other textures.
  MaterialKind forAlphaOnly() const { return {masked, masked && textured, false}; }
  // The kind as far as the base colour goes (the G-buffer pass's base-colour target): no shading variant.
  MaterialKind forBaseColor() const { return {masked, textured, pbr}; }
  // A kind beyond the core material (the lighting builds these on first use, not when it is made).
  bool extended() const { return unlit || layered || transmission; }

  // ",opaque" / ",mask", then ",texture" where textured, ",pbr" where pbr, ",unlit", ",layers", ",transmission":
  // for program names.
  std::string nameSuffix() const {
    return std::string(masked ? ",mask" : ",opaque") + (textured ? ",texture" : "") + (pbr ? ",pbr" : "") +
           (unlit ? ",unlit" : "") + (layered ? ",layers" : "") + (transmission ? ",transmission" : "");
  }
  std::vector<std::pair<std::string, std::string>> defines() const {
    return {{"ALPHA_MASK", masked ? "1" : "0"},
            {"BASE_COLOR_TEXTURE", textured ? "1" : "0"},
            {"PBR_TEXTURES", pbr ? "1" : "0"},
            {"UNLIT", unlit ? "1" : "0"},
            {"MATERIAL_LAYERS", layered ? "1" : "0"},
            {"TRANSMISSION", transmission ? "1" : "0"}};
  }
  // The opaque layer's kinds: the core eight, the unlit ones (an unlit material reads no other texture, so no pbr
  // and no layers) and the layered ones. Transmission is the transparent layer's (transparentKinds).
  static std::vector<MaterialKind> all() {
    std::vector<MaterialKind> kinds;
    for (bool layered : {false, true})
      for (bool pbr : {false, true})
        for (bool masked : {false, true})
          for (bool textured : {false, true}) kinds.push_back({masked, textured, pbr, false, layered, false});
    for (bool masked : {false, true})
      for (bool textured : {false, true}) kinds.push_back({masked, textured, false, true, false, false});
    return kinds;
  }
  // The transparent layer's kinds (effects/transparency): blended, not masked; with or without transmission.
  static std::vector<MaterialKind> transparentKinds() {
    std::vector<MaterialKind> kinds;
    for (bool transmission : {false, true})
      for (bool layered : {false, true})
        for (bool pbr : {false, true})
          for (bool textured : {false, true}) kinds.push_back({false, textured, pbr, false, layered, transmission});
    for (bool textured : {false, true}) kinds.push_back({false, textured, false, true, false, false});
    return kinds;
  }
};

}  // namespace obscura
