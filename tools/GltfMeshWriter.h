#pragma once
// Writing meshes into a glTF 2.0 model with tinygltf, for the tools that make sample scenes (obscura-make-room,
// obscura-make-pbr-samples): each array one buffer view of buffer 0 (4-byte aligned) and one accessor; a mesh one
// primitive, one glTF mesh and one node placed by a matrix.
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

}  // namespace obscura::tools
