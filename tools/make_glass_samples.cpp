// obscura-make-glass-samples: writes assets/scenes/glass-samples.glb, a glTF 2.0 sample of what issue 31 added to the
// material model: the transparent layer (effects/transparency: alphaMode BLEND, KHR_materials_transmission), the
// material layers (KHR_materials_clearcoat, _ior, _specular) and KHR_materials_unlit with vertex colours (COLOR_0).
// obscura-bench and the browser benchmark time the transparent pass, transmission and clear coat on it, the docs
// show it (docs/transparency.md), and the glTF-Validator checks it with the rest of the corpus.
//
// Why it exists: Debian's glTF samples have one clear-coat file (ClearCoat-glTF) and no transparency or
// transmission. The scene, metres, +y up:
//   - a floor and a back wall of coloured stripes (a base-colour texture), so what lies behind glass shows;
//   - in front, three glass spheres (transmission 1, ior 1.5) of roughness 0, 0.25 and 0.5;
//   - two overlapping blended panes, red and blue, alpha 0.4, double-sided;
//   - two clear-coated spheres: rough red paint under a smooth coat, brushed blue metal under a half coat (ior 1.8
//     and a tinted specular on the first: KHR_materials_ior and _specular);
//   - an unlit box whose vertex colours run from yellow to magenta.
// Deterministic: the same bytes on every run. Usage: obscura-make-glass-samples OUT.glb
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <tiny_gltf.h>

#include "GltfMeshWriter.h"
#include "scene/Primitives.h"
#include "scene/Scene.h"

using namespace obscura;

namespace {

constexpr int kStripes = 64;

std::vector<unsigned char> stripes() {  // sRGB: six coloured stripes across
  const unsigned char colours[6][3] = {{230, 70, 60},  {240, 200, 60}, {80, 190, 90},
                                       {60, 150, 230}, {150, 90, 210}, {245, 245, 240}};
  std::vector<unsigned char> rgba;
  for (int y = 0; y < kStripes; ++y)
    for (int x = 0; x < kStripes; ++x) {
      const unsigned char* c = colours[(x * 6) / kStripes];
      rgba.insert(rgba.end(), {c[0], c[1], c[2], 255});
    }
  return rgba;
}

tinygltf::Value object(std::initializer_list<std::pair<const char*, tinygltf::Value>> members) {
  tinygltf::Value::Object o;
  for (const auto& [key, value] : members) o[key] = value;
  return tinygltf::Value(o);
}

void build(tools::SampleSceneWriter& w) {
  // The floor, and the back wall's stripes.
  Mesh floor;
  addQuad(floor, {-3, 0, 2}, {3, 0, 2}, {3, 0, -2}, {-3, 0, -2});
  w.mesh(floor, w.material(tools::factorMaterial({0.55f, 0.55f, 0.55f, 1.0f}, 0.0, 0.9)), glm::mat4(1.0f));
  tinygltf::Material wall = tools::factorMaterial({1, 1, 1, 1}, 0.0, 0.8);
  wall.pbrMetallicRoughness.baseColorTexture.index = w.texture("stripes", kStripes, stripes());
  Mesh wallMesh;
  addQuad(wallMesh, {-3, 0, -1}, {3, 0, -1}, {3, 2.2f, -1}, {-3, 2.2f, -1});
  w.mesh(wallMesh, w.material(wall), glm::mat4(1.0f));

  // Glass spheres: transmission 1, ior 1.5 (the default, written out), roughness 0, 0.25, 0.5.
  const Mesh sphere = makeSphere(0.32f, 48, 24);
  for (int i = 0; i < 3; ++i) {
    tinygltf::Material glass = tools::factorMaterial({1, 1, 1, 1}, 0.0, 0.25 * i);
    glass.extensions["KHR_materials_transmission"] = object({{"transmissionFactor", tinygltf::Value(1.0)}});
    glass.extensions["KHR_materials_ior"] = object({{"ior", tinygltf::Value(1.5)}});
    w.mesh(sphere, w.material(glass),
           glm::translate(glm::mat4(1.0f), glm::vec3(-2.0f + 0.8f * static_cast<float>(i), 0.32f, 0.6f)));
  }

  // Two overlapping blended panes, double-sided.
  for (int i = 0; i < 2; ++i) {
    const glm::vec4 colour = i == 0 ? glm::vec4(0.9f, 0.15f, 0.1f, 0.4f) : glm::vec4(0.1f, 0.3f, 0.9f, 0.4f);
    tinygltf::Material pane = tools::factorMaterial(colour, 0.0, 0.1);
    pane.alphaMode = "BLEND";
    pane.doubleSided = true;
    Mesh quad;
    addQuad(quad, {-0.4f, 0, 0}, {0.4f, 0, 0}, {0.4f, 1.0f, 0}, {-0.4f, 1.0f, 0});
    w.mesh(quad, w.material(pane),
           glm::translate(glm::mat4(1.0f), glm::vec3(0.15f + 0.35f * static_cast<float>(i), 0.0f,
                                                     0.2f + 0.35f * static_cast<float>(i))));
  }

  // Clear-coated spheres: rough red paint under a smooth coat (ior 1.8, a warm specular), brushed blue metal under a
  // half coat.
  tinygltf::Material paint = tools::factorMaterial({0.7f, 0.05f, 0.04f, 1}, 0.0, 0.8);
  paint.extensions["KHR_materials_clearcoat"] =
      object({{"clearcoatFactor", tinygltf::Value(1.0)}, {"clearcoatRoughnessFactor", tinygltf::Value(0.05)}});
  paint.extensions["KHR_materials_ior"] = object({{"ior", tinygltf::Value(1.8)}});
  paint.extensions["KHR_materials_specular"] = object(
      {{"specularColorFactor", tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(1.0), tinygltf::Value(0.8),
                                                                      tinygltf::Value(0.6)})}});
  w.mesh(sphere, w.material(paint), glm::translate(glm::mat4(1.0f), glm::vec3(1.3f, 0.32f, 0.5f)));
  tinygltf::Material metal = tools::factorMaterial({0.3f, 0.45f, 0.8f, 1}, 1.0, 0.5);
  metal.extensions["KHR_materials_clearcoat"] =
      object({{"clearcoatFactor", tinygltf::Value(0.5)}, {"clearcoatRoughnessFactor", tinygltf::Value(0.2)}});
  w.mesh(sphere, w.material(metal), glm::translate(glm::mat4(1.0f), glm::vec3(2.1f, 0.32f, 0.3f)));

  // An unlit box with vertex colours, yellow at the bottom to magenta at the top.
  tinygltf::Material unlit = tools::factorMaterial({1, 1, 1, 1}, 0.0, 1.0);
  unlit.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object{});
  Mesh box = makeBox({-0.25f, 0.0f, -0.25f}, {0.25f, 0.5f, 0.25f});
  std::vector<glm::vec4> colours;
  for (const glm::vec3& p : box.positions) colours.push_back(glm::mix(glm::vec4(1, 0.9f, 0.1f, 1),
                                                                      glm::vec4(0.9f, 0.1f, 0.8f, 1), p.y / 0.5f));
  const int node =
      w.mesh(box, w.material(unlit), glm::translate(glm::mat4(1.0f), glm::vec3(-1.3f, 0.0f, -0.5f)));
  tinygltf::Mesh& written = w.model.meshes[static_cast<size_t>(w.model.nodes[static_cast<size_t>(node)].mesh)];
  written.primitives[0].attributes["COLOR_0"] = tools::appendAccessor(
      w.model, colours, TINYGLTF_TARGET_ARRAY_BUFFER, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 || std::strcmp(argv[1], "--help") == 0) {
    std::cerr << "usage: obscura-make-glass-samples OUT.glb   (writes the glass and layers sample; see the source)\n";
    return argc == 2 ? 0 : 2;
  }
  tools::SampleSceneWriter writer("obscura-make-glass-samples (tools/make_glass_samples.cpp); units: metres",
                                  {"KHR_materials_transmission", "KHR_materials_clearcoat", "KHR_materials_ior",
                                   "KHR_materials_specular", "KHR_materials_unlit"});
  build(writer);
  return writer.writeGlb("obscura-make-glass-samples", argv[1],
                         std::to_string(writer.model.meshes.size()) + " meshes, " +
                             std::to_string(writer.model.materials.size()) + " materials");
}
