// obscura-make-pbr-samples: writes assets/scenes/pbr-samples.glb, a glTF 2.0 sample of the metallic-roughness
// material model for the lighting pass (effects/lighting/LightingEffect.h, docs/pbr.md): the README's picture, the
// forward shading golden image (tests/test_golden.cpp) and the loader test of every material input
// (tests/test_pbr.cpp).
//
// Why it exists: none of the glTF files Debian ships (/usr/share/assimp/models/glTF2) has metallic-roughness,
// normal, occlusion and emissive textures together with KHR_lights_punctual, so the sample is generated here and
// written as an ordinary binary glTF that reaches the renderer through the same loader as any user's file:
//   - two rows of five spheres, roughness 0.1 .. 1.0: a red dielectric in front, gold behind (factors only);
//   - a floor of tiles: a normal texture (bevelled tile edges) and an occlusion texture (dark grout) sharing one
//     KHR_texture_transform that repeats them 6 x 4 times; its tangents are left to the loader (MikkTSpace);
//   - a back wall whose metallicRoughness texture alternates polished metal and rough paint stripes;
//   - an emissive panel (emissiveTexture x emissiveFactor x KHR_materials_emissive_strength 8: brighter than 1);
//   - KHR_lights_punctual: a warm point light with a range and a cool spot light.
// Units: metres, +y up. Deterministic: the same bytes on every run. Usage: obscura-make-pbr-samples OUT.glb
#include <algorithm>
#include <cmath>
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

constexpr int kTextureSize = 64;

// --- The textures, RGBA8 ---
std::vector<unsigned char> tileNormals() {  // a bevel 6 texels wide around each tile; flat inside
  std::vector<unsigned char> rgba;
  const auto last = static_cast<float>(kTextureSize - 1);
  for (int row = 0; row < kTextureSize; ++row)
    for (int column = 0; column < kTextureSize; ++column) {
      const float bevel = 6.0f, x = static_cast<float>(column), y = static_cast<float>(row);
      float nx = 0.0f, ny = 0.0f;
      if (x < bevel) nx = -0.6f * (1.0f - x / bevel);
      if (x > last - bevel) nx = 0.6f * (1.0f - (last - x) / bevel);
      if (y < bevel) ny = -0.6f * (1.0f - y / bevel);
      if (y > last - bevel) ny = 0.6f * (1.0f - (last - y) / bevel);
      const float nz = std::sqrt(std::max(0.0f, 1.0f - nx * nx - ny * ny));
      for (float c : {nx, ny, nz}) rgba.push_back(static_cast<unsigned char>(std::lround((c * 0.5f + 0.5f) * 255)));
      rgba.push_back(255);
    }
  return rgba;
}

std::vector<unsigned char> groutOcclusion() {  // R: 0.25 in the grout, rising to 1 over the bevel
  std::vector<unsigned char> rgba;
  for (int y = 0; y < kTextureSize; ++y)
    for (int x = 0; x < kTextureSize; ++x) {
      const int edge = std::min(std::min(x, kTextureSize - 1 - x), std::min(y, kTextureSize - 1 - y));
      const float occlusion = edge < 2 ? 0.25f : std::min(1.0f, 0.25f + 0.75f * static_cast<float>(edge - 1) / 7.0f);
      const auto r = static_cast<unsigned char>(std::lround(occlusion * 255));
      rgba.insert(rgba.end(), {r, r, r, 255});
    }
  return rgba;
}

std::vector<unsigned char> stripesMetallicRoughness() {  // G roughness, B metallic: polished metal | rough paint
  std::vector<unsigned char> rgba;
  for (int y = 0; y < kTextureSize; ++y)
    for (int x = 0; x < kTextureSize; ++x) {
      const bool metal = (x / 16) % 2 == 0;
      const auto roughness = static_cast<unsigned char>(metal ? 40 : 230);
      const auto metallic = static_cast<unsigned char>(metal ? 255 : 0);
      rgba.insert(rgba.end(), {0, roughness, metallic, 255});
    }
  return rgba;
}

std::vector<unsigned char> emissiveGrid() {  // sRGB: a bright grid of lines on black
  std::vector<unsigned char> rgba;
  for (int y = 0; y < kTextureSize; ++y)
    for (int x = 0; x < kTextureSize; ++x) {
      const bool line = x % 16 < 3 || y % 16 < 3;
      const unsigned char v = line ? 255 : 0;
      rgba.insert(rgba.end(), {v, v, v, 255});
    }
  return rgba;
}

tinygltf::Value transform(float scaleU, float scaleV) {
  tinygltf::Value::Object t;
  t["scale"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(scaleU), tinygltf::Value(scaleV)});
  return tinygltf::Value(t);
}

void build(tools::SampleSceneWriter& w) {
  // The spheres: a red dielectric row in front, a gold row behind, roughness 0.1 .. 1.0 from left to right.
  const Mesh sphere = makeSphere(0.35f, 48, 24);
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < 5; ++i) {
      const double roughness = 0.1 + 0.225 * i;
      const int material = w.material(row == 0 ? tools::factorMaterial({0.80f, 0.12f, 0.08f, 1.0f}, 0.0, roughness)
                                               : tools::factorMaterial({1.00f, 0.77f, 0.34f, 1.0f}, 1.0, roughness));
      w.mesh(sphere, material,
             glm::translate(glm::mat4(1.0f),
                            glm::vec3(-1.8f + 0.9f * static_cast<float>(i), 0.35f, row == 0 ? 0.7f : -0.3f)));
    }

  // The floor: tiles (normal and occlusion textures, repeated 6 x 4 by one KHR_texture_transform).
  tinygltf::Material floor = tools::factorMaterial({0.55f, 0.53f, 0.50f, 1.0f}, 0.0, 0.7);
  floor.normalTexture.index = w.texture("tile normals", kTextureSize, tileNormals());
  floor.normalTexture.extensions["KHR_texture_transform"] = transform(6.0f, 4.0f);
  floor.occlusionTexture.index = w.texture("grout occlusion", kTextureSize, groutOcclusion());
  floor.occlusionTexture.extensions["KHR_texture_transform"] = transform(6.0f, 4.0f);
  Mesh floorMesh;
  addQuad(floorMesh, {-3, 0, 2}, {3, 0, 2}, {3, 0, -2}, {-3, 0, -2});
  w.mesh(floorMesh, w.material(floor), glm::mat4(1.0f));

  // The back wall: polished metal and rough paint stripes (a metallicRoughness texture), repeated 4 times across.
  tinygltf::Material wall = tools::factorMaterial({0.70f, 0.72f, 0.75f, 1.0f}, 1.0, 1.0);
  wall.pbrMetallicRoughness.metallicRoughnessTexture.index =
      w.texture("metal stripes", kTextureSize, stripesMetallicRoughness());
  wall.pbrMetallicRoughness.metallicRoughnessTexture.extensions["KHR_texture_transform"] = transform(4.0f, 1.0f);
  Mesh wallMesh;
  addQuad(wallMesh, {-3, 0, -1}, {3, 0, -1}, {3, 2.2f, -1}, {-3, 2.2f, -1});
  w.mesh(wallMesh, w.material(wall), glm::mat4(1.0f));

  // The emissive panel on the wall, brighter than 1 (KHR_materials_emissive_strength).
  tinygltf::Material panel = tools::factorMaterial({0.05f, 0.05f, 0.05f, 1.0f}, 0.0, 0.5);
  panel.emissiveFactor = {1.0, 0.55, 0.2};
  panel.emissiveTexture.index = w.texture("emissive grid", kTextureSize, emissiveGrid());
  tinygltf::Value::Object strength;
  strength["emissiveStrength"] = tinygltf::Value(8.0);
  panel.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(strength);
  Mesh panelMesh;
  addQuad(panelMesh, {1.6f, 1.2f, -0.98f}, {2.6f, 1.2f, -0.98f}, {2.6f, 1.9f, -0.98f}, {1.6f, 1.9f, -0.98f});
  w.mesh(panelMesh, w.material(panel), glm::mat4(1.0f));

  // The lights: a warm point light over the spheres, a cool spot light from the left aimed at the floor.
  tinygltf::Light point;
  point.type = "point";
  point.color = {1.0, 0.78, 0.55};
  point.intensity = 6.0;
  point.range = 5.0;
  w.light(point, glm::translate(glm::mat4(1.0f), glm::vec3(0.4f, 1.6f, 0.9f)));
  tinygltf::Light spot;
  spot.type = "spot";
  spot.color = {0.55, 0.75, 1.0};
  spot.intensity = 30.0;
  spot.spot.innerConeAngle = 0.25;
  spot.spot.outerConeAngle = 0.45;
  // At (-2.6, 2.4, 1.6), its -z turned towards (-1.2, 0, 0.2).
  const glm::vec3 from(-2.6f, 2.4f, 1.6f), to(-1.2f, 0.0f, 0.2f);
  w.light(spot, glm::inverse(glm::lookAt(from, to, glm::vec3(0, 1, 0))));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 || std::strcmp(argv[1], "--help") == 0) {
    std::cerr << "usage: obscura-make-pbr-samples OUT.glb   (writes the metallic-roughness sample; see the source)\n";
    return argc == 2 ? 0 : 2;
  }
  tools::SampleSceneWriter writer("obscura-make-pbr-samples (tools/make_pbr_samples.cpp); units: metres",
                                  {"KHR_texture_transform", "KHR_materials_emissive_strength", "KHR_lights_punctual"});
  build(writer);
  return writer.writeGlb("obscura-make-pbr-samples", argv[1],
                         std::to_string(writer.model.meshes.size()) + " meshes, " +
                             std::to_string(writer.model.textures.size()) + " textures, " +
                             std::to_string(writer.model.lights.size()) + " lights");
}
