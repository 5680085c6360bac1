#pragma once
// Writing meshes into a glTF 2.0 model with tinygltf, for the tools that make sample scenes (obscura-make-room,
// obscura-make-pbr-samples, obscura-make-glass-samples): each array one buffer view of buffer 0 (4-byte aligned) and
// one accessor; a mesh one primitive, one glTF mesh and one node placed by a matrix. SampleSceneWriter adds the
// materials, square RGBA8 textures, lights and nodes of one scene, and writes it as a .glb.
#include <cstdio>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

#include "scene/Scene.h"

namespace obscura::tools {

template <typename T>
int appendView(tinygltf::Model& model, const std::vector<T>& data, int target) {
  std::vector<unsigned char>& buffer = model.buffers[0].data;
  while (buffer.size() % 4) buffer.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = data.size() * sizeof(T);
  view.target = target;
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  buffer.insert(buffer.end(), bytes, bytes + view.byteLength);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

// `data` as one accessor of its size.
template <typename T>
int appendAccessor(tinygltf::Model& model, const std::vector<T>& data, int target, int componentType, int type) {
  tinygltf::Accessor accessor;
  accessor.bufferView = appendView(model, data, target);
  accessor.componentType = componentType;
  accessor.type = type;
  accessor.count = data.size();
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size()) - 1;
}

// The mesh's positions (with their bounds, as glTF requires), normals, texture coordinates if `texcoords`, and 32-bit
// indices as triangles of `material`, in a node placed by `world`. Returns the node's index (the caller adds it to a
// scene).
inline int appendMeshNode(tinygltf::Model& model, const Mesh& mesh, int material, const glm::mat4& world,
                          bool texcoords) {
  tinygltf::Primitive primitive;
  const int positions = appendAccessor(model, mesh.positions, TINYGLTF_TARGET_ARRAY_BUFFER,
                                       TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3);
  Bounds bounds;
  for (const glm::vec3& p : mesh.positions) bounds.add(p);
  model.accessors[static_cast<size_t>(positions)].minValues = {bounds.min.x, bounds.min.y, bounds.min.z};
  model.accessors[static_cast<size_t>(positions)].maxValues = {bounds.max.x, bounds.max.y, bounds.max.z};
  primitive.attributes["POSITION"] = positions;
  primitive.attributes["NORMAL"] = appendAccessor(model, mesh.normals, TINYGLTF_TARGET_ARRAY_BUFFER,
                                                  TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3);
  if (texcoords)
    primitive.attributes["TEXCOORD_0"] = appendAccessor(model, mesh.texcoords, TINYGLTF_TARGET_ARRAY_BUFFER,
                                                        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2);
  primitive.indices = appendAccessor(model, mesh.indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER,
                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR);
  primitive.material = material;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh gltfMesh;
  gltfMesh.primitives.push_back(primitive);
  model.meshes.push_back(gltfMesh);
  tinygltf::Node node;
  node.mesh = static_cast<int>(model.meshes.size()) - 1;
  node.matrix.assign(&world[0][0], &world[0][0] + 16);
  model.nodes.push_back(node);
  return static_cast<int>(model.nodes.size()) - 1;
}

// A material of base colour, metallic and roughness factors; the caller adds textures and extensions.
inline tinygltf::Material factorMaterial(const glm::vec4& base, double metallic, double roughness) {
  tinygltf::Material m;
  m.pbrMetallicRoughness.baseColorFactor = {base.r, base.g, base.b, base.a};
  m.pbrMetallicRoughness.metallicFactor = metallic;
  m.pbrMetallicRoughness.roughnessFactor = roughness;
  return m;
}

// One sample scene: buffer 0, one repeating trilinear sampler, and scene 0 holding every node added.
struct SampleSceneWriter {
  tinygltf::Model model;
  tinygltf::Scene root;

  SampleSceneWriter(const std::string& generator, std::vector<std::string> extensionsUsed) {
    model.asset.version = "2.0";
    model.asset.generator = generator;
    model.buffers.resize(1);
    model.extensionsUsed = std::move(extensionsUsed);
    tinygltf::Sampler repeat;
    repeat.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    repeat.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    model.samplers.push_back(repeat);
  }

  // A `side` x `side` RGBA8 image (stored as PNG) and its texture; returns the texture's index.
  int texture(const std::string& name, int side, std::vector<unsigned char> rgba) {
    tinygltf::Image image;
    image.name = name;
    image.width = image.height = side;
    image.component = 4;
    image.bits = 8;
    image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image.image = std::move(rgba);
    image.mimeType = "image/png";
    model.images.push_back(image);
    tinygltf::Texture texture;
    texture.source = static_cast<int>(model.images.size()) - 1;
    texture.sampler = 0;
    model.textures.push_back(texture);
    return static_cast<int>(model.textures.size()) - 1;
  }

  int material(tinygltf::Material m) {
    model.materials.push_back(std::move(m));
    return static_cast<int>(model.materials.size()) - 1;
  }

  // The mesh (with texture coordinates) as a node of the scene; returns the node's index.
  int mesh(const Mesh& mesh, int material, const glm::mat4& world) {
    const int node = appendMeshNode(model, mesh, material, world, true);
    root.nodes.push_back(node);
    return node;
  }

  // A KHR_lights_punctual light in a node of the scene placed by `world`.
  void light(tinygltf::Light light, const glm::mat4& world) {
    model.lights.push_back(std::move(light));
    tinygltf::Node node;
    tinygltf::Value::Object reference;
    reference["light"] = tinygltf::Value(static_cast<int>(model.lights.size()) - 1);
    node.extensions["KHR_lights_punctual"] = tinygltf::Value(reference);
    node.matrix.assign(&world[0][0], &world[0][0] + 16);
    model.nodes.push_back(node);
    root.nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
  }

  // Scene 0 as the default, written as a .glb with embedded images and buffers; prints what it wrote (`summary`) and
  // returns the tool's exit status.
  int writeGlb(const std::string& tool, const std::string& path, const std::string& summary) {
    model.scenes.push_back(root);
    model.defaultScene = 0;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToFile(&model, path, true, true, false, true)) {
      std::cerr << tool << ": cannot write " << path << "\n";
      return 1;
    }
    std::printf("%s: wrote %s (%s)\n", tool.c_str(), path.c_str(), summary.c_str());
    return 0;
  }
};

}  // namespace obscura::tools
