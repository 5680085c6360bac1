#pragma once
// The glTF loader's parts (scene/GltfLoader.h is the interface), one file per thing it reads:
// - GltfAccessors.cpp: buffer views and accessors, bounds checked before anything is allocated;
// - GltfMeshes.cpp: primitives as meshes (triangles, skin attributes, morph targets) or as points and lines;
// - GltfMaterials.cpp: images, textures, materials and their texture transforms;
// - GltfNodes.cpp: the default scene's hierarchy, the instances it places, skins and lights;
// - GltfAnimations.cpp: animations, whose channels name the nodes collected;
// - GltfLoader.cpp: the file (resolving side files, decoding images, required extensions) and the order of the above.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "base/Error.h"
#include "scene/GltfLoader.h"
#include "scene/Scene.h"

namespace obscura::gltf {

// Everything that can go wrong names the file first, then the glTF object, then the problem.
class Refusal {
 public:
  explicit Refusal(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void operator()(const std::string& problem) const { throw InputError(file_ + ": " + problem); }

 private:
  std::string file_;
};

// What the scene has read so far against the limits that span many accessors (GltfLimits).
struct LoadBudget {
  std::uint64_t morphTargetVertices = 0;
  std::uint64_t animationValues = 0;
};

struct LoaderContext {
  const tinygltf::Model& model;
  const GltfLimits& limits;
  Refusal refuse;
  GltfLoadReport& report;
  LoadBudget& budget;
};

// --- GltfAccessors.cpp ---
int componentSize(int componentType);
int componentCount(int type);
const char* componentTypeName(int componentType);

// Reads an accessor into doubles (count x components), validating every bound. `allowed` lists the component types
// this use permits; `components` the element width it needs.
std::vector<double> readAccessor(const LoaderContext& ctx, int accessorIndex, const std::string& use, int components,
                                 const std::vector<int>& allowed);

// A vertex attribute in the component types its use allows: glTF 2.0's (3.7.2.1), widened by KHR_mesh_quantization
// when the file uses it (GltfCompression.h). Integer types read as integers unless the accessor is normalized.
std::vector<double> readVertexAttribute(const LoaderContext& ctx, int accessorIndex, const std::string& what,
                                        int components, const char* use);

template <int N>
std::vector<glm::vec<N, float>> toVectors(const std::vector<double>& flat) {
  std::vector<glm::vec<N, float>> out(flat.size() / N);
  for (size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < N; ++c) out[i][c] = static_cast<float>(flat[i * N + c]);
  return out;
}

int attributeAccessor(const tinygltf::Primitive& primitive, const char* name);
bool allFinite(const std::vector<double>& values);

// --- GltfMeshes.cpp ---
// One glTF primitive as a Mesh. `readSkin`: keep JOINTS_0 / WEIGHTS_0 (the node placing it has a skin). Sets
// `skipped` for points and lines, which loadLinePrimitive reads.
Mesh loadPrimitive(const LoaderContext& ctx, const tinygltf::Primitive& primitive, const std::string& what,
                   bool readSkin, bool* skipped);
// A POINTS, LINES, LINE_LOOP or LINE_STRIP primitive as a LineMesh.
LineMesh loadLinePrimitive(const LoaderContext& ctx, const tinygltf::Primitive& primitive, const std::string& what);
std::vector<glm::vec4> readColors(const LoaderContext& ctx, const tinygltf::Primitive& primitive,
                                  const std::string& what, size_t vertexCount);

// --- GltfMaterials.cpp ---
void loadMaterials(const LoaderContext& ctx, Scene& scene);
const tinygltf::Material* materialOf(const LoaderContext& ctx, int materialIndex);
// Where a material has no texture besides the base colour's, the loader bakes the base colour's coordinates (its set
// through its KHR_texture_transform) into the mesh's TEXCOORD_0: the vertex stage then reads them as they are.
struct BakedBaseColorUv {
  glm::mat3 transform{1.0f};
  int texCoord = 0;  // the set the base colour samples
};
BakedBaseColorUv baseColorUvToBake(const LoaderContext& ctx, int materialIndex, const std::string& what);
// The set the normal texture samples (its tangents follow that set's gradients).
int normalTextureTexCoord(const tinygltf::Material& material);
// Some slot the loader keeps samples TEXCOORD_1.
bool usesTexCoord1(const tinygltf::Material& material);
// How many texture coordinate sets a material's textures sample: 0 (none), 1 (TEXCOORD_0), 2 (TEXCOORD_1 too).
int texCoordSetsSampled(const LoaderContext& ctx, int materialIndex);

// --- GltfNodes.cpp ---
// The default scene's nodes (parents before children), the instances and lights they place, the skins those need.
// Returns, per glTF node, its Scene::nodes indices (several where it is reached by several paths).
std::vector<std::vector<int>> loadNodes(const LoaderContext& ctx, Scene& scene);

// --- GltfAnimations.cpp ---
// Every animation, its channels on the Scene nodes `copies` maps each glTF node to.
void loadAnimations(const LoaderContext& ctx, const std::vector<std::vector<int>>& copies, Scene& scene);

}  // namespace obscura::gltf
