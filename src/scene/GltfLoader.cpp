#include "scene/GltfLoader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <set>
#include <string_view>
#include <tuple>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <stb_image.h>
#include <tiny_gltf.h>

#include "base/Error.h"
#include "scene/GltfCompression.h"
#include "scene/MeshProcessing.h"

namespace obscura {
namespace {

// Extensions a file may require: KHR_texture_transform is applied (to the base colour's TEXCOORD_0, below); the others
// change nothing the AO renderer depends on, so a file that *requires* them still renders right.
const std::set<std::string> kHarmlessRequiredExtensions = {
    "KHR_materials_unlit", "KHR_materials_emissive_strength", "KHR_texture_transform", "KHR_materials_ior",
    "KHR_materials_specular", "KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_transmission",
    "KHR_materials_volume", "KHR_materials_variants", "KHR_lights_punctual"};

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

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

const char* componentTypeName(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "an invalid component type";
  }
}

// Reads component `c` of a tightly described element as a double, applying glTF's normalisation rules.
double readComponent(const std::uint8_t* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? *p / 255.0 : *p;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      std::int32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: return 0.0;
  }
}

// The bytes a buffer view covers, after checking that it lies inside its buffer.
const std::uint8_t* bufferViewData(const LoaderContext& ctx, int viewIndex, const std::string& what,
                                   std::uint64_t* length) {
  const auto& views = ctx.model.bufferViews;
  if (viewIndex < 0 || static_cast<size_t>(viewIndex) >= views.size())
    ctx.refuse(what + " refers to bufferView " + std::to_string(viewIndex) + ", which does not exist");
  const tinygltf::BufferView& view = views[static_cast<size_t>(viewIndex)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= ctx.model.buffers.size())
    ctx.refuse("bufferView " + std::to_string(viewIndex) + " refers to buffer " + std::to_string(view.buffer) +
               ", which does not exist");
  const tinygltf::Buffer& buffer = ctx.model.buffers[static_cast<size_t>(view.buffer)];
  const std::uint64_t end = std::uint64_t(view.byteOffset) + std::uint64_t(view.byteLength);
  if (end > buffer.data.size())
    ctx.refuse("bufferView " + std::to_string(viewIndex) + " spans bytes " + std::to_string(view.byteOffset) + ".." +
               std::to_string(end) + " but buffer " + std::to_string(view.buffer) + " holds " +
               std::to_string(buffer.data.size()) + " bytes" +
               (buffer.data.empty() ? " (is its .bin file missing?)" : ""));
  *length = view.byteLength;
  return buffer.data.data() + view.byteOffset;
}

// Reads an accessor into doubles (count x components), validating every bound. `allowed` lists the component types
// this use permits; `components` the element width it needs.
std::vector<double> readAccessor(const LoaderContext& ctx, int accessorIndex, const std::string& use, int components,
                                 const std::vector<int>& allowed) {
  const auto& accessors = ctx.model.accessors;
  if (accessorIndex < 0 || static_cast<size_t>(accessorIndex) >= accessors.size())
    ctx.refuse(use + " refers to accessor " + std::to_string(accessorIndex) + ", which does not exist");
  const tinygltf::Accessor& a = accessors[static_cast<size_t>(accessorIndex)];
  const std::string what = use + " (accessor " + std::to_string(accessorIndex) + ")";
  if (componentCount(a.type) != components)
    ctx.refuse(what + " has " + std::to_string(componentCount(a.type)) + " components per element, expected " +
               std::to_string(components));
  if (std::find(allowed.begin(), allowed.end(), a.componentType) == allowed.end())
    ctx.refuse(what + " has component type " + componentTypeName(a.componentType) + ", which glTF does not allow here");
  if (a.count > ctx.limits.maxAccessorElements)
    ctx.refuse(what + " has " + std::to_string(a.count) + " elements, over the limit of " +
               std::to_string(ctx.limits.maxAccessorElements));

  const int size = componentSize(a.componentType);
  const std::uint64_t elementSize = std::uint64_t(size) * components;
  // Every bound is checked before anything is allocated: a small file declaring a huge count over a short buffer is
  // refused at once, not after reserving memory for the count.
  const std::uint8_t* data = nullptr;
  std::uint64_t stride = elementSize;
  if (a.bufferView >= 0) {
    std::uint64_t viewLength = 0;
    data = bufferViewData(ctx, a.bufferView, what, &viewLength);
    const tinygltf::BufferView& view = ctx.model.bufferViews[static_cast<size_t>(a.bufferView)];
    if (view.byteStride && (view.byteStride < elementSize || view.byteStride > 252 || view.byteStride % 4 != 0))
      ctx.refuse(what + " has byteStride " + std::to_string(view.byteStride) + ", expected a multiple of 4 in " +
                 std::to_string(elementSize) + " .. 252");
    if (view.byteStride) stride = view.byteStride;
    if (a.count > 0) {
      const std::uint64_t last = std::uint64_t(a.byteOffset) + stride * (a.count - 1) + elementSize;
      if (last > viewLength)
        ctx.refuse(what + " reads up to byte " + std::to_string(last) + " of bufferView " +
                   std::to_string(a.bufferView) + ", which holds " + std::to_string(viewLength));
    }
  }

  std::vector<double> out(a.count * static_cast<size_t>(components), 0.0);
  if (data) {
    for (size_t i = 0; i < a.count; ++i) {
      const std::uint8_t* element = data + a.byteOffset + stride * i;
      for (int c = 0; c < components; ++c)
        out[i * components + c] = readComponent(element + c * size, a.componentType, a.normalized);
    }
  }

  if (a.sparse.isSparse) {
    const auto& s = a.sparse;
    if (s.count < 0 || static_cast<size_t>(s.count) > a.count)
      ctx.refuse(what + " has a sparse count of " + std::to_string(s.count) + " for " + std::to_string(a.count) +
                 " elements");
    const int indexSize = componentSize(s.indices.componentType);
    if (s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      ctx.refuse(what + " has sparse indices of component type " + componentTypeName(s.indices.componentType));
    std::uint64_t indexViewLength = 0, valueViewLength = 0;
    const std::uint8_t* indexData = bufferViewData(ctx, s.indices.bufferView, what + " sparse indices", &indexViewLength);
    const std::uint8_t* valueData = bufferViewData(ctx, s.values.bufferView, what + " sparse values", &valueViewLength);
    if (s.indices.byteOffset < 0 || s.values.byteOffset < 0 ||
        std::uint64_t(s.indices.byteOffset) + std::uint64_t(indexSize) * s.count > indexViewLength ||
        std::uint64_t(s.values.byteOffset) + elementSize * s.count > valueViewLength)
      ctx.refuse(what + " has sparse data outside its buffer views");
    for (int k = 0; k < s.count; ++k) {
      const double target = readComponent(indexData + s.indices.byteOffset + std::uint64_t(k) * indexSize,
                                          s.indices.componentType, false);
      if (target < 0 || target >= static_cast<double>(a.count))
        ctx.refuse(what + " has sparse index " + std::to_string(static_cast<std::uint64_t>(target)) +
                   " outside its " + std::to_string(a.count) + " elements");
      const std::uint8_t* element = valueData + s.values.byteOffset + elementSize * std::uint64_t(k);
      for (int c = 0; c < components; ++c)
        out[static_cast<size_t>(target) * components + c] = readComponent(element + c * size, a.componentType,
                                                                          a.normalized);
    }
  }
  return out;
}

template <int N>
std::vector<glm::vec<N, float>> toVectors(const std::vector<double>& flat) {
  std::vector<glm::vec<N, float>> out(flat.size() / N);
  for (size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < N; ++c) out[i][c] = static_cast<float>(flat[i * N + c]);
  return out;
}

// Triangle-list indices for a primitive, converting strips and fans.
std::vector<std::uint32_t> triangleIndices(const LoaderContext& ctx, const tinygltf::Primitive& primitive,
                                           size_t vertexCount, const std::string& what) {
  std::vector<std::uint32_t> raw;
  if (primitive.indices >= 0) {
    const std::vector<double> values =
        readAccessor(ctx, primitive.indices, what + " indices", 1,
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
    raw.reserve(values.size());
    for (double v : values) {
      if (v >= static_cast<double>(vertexCount))
        ctx.refuse(what + " has index " + std::to_string(static_cast<std::uint64_t>(v)) + " but only " +
                   std::to_string(vertexCount) + " vertices");
      raw.push_back(static_cast<std::uint32_t>(v));
    }
  } else {
    raw.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) raw[i] = static_cast<std::uint32_t>(i);
  }
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  std::vector<std::uint32_t> triangles;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (raw.size() % 3 != 0)
      ctx.report.warnings.push_back(what + ": index count " + std::to_string(raw.size()) +
                                    " is not a multiple of 3; the last partial triangle is ignored");
    raw.resize(raw.size() / 3 * 3);
    triangles = std::move(raw);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 2; i < raw.size(); ++i) {
      // Alternate the winding so every triangle keeps the strip's orientation.
      if (i % 2 == 0) triangles.insert(triangles.end(), {raw[i - 2], raw[i - 1], raw[i]});
      else triangles.insert(triangles.end(), {raw[i - 1], raw[i - 2], raw[i]});
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (size_t i = 2; i < raw.size(); ++i) triangles.insert(triangles.end(), {raw[0], raw[i - 1], raw[i]});
  }
  return triangles;
}

// Removes triangles with repeated vertices or zero area; they cover no pixels and break normal generation. A skinned
// or morphed mesh keeps its zero-area triangles with three distinct corners: a pose can open them (three collinear
// vertices following different joints, or a morph target that inflates a collapsed face).
size_t dropDegenerateTriangles(Mesh& mesh) {
  const bool poseCanChangeShape = mesh.skinned() || !mesh.morphTargets.empty();
  std::vector<std::uint32_t> kept;
  kept.reserve(mesh.indices.size());
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    if (a == b || b == c || a == c) continue;
    const glm::vec3 cross = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    if (!poseCanChangeShape && !(glm::dot(cross, cross) > 0.0f)) continue;
    kept.insert(kept.end(), {a, b, c});
  }
  const size_t dropped = (mesh.indices.size() - kept.size()) / 3;
  mesh.indices = std::move(kept);
  return dropped;
}

// KHR_texture_transform on one texture, as the matrix that maps TEXCOORD_0 to the coordinates sampled:
// uv' = T(offset) * R(rotation) * S(scale) * uv. The extension's README lists R as the usual counter-clockwise matrix,
// but in glTF's UV space (v pointing down) the sample model TextureTransformTest, Babylon.js and three.js all use
// u' = cos r u + sin r v, v' = -sin r u + cos r v (KhronosGroup/glTF issue #1563); so does this.
// Identity when the texture has no such extension. Scales and offsets that are not finite are refused.
glm::mat3 uvTransform(const LoaderContext& ctx, int textureIndex, const tinygltf::ExtensionMap& extensions,
                      const std::string& what) {
  const auto it = extensions.find("KHR_texture_transform");
  if (textureIndex < 0 || it == extensions.end() || !it->second.IsObject()) return glm::mat3(1.0f);
  const tinygltf::Value& transform = it->second;
  auto pair = [&](const char* key, glm::vec2 fallback) {
    if (!transform.Has(key)) return fallback;
    const tinygltf::Value& v = transform.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
      ctx.refuse(what + ": KHR_texture_transform " + key + " is not an array of two numbers");
    return glm::vec2(static_cast<float>(v.Get(0).GetNumberAsDouble()),
                     static_cast<float>(v.Get(1).GetNumberAsDouble()));
  };
  const glm::vec2 offset = pair("offset", glm::vec2(0.0f)), scale = pair("scale", glm::vec2(1.0f));
  float rotation = 0.0f;
  if (transform.Has("rotation")) {
    if (!transform.Get("rotation").IsNumber()) ctx.refuse(what + ": KHR_texture_transform rotation is not a number");
    rotation = static_cast<float>(transform.Get("rotation").GetNumberAsDouble());
  }
  if (!std::isfinite(offset.x) || !std::isfinite(offset.y) || !std::isfinite(scale.x) || !std::isfinite(scale.y) ||
      !std::isfinite(rotation))
    ctx.refuse(what + ": KHR_texture_transform has a value that is not finite");
  const int texCoord = transform.Has("texCoord") && transform.Get("texCoord").IsInt()
                           ? transform.Get("texCoord").GetNumberAsInt()
                           : 0;
  if (texCoord != 0)
    ctx.report.warnings.push_back(what + ": KHR_texture_transform asks for TEXCOORD_" + std::to_string(texCoord) +
                                  ", only TEXCOORD_0 is read");
  const float c = std::cos(rotation), s = std::sin(rotation);
  const glm::mat3 translationMatrix(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);  // columns
  const glm::mat3 rotationMatrix(c, -s, 0, s, c, 0, 0, 0, 1);
  const glm::mat3 scaleMatrix(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  return translationMatrix * rotationMatrix * scaleMatrix;
}

const tinygltf::Material* materialOf(const LoaderContext& ctx, int materialIndex) {
  if (materialIndex < 0 || static_cast<size_t>(materialIndex) >= ctx.model.materials.size()) return nullptr;
  return &ctx.model.materials[static_cast<size_t>(materialIndex)];
}

// The material samples textures besides the base colour (Material::hasPbrTextures): its slots' transforms then go to
// the vertex stage, and the base colour's is not baked into TEXCOORD_0.
bool hasPbrTextures(const tinygltf::Material& m) {
  // As loadMaterials keeps them: a slot on another TEXCOORD is ignored.
  auto used = [](int index, int texCoord) { return index >= 0 && texCoord == 0; };
  const auto& mr = m.pbrMetallicRoughness.metallicRoughnessTexture;
  return used(mr.index, mr.texCoord) || used(m.normalTexture.index, m.normalTexture.texCoord) ||
         used(m.occlusionTexture.index, m.occlusionTexture.texCoord) ||
         used(m.emissiveTexture.index, m.emissiveTexture.texCoord);
}

// The base colour's transform where the loader bakes it into TEXCOORD_0 (a material with no other texture); identity
// otherwise.
glm::mat3 baseColorUvTransform(const LoaderContext& ctx, int materialIndex, const std::string& what) {
  const tinygltf::Material* material = materialOf(ctx, materialIndex);
  if (!material || hasPbrTextures(*material)) return glm::mat3(1.0f);
  const tinygltf::TextureInfo& info = material->pbrMetallicRoughness.baseColorTexture;
  return uvTransform(ctx, info.index, info.extensions, what);
}

int attributeAccessor(const tinygltf::Primitive& primitive, const char* name) {
  auto it = primitive.attributes.find(name);
  return it == primitive.attributes.end() ? -1 : it->second;
}

bool allFinite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
}

// JOINTS_0 / WEIGHTS_0 (glTF 2.0 sec. 3.7.3.3): joints unsigned byte or short, not normalised; weights float or
// normalised unsigned byte or short, not negative, summing to 1. Repairs, so that the vertex stage can rely on them:
// weights are renormalised (a warning counts the vertices more than 1 % off, beyond what 8-bit quantisation
// explains); all-zero weights become weight 1 on the first joint listed; slots of weight zero point at joint 0.
void loadSkinAttributes(const LoaderContext& ctx, const tinygltf::Primitive& primitive, const std::string& what,
                        size_t vertexCount, Mesh& mesh) {
  const int jointsAccessor = attributeAccessor(primitive, "JOINTS_0");
  const int weightsAccessor = attributeAccessor(primitive, "WEIGHTS_0");
  if (weightsAccessor < 0) ctx.refuse(what + " has JOINTS_0 without WEIGHTS_0");
  const std::vector<double> joints = readAccessor(
      ctx, jointsAccessor, what + " JOINTS_0", 4,
      {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
  if (ctx.model.accessors[static_cast<size_t>(jointsAccessor)].normalized)
    ctx.refuse(what + " JOINTS_0 (accessor " + std::to_string(jointsAccessor) +
               ") is normalized, which glTF does not allow for joint indices");
  const std::vector<double> weights = readAccessor(
      ctx, weightsAccessor, what + " WEIGHTS_0", 4,
      {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
  const tinygltf::Accessor& weightsSource = ctx.model.accessors[static_cast<size_t>(weightsAccessor)];
  if (weightsSource.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !weightsSource.normalized)
    ctx.refuse(what + " WEIGHTS_0 (accessor " + std::to_string(weightsAccessor) + ") has component type " +
               componentTypeName(weightsSource.componentType) + " without normalized: true, which glTF does not allow");
  if (joints.size() / 4 != vertexCount || weights.size() / 4 != vertexCount)
    ctx.refuse(what + " has " + std::to_string(joints.size() / 4) + " JOINTS_0 and " +
               std::to_string(weights.size() / 4) + " WEIGHTS_0 for " + std::to_string(vertexCount) + " positions");
  mesh.joints.resize(vertexCount);
  mesh.weights.resize(vertexCount);
  size_t renormalised = 0, weightless = 0;
  for (size_t v = 0; v < vertexCount; ++v) {
    double sum = 0.0;
    for (int c = 0; c < 4; ++c) {
      const double w = weights[v * 4 + static_cast<size_t>(c)];
      if (!std::isfinite(w) || w < 0.0)
        ctx.refuse(what + " WEIGHTS_0 " + std::to_string(v) + " is negative or not finite");
      sum += w;
    }
    glm::dvec4 w(weights[v * 4], weights[v * 4 + 1], weights[v * 4 + 2], weights[v * 4 + 3]);
    if (!(sum > 0.0)) {
      w = glm::dvec4(1.0, 0.0, 0.0, 0.0);
      ++weightless;
    } else {
      if (std::abs(sum - 1.0) > 0.01) ++renormalised;
      w /= sum;
    }
    for (int c = 0; c < 4; ++c) {
      mesh.weights[v][c] = static_cast<float>(w[c]);
      mesh.joints[v][c] = w[c] > 0.0 ? static_cast<std::uint16_t>(joints[v * 4 + static_cast<size_t>(c)]) : 0;
    }
  }
  if (renormalised > 0)
    ctx.report.warnings.push_back(what + ": WEIGHTS_0 of " + std::to_string(renormalised) +
                                  " vertices did not sum to 1; renormalised");
  if (weightless > 0)
    ctx.report.warnings.push_back(what + ": " + std::to_string(weightless) +
                                  " vertices have all WEIGHTS_0 zero; they follow their first joint");
  if (attributeAccessor(primitive, "JOINTS_1") >= 0 || attributeAccessor(primitive, "WEIGHTS_1") >= 0)
    ctx.report.warnings.push_back(what + ": JOINTS_1 / WEIGHTS_1 ignored (only four joints per vertex are drawn); "
                                         "WEIGHTS_0 renormalised");
}

// A vertex attribute in the component types its use allows: glTF 2.0's (3.7.2.1), widened by KHR_mesh_quantization
// when the file uses it (GltfCompression.h). Integer types read as integers unless the accessor is normalized.
std::vector<double> readVertexAttribute(const LoaderContext& ctx, int accessorIndex, const std::string& what,
                                        int components, const char* use) {
  const AttributeTypes types = quantizedAttributeTypes(use, usesMeshQuantization(ctx.model));
  std::vector<double> values = readAccessor(ctx, accessorIndex, what, components, types.allowed);
  const tinygltf::Accessor& accessor = ctx.model.accessors[static_cast<size_t>(accessorIndex)];
  if (!accessor.normalized && std::find(types.normalizedOnly.begin(), types.normalizedOnly.end(),
                                        accessor.componentType) != types.normalizedOnly.end())
    ctx.refuse(what + " (accessor " + std::to_string(accessorIndex) + ") has component type " +
               componentTypeName(accessor.componentType) + " without normalized: true, which glTF does not allow");
  return values;
}

// Morph targets (glTF 2.0 sec. 3.7.2.2): per target, POSITION and NORMAL displacements, float VEC3, one per vertex
// (sparse accessors welcome: targets are mostly zeros). TANGENT and any other attribute are ignored: nothing here
// uses tangents. A target without POSITION displaces nothing.
void loadMorphTargets(const LoaderContext& ctx, const tinygltf::Primitive& primitive, const std::string& what,
                      size_t vertexCount, Mesh& mesh) {
  for (size_t t = 0; t < primitive.targets.size(); ++t) {
    const std::string target = what + " target " + std::to_string(t);
    ctx.budget.morphTargetVertices += vertexCount;
    if (ctx.budget.morphTargetVertices > ctx.limits.maxMorphTargetVertices)
      ctx.refuse(target + ": more than " + std::to_string(ctx.limits.maxMorphTargetVertices) +
                 " morph target vertices in the scene");
    MorphTarget morph;
    for (const char* name : {"POSITION", "NORMAL"}) {
      auto it = primitive.targets[t].find(name);
      if (it == primitive.targets[t].end()) continue;
      const std::vector<double> deltas =
          readVertexAttribute(ctx, it->second, target + " " + name, 3,
                              std::strcmp(name, "POSITION") == 0 ? "MORPH_POSITION" : "MORPH_NORMAL");
      if (deltas.size() / 3 != vertexCount)
        ctx.refuse(target + " has " + std::to_string(deltas.size() / 3) + " " + name + " displacements for " +
                   std::to_string(vertexCount) + " positions");
      if (!allFinite(deltas)) ctx.refuse(target + " " + name + " has a displacement that is not finite");
      (std::strcmp(name, "POSITION") == 0 ? morph.positions : morph.normals) = toVectors<3>(deltas);
    }
    if (morph.positions.empty()) morph.positions.assign(vertexCount, glm::vec3(0.0f));
    mesh.morphTargets.push_back(std::move(morph));
  }
}

// One glTF primitive as a Mesh. `readSkin`: keep JOINTS_0 / WEIGHTS_0 (the node placing it has a skin).
Mesh loadPrimitive(const LoaderContext& ctx, const tinygltf::Primitive& primitive, const std::string& what,
                   bool readSkin, bool* skipped) {
  Mesh mesh;
  *skipped = false;
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    if (mode < 0 || mode > 6) ctx.refuse(what + " has primitive mode " + std::to_string(mode) + ", not a glTF mode");
    *skipped = true;  // points and lines have no surface to occlude: loadLinePrimitive reads them
    return mesh;
  }
  auto attribute = [&](const char* name) { return attributeAccessor(primitive, name); };
  const int positionAccessor = attribute("POSITION");
  if (positionAccessor < 0) ctx.refuse(what + " has no POSITION attribute");
  mesh.positions = toVectors<3>(readVertexAttribute(ctx, positionAccessor, what + " POSITION", 3, "POSITION"));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      ctx.refuse(what + " POSITION " + std::to_string(i) + " is not finite (NaN or Inf)");
  }
  const size_t vertexCount = mesh.positions.size();

  const int normalAccessor = attribute("NORMAL");
  bool normalsUsable = false;
  if (normalAccessor >= 0) {
    mesh.normals = toVectors<3>(readVertexAttribute(ctx, normalAccessor, what + " NORMAL", 3, "NORMAL"));
    if (mesh.normals.size() != vertexCount)
      ctx.refuse(what + " has " + std::to_string(mesh.normals.size()) + " normals for " +
                 std::to_string(vertexCount) + " positions");
    normalsUsable = true;
    for (glm::vec3& n : mesh.normals) {
      const float length = glm::length(n);
      if (!std::isfinite(length) || length < 1e-6f) {
        normalsUsable = false;
        break;
      }
      n /= length;  // the spec requires unit normals; tolerate slightly off ones
    }
    if (!normalsUsable)
      ctx.report.warnings.push_back(what + ": NORMAL has zero-length or non-finite vectors; flat normals generated");
  }

  const int uvAccessor = attribute("TEXCOORD_0");
  if (uvAccessor >= 0) {
    // glTF 2.0 (3.7.2.1) allows integer texture coordinates only normalised (raw integers would be coordinates
    // hundreds of textures wide); KHR_mesh_quantization allows them raw, scaled by KHR_texture_transform.
    mesh.texcoords = toVectors<2>(readVertexAttribute(ctx, uvAccessor, what + " TEXCOORD_0", 2, "TEXCOORD"));
    if (mesh.texcoords.size() != vertexCount)
      ctx.refuse(what + " has " + std::to_string(mesh.texcoords.size()) + " texture coordinates for " +
                 std::to_string(vertexCount) + " positions");
    for (glm::vec2& uv : mesh.texcoords)
      if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
    // Each glTF primitive becomes its own Mesh with its own copy of the coordinates, so applying the material's
    // transform here is right even when primitives with different materials share one TEXCOORD_0 accessor.
    const glm::mat3 transform = baseColorUvTransform(ctx, primitive.material, what);
    if (transform != glm::mat3(1.0f))
      for (glm::vec2& uv : mesh.texcoords) uv = glm::vec2(transform * glm::vec3(uv, 1.0f));
  }

  const int tangentAccessor = attribute("TANGENT");
  const tinygltf::Material* material = materialOf(ctx, primitive.material);
  const bool normalMapped = material && material->normalTexture.index >= 0;
  if (tangentAccessor >= 0 && normalMapped && normalsUsable) {
    const std::vector<double> tangents = readVertexAttribute(ctx, tangentAccessor, what + " TANGENT", 4, "NORMAL");
    if (tangents.size() / 4 != vertexCount)
      ctx.refuse(what + " has " + std::to_string(tangents.size() / 4) + " tangents for " +
                 std::to_string(vertexCount) + " positions");
    mesh.tangents = toVectors<4>(tangents);
    for (size_t v = 0; v < vertexCount; ++v) {
      glm::vec4& t = mesh.tangents[v];
      const float length = glm::length(glm::vec3(t));
      // glTF: XYZ unit, W +-1. Tolerate slightly off ones; a broken one takes a perpendicular of the normal.
      const glm::vec3 xyz = std::isfinite(length) && length > 1e-6f ? glm::vec3(t) / length
                                                                     : anyPerpendicular(mesh.normals[v]);
      t = glm::vec4(xyz, t.w < 0.0f ? -1.0f : 1.0f);
    }
  }

  if (readSkin) loadSkinAttributes(ctx, primitive, what, vertexCount, mesh);
  loadMorphTargets(ctx, primitive, what, vertexCount, mesh);
  // Normal displacements are relative to the file's normals; where those are replaced by flat ones,
  // generateFlatNormals derives each target's from its displaced faces instead.
  if (!normalsUsable)
    for (MorphTarget& target : mesh.morphTargets) target.normals.clear();

  mesh.indices = triangleIndices(ctx, primitive, vertexCount, what);
  const size_t dropped = dropDegenerateTriangles(mesh);
  if (dropped > 0)
    ctx.report.warnings.push_back(what + ": dropped " + std::to_string(dropped) + " degenerate triangles");
  if (primitive.material >= 0 && static_cast<size_t>(primitive.material) >= ctx.model.materials.size())
    ctx.refuse(what + " refers to material " + std::to_string(primitive.material) + ", which does not exist");
  mesh.material = primitive.material;
  if (!normalsUsable) generateFlatNormals(mesh);
  // glTF 2.0 (3.7.2.1): without TANGENT, tangents are computed (MikkTSpace) where a normal texture needs them.
  if (normalMapped && mesh.tangents.empty()) generateTangents(mesh);
  return mesh;
}

// A POINTS, LINES, LINE_LOOP or LINE_STRIP primitive as a LineMesh: POSITION (float, or quantized under
// KHR_mesh_quantization), COLOR_0 (float or normalised u8/u16, RGB or RGBA), indices as for triangles. Strips and
// loops become segment lists; a zero-length segment is kept (it covers a pixel, as a point would).
LineMesh loadLinePrimitive(const LoaderContext& ctx, const tinygltf::Primitive& primitive, const std::string& what) {
  const int mode = primitive.mode;
  LineMesh lines;
  lines.points = mode == TINYGLTF_MODE_POINTS;
  const int positionAccessor = attributeAccessor(primitive, "POSITION");
  if (positionAccessor < 0) ctx.refuse(what + " has no POSITION attribute");
  const std::vector<glm::vec3> positions =
      toVectors<3>(readVertexAttribute(ctx, positionAccessor, what + " POSITION", 3, "POSITION"));
  for (size_t i = 0; i < positions.size(); ++i)
    if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z))
      ctx.refuse(what + " POSITION " + std::to_string(i) + " is not finite (NaN or Inf)");
  std::vector<glm::vec4> colors;
  const int colorAccessor = attributeAccessor(primitive, "COLOR_0");
  if (colorAccessor >= 0) {
    const tinygltf::Accessor& accessor = ctx.model.accessors.at(static_cast<size_t>(colorAccessor));
    const int components = accessor.type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
    const std::vector<double> values =
        readAccessor(ctx, colorAccessor, what + " COLOR_0", components,
                     {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
    if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !accessor.normalized)
      ctx.refuse(what + " COLOR_0 (accessor " + std::to_string(colorAccessor) + ") has component type " +
                 componentTypeName(accessor.componentType) + " without normalized: true, which glTF does not allow");
    if (values.size() / static_cast<size_t>(components) != positions.size())
      ctx.refuse(what + " has " + std::to_string(values.size() / static_cast<size_t>(components)) +
                 " colours for " + std::to_string(positions.size()) + " positions");
    for (size_t i = 0; i < positions.size(); ++i) {
      glm::vec4 c(1.0f);
      for (int k = 0; k < components; ++k) {
        const double v = values[i * static_cast<size_t>(components) + static_cast<size_t>(k)];
        c[k] = std::isfinite(v) ? static_cast<float>(std::clamp(v, 0.0, 1.0)) : 0.0f;
      }
      colors.push_back(c);
    }
  }
  std::vector<std::uint32_t> order;
  if (primitive.indices >= 0) {
    const std::vector<double> values =
        readAccessor(ctx, primitive.indices, what + " indices", 1,
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
    for (double v : values) {
      if (v >= static_cast<double>(positions.size()))
        ctx.refuse(what + " has index " + std::to_string(static_cast<std::uint64_t>(v)) + " but only " +
                   std::to_string(positions.size()) + " vertices");
      order.push_back(static_cast<std::uint32_t>(v));
    }
  } else {
    for (size_t i = 0; i < positions.size(); ++i) order.push_back(static_cast<std::uint32_t>(i));
  }
  std::vector<std::uint32_t> corners;  // points, or segment ends in pairs
  if (mode == TINYGLTF_MODE_POINTS) {
    corners = order;
  } else if (mode == TINYGLTF_MODE_LINE) {
    if (order.size() % 2 != 0)
      ctx.report.warnings.push_back(what + ": index count " + std::to_string(order.size()) +
                                    " is odd; the last partial line is ignored");
    corners.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(order.size() / 2 * 2));
  } else {
    for (size_t i = 1; i < order.size(); ++i) corners.insert(corners.end(), {order[i - 1], order[i]});
    if (mode == TINYGLTF_MODE_LINE_LOOP && order.size() > 2) corners.insert(corners.end(), {order.back(), order[0]});
  }
  if (corners.size() > ctx.limits.maxAccessorElements)
    ctx.refuse(what + " expands to " + std::to_string(corners.size()) + " vertices, over the limit");
  for (std::uint32_t c : corners) {
    lines.positions.push_back(positions[c]);
    if (!colors.empty()) lines.colors.push_back(colors[c]);
  }
  if (primitive.material >= 0 && static_cast<size_t>(primitive.material) >= ctx.model.materials.size())
    ctx.refuse(what + " refers to material " + std::to_string(primitive.material) + ", which does not exist");
  lines.material = primitive.material;
  return lines;
}

// A node's rest transform, checked: a matrix of 16 finite numbers, or finite TRS with a non-zero rotation (kept
// normalised). A node with both keeps the matrix, as before nodes were kept.
Node readNode(const LoaderContext& ctx, const tinygltf::Node& source, int index) {
  const std::string what = "node " + std::to_string(index);
  Node node;
  node.name = source.name;
  if (source.matrix.size() == 16) {
    if (!allFinite(source.matrix)) ctx.refuse(what + " has a non-finite matrix");
    node.hasMatrix = true;
    for (int i = 0; i < 16; ++i)
      glm::value_ptr(node.matrix)[i] = static_cast<float>(source.matrix[static_cast<size_t>(i)]);
    return node;
  }
  if (!source.matrix.empty())
    ctx.refuse(what + " has a matrix of " + std::to_string(source.matrix.size()) + " numbers, expected 16");
  if (!source.translation.empty()) {
    if (source.translation.size() != 3 || !allFinite(source.translation))
      ctx.refuse(what + " has an invalid translation");
    node.translation = glm::vec3(source.translation[0], source.translation[1], source.translation[2]);
  }
  if (!source.rotation.empty()) {
    if (source.rotation.size() != 4 || !allFinite(source.rotation)) ctx.refuse(what + " has an invalid rotation");
    const glm::quat q(static_cast<float>(source.rotation[3]), static_cast<float>(source.rotation[0]),
                      static_cast<float>(source.rotation[1]), static_cast<float>(source.rotation[2]));
    const float length = glm::length(q);
    if (length < 1e-6f) ctx.refuse(what + " has a zero rotation quaternion");
    node.rotation = q / length;
  }
  if (!source.scale.empty()) {
    if (source.scale.size() != 3 || !allFinite(source.scale)) ctx.refuse(what + " has an invalid scale");
    node.scale = glm::vec3(source.scale[0], source.scale[1], source.scale[2]);
  }
  return node;
}

void loadMaterials(const LoaderContext& ctx, Scene& scene) {
  const tinygltf::Model& model = ctx.model;
  for (const tinygltf::Image& source : model.images) {
    Image image;
    if (!source.image.empty() && source.width > 0 && source.height > 0 && source.component == 4 && source.bits == 8 &&
        source.image.size() == size_t(source.width) * source.height * 4) {
      image.width = source.width;
      image.height = source.height;
      image.rgba = source.image;
    } else {
      ctx.report.warnings.push_back("image '" + (source.name.empty() ? source.uri : source.name) +
                                    "' could not be decoded; its texture is drawn white");
    }
    scene.images.push_back(std::move(image));
  }
  for (const tinygltf::Texture& source : model.textures) {
    Texture texture;
    if (source.source >= 0 && static_cast<size_t>(source.source) < scene.images.size() &&
        scene.images[static_cast<size_t>(source.source)].width > 0)
      texture.image = source.source;
    if (source.sampler >= 0 && static_cast<size_t>(source.sampler) < model.samplers.size()) {
      const tinygltf::Sampler& s = model.samplers[static_cast<size_t>(source.sampler)];
      if (s.magFilter > 0) texture.sampler.magFilter = s.magFilter;
      if (s.minFilter > 0) texture.sampler.minFilter = s.minFilter;
      texture.sampler.wrapS = s.wrapS;
      texture.sampler.wrapT = s.wrapT;
    }
    scene.textures.push_back(texture);
  }
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const tinygltf::Material& source = model.materials[i];
    Material material;
    material.metallicFactor = 1.0f;  // glTF's defaults (a Material made in code is a dielectric)
    material.roughnessFactor = 1.0f;
    const auto& factor = source.pbrMetallicRoughness.baseColorFactor;
    if (factor.size() == 4 && std::all_of(factor.begin(), factor.end(), [](double v) { return std::isfinite(v); }))
      material.baseColorFactor = glm::clamp(glm::vec4(factor[0], factor[1], factor[2], factor[3]), 0.0f, 1.0f);
    const auto& textureInfo = source.pbrMetallicRoughness.baseColorTexture;
    if (textureInfo.index >= 0) {
      if (static_cast<size_t>(textureInfo.index) >= scene.textures.size())
        ctx.refuse("material " + std::to_string(i) + " refers to texture " + std::to_string(textureInfo.index) +
                   ", which does not exist");
      if (textureInfo.texCoord == 0) material.baseColorTexture = textureInfo.index;
      else ctx.report.warnings.push_back("material " + std::to_string(i) + ": base colour uses TEXCOORD_" +
                                         std::to_string(textureInfo.texCoord) + ", only TEXCOORD_0 is read");
    }
    const std::string name = "material " + std::to_string(i);
    // A texture of another slot: checked, TEXCOORD_0 only, its KHR_texture_transform kept for the vertex stage.
    auto slot = [&](TextureSlot which, int index, int texCoord, const tinygltf::ExtensionMap& extensions,
                    const char* slotName) {
      if (index < 0) return -1;
      if (static_cast<size_t>(index) >= scene.textures.size())
        ctx.refuse(name + " refers to texture " + std::to_string(index) + ", which does not exist");
      if (texCoord != 0) {
        ctx.report.warnings.push_back(name + ": " + slotName + " uses TEXCOORD_" + std::to_string(texCoord) +
                                      ", only TEXCOORD_0 is read; the slot is ignored");
        return -1;
      }
      material.uvTransforms[static_cast<size_t>(which)] = uvTransform(ctx, index, extensions, name + " " + slotName);
      return index;
    };
    auto finite = [](double v, double fallback) { return std::isfinite(v) ? v : fallback; };
    const auto& pbr = source.pbrMetallicRoughness;
    material.metallicFactor = static_cast<float>(std::clamp(finite(pbr.metallicFactor, 1.0), 0.0, 1.0));
    material.roughnessFactor = static_cast<float>(std::clamp(finite(pbr.roughnessFactor, 1.0), 0.0, 1.0));
    material.metallicRoughnessTexture =
        slot(TextureSlot::MetallicRoughness, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
             pbr.metallicRoughnessTexture.extensions, "metallicRoughnessTexture");
    material.normalTexture = slot(TextureSlot::Normal, source.normalTexture.index, source.normalTexture.texCoord,
                                  source.normalTexture.extensions, "normalTexture");
    material.normalScale = static_cast<float>(finite(source.normalTexture.scale, 1.0));
    material.occlusionTexture =
        slot(TextureSlot::Occlusion, source.occlusionTexture.index, source.occlusionTexture.texCoord,
             source.occlusionTexture.extensions, "occlusionTexture");
    material.occlusionStrength =
        static_cast<float>(std::clamp(finite(source.occlusionTexture.strength, 1.0), 0.0, 1.0));
    material.emissiveTexture = slot(TextureSlot::Emissive, source.emissiveTexture.index,
                                    source.emissiveTexture.texCoord, source.emissiveTexture.extensions,
                                    "emissiveTexture");
    if (source.emissiveFactor.size() == 3)
      material.emissiveFactor = glm::clamp(glm::vec3(finite(source.emissiveFactor[0], 0.0),
                                                     finite(source.emissiveFactor[1], 0.0),
                                                     finite(source.emissiveFactor[2], 0.0)),
                                           0.0f, 1.0f);
    const auto strength = source.extensions.find("KHR_materials_emissive_strength");
    if (strength != source.extensions.end() && strength->second.IsObject() &&
        strength->second.Has("emissiveStrength") && strength->second.Get("emissiveStrength").IsNumber()) {
      const double value = strength->second.Get("emissiveStrength").GetNumberAsDouble();
      if (!std::isfinite(value) || value < 0.0) ctx.refuse(name + ": emissiveStrength is negative or not finite");
      material.emissiveStrength = static_cast<float>(value);
    }
    // The base colour's transform: baked into TEXCOORD_0 (loadPrimitive) unless other slots need the coordinates.
    if (material.hasPbrTextures() && material.baseColorTexture >= 0)
      material.uvTransforms[0] =
          uvTransform(ctx, textureInfo.index, textureInfo.extensions, name + " baseColorTexture");
    if (source.alphaMode == "MASK") material.alphaMode = AlphaMode::Mask;
    else if (source.alphaMode == "BLEND") material.alphaMode = AlphaMode::Blend;
    material.alphaCutoff = std::isfinite(source.alphaCutoff) ? static_cast<float>(source.alphaCutoff) : 0.5f;
    material.doubleSided = source.doubleSided;
    scene.materials.push_back(material);
  }
}

// The default scene's nodes, meshes, skins and animations, as Scene data. Nodes are collected first (parents
// before children), then every node's mesh is placed, loading each skin it needs, then the animations, whose
// channels name the nodes collected.
class SceneBuilder {
 public:
  SceneBuilder(const LoaderContext& ctx, Scene& scene)
      : ctx_(ctx), model_(ctx.model), scene_(scene), copies_(ctx.model.nodes.size()) {}

  void build() {
    for (int root : roots()) visit(root, -1);
    placeInstances();
    loadAnimations();
  }

 private:
  std::vector<int> roots() const {
    if (!model_.scenes.empty()) {
      const int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (static_cast<size_t>(sceneIndex) >= model_.scenes.size())
        ctx_.refuse("default scene " + std::to_string(sceneIndex) + " does not exist");
      return model_.scenes[static_cast<size_t>(sceneIndex)].nodes;
    }
    // No scene: show every node that is nobody's child.
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes)
      for (int child : node.children)
        if (child >= 0 && static_cast<size_t>(child) < isChild.size()) isChild[static_cast<size_t>(child)] = true;
    std::vector<int> out;
    for (size_t i = 0; i < model_.nodes.size(); ++i)
      if (!isChild[i]) out.push_back(static_cast<int>(i));
    return out;
  }

  // Depth first, so that a node's parent is always collected before it (Node::parent is lower than its index).
  void visit(int nodeIndex, int parent) {
    if (nodeIndex < 0 || static_cast<size_t>(nodeIndex) >= model_.nodes.size())
      ctx_.refuse("node " + std::to_string(nodeIndex) + " is referenced but does not exist");
    if (std::find(path_.begin(), path_.end(), nodeIndex) != path_.end())
      ctx_.refuse("node hierarchy has a cycle through node " + std::to_string(nodeIndex));
    if (static_cast<int>(path_.size()) >= ctx_.limits.maxNodeDepth)
      ctx_.refuse("node hierarchy is deeper than " + std::to_string(ctx_.limits.maxNodeDepth) + " levels");
    if (scene_.nodes.size() >= ctx_.limits.maxNodes)
      ctx_.refuse("has more than " + std::to_string(ctx_.limits.maxNodes) + " nodes in its hierarchy");
    const tinygltf::Node& source = model_.nodes[static_cast<size_t>(nodeIndex)];
    Node node = readNode(ctx_, source, nodeIndex);
    node.parent = parent;
    if (source.mesh >= 0) {
      if (static_cast<size_t>(source.mesh) >= model_.meshes.size())
        ctx_.refuse("node " + std::to_string(nodeIndex) + " refers to mesh " + std::to_string(source.mesh) +
                    ", which does not exist");
      node.weights = restWeights(source, nodeIndex);
    }
    // glTF 2.0 (sec. 3.5.3) requires disjoint trees; a node under two parents has been drawn twice since before
    // nodes were kept, so it still is: one Scene node per path.
    if (!copies_[static_cast<size_t>(nodeIndex)].empty() && !warnedSharedNode_) {
      warnedSharedNode_ = true;
      ctx_.report.warnings.push_back("node " + std::to_string(nodeIndex) +
                                     " has more than one parent (glTF requires disjoint trees); each path gets a copy");
    }
    const int index = static_cast<int>(scene_.nodes.size());
    restWorld_.push_back((parent >= 0 ? restWorld_[static_cast<size_t>(parent)] : glm::mat4(1.0f)) * node.localRest());
    addLight(source, nodeIndex, index);
    addCamera(source, nodeIndex, index, node.name);
    scene_.nodes.push_back(std::move(node));
    sourceNode_.push_back(nodeIndex);
    copies_[static_cast<size_t>(nodeIndex)].push_back(index);
    path_.push_back(nodeIndex);
    for (int child : source.children) visit(child, index);
    path_.pop_back();
  }

  // KHR_lights_punctual: the node's point or spot light (directional lights are not loaded: the sun is the
  // renderer's own, effects/lighting/LightingEffect.h).
  void addLight(const tinygltf::Node& source, int nodeIndex, int index) {
    const auto it = source.extensions.find("KHR_lights_punctual");
    if (it == source.extensions.end() || !it->second.IsObject() || !it->second.Has("light")) return;
    const tinygltf::Value& reference = it->second.Get("light");
    const int lightIndex = reference.IsInt() ? reference.GetNumberAsInt() : -1;
    if (lightIndex < 0 || static_cast<size_t>(lightIndex) >= model_.lights.size())
      ctx_.refuse("node " + std::to_string(nodeIndex) + " refers to light " + std::to_string(lightIndex) +
                  ", which does not exist");
    const tinygltf::Light& light = model_.lights[static_cast<size_t>(lightIndex)];
    const std::string what = "light " + std::to_string(lightIndex);
    if (light.type == "directional") {
      if (!warnedDirectional_)
        ctx_.report.warnings.push_back(what + " is directional: not loaded (the renderer's sun is the directional "
                                       "light; lighting.sun-*)");
      warnedDirectional_ = true;
      return;
    }
    if (light.type != "point" && light.type != "spot") ctx_.refuse(what + " has unknown type '" + light.type + "'");
    PunctualLight out;
    out.type = light.type == "spot" ? LightType::Spot : LightType::Point;
    if (light.color.size() == 3 && allFinite(light.color))
      out.color = glm::max(glm::vec3(light.color[0], light.color[1], light.color[2]), glm::vec3(0.0f));
    if (!std::isfinite(light.intensity) || light.intensity < 0.0 || !std::isfinite(light.range) || light.range < 0.0)
      ctx_.refuse(what + " has a negative or non-finite intensity or range");
    out.intensity = static_cast<float>(light.intensity);
    out.range = static_cast<float>(light.range);
    const double inner = light.spot.innerConeAngle, outer = light.spot.outerConeAngle;
    if (out.type == LightType::Spot &&
        !(std::isfinite(inner) && std::isfinite(outer) && inner >= 0.0 && inner < outer && outer <= 1.5707963268))
      ctx_.refuse(what + " needs 0 <= innerConeAngle < outerConeAngle <= pi/2");
    out.innerConeAngle = static_cast<float>(inner);
    out.outerConeAngle = static_cast<float>(outer);
    out.node = index;
    out.world = restWorld_[static_cast<size_t>(index)];
    scene_.lights.push_back(out);
  }

  // The node's camera (glTF 2.0 sec. 3.10), perspective or orthographic, with the values the spec requires checked.
  void addCamera(const tinygltf::Node& source, int nodeIndex, int index, const std::string& nodeName) {
    if (source.camera < 0) return;
    if (static_cast<size_t>(source.camera) >= model_.cameras.size())
      ctx_.refuse("node " + std::to_string(nodeIndex) + " refers to camera " + std::to_string(source.camera) +
                  ", which does not exist");
    const tinygltf::Camera& camera = model_.cameras[static_cast<size_t>(source.camera)];
    const std::string what = "camera " + std::to_string(source.camera);
    SceneCamera out;
    out.name = camera.name;
    out.nodeName = nodeName;
    out.node = index;
    out.world = restWorld_[static_cast<size_t>(index)];
    auto finite = [](double v) { return std::isfinite(v); };
    if (camera.type == "perspective") {
      const tinygltf::PerspectiveCamera& p = camera.perspective;
      if (!(finite(p.yfov) && p.yfov > 0.0 && p.yfov < 3.14159265358979))
        ctx_.refuse(what + " has yfov " + std::to_string(p.yfov) + " (glTF: radians, > 0 and < pi)");
      if (!(finite(p.znear) && p.znear > 0.0)) ctx_.refuse(what + " needs znear > 0");
      if (!(finite(p.zfar) && (p.zfar == 0.0 || p.zfar > p.znear)))
        ctx_.refuse(what + " needs zfar > znear (or none: infinite)");
      if (!(finite(p.aspectRatio) && p.aspectRatio >= 0.0)) ctx_.refuse(what + " needs aspectRatio > 0");
      // The renderer's cameras span 1 .. 170 degrees (scene/Camera.h); a wider one is drawn at 170.
      const double widest = 170.0 * 3.14159265358979 / 180.0, narrowest = 3.14159265358979 / 180.0;
      if (p.yfov > widest || p.yfov < narrowest)
        ctx_.report.warnings.push_back(what + " has yfov " + std::to_string(p.yfov) +
                                       " radians, beyond 1 .. 170 degrees: drawn at the nearest");
      out.yfov = static_cast<float>(std::clamp(p.yfov, narrowest, widest));
      out.aspectRatio = static_cast<float>(p.aspectRatio);
      out.znear = static_cast<float>(p.znear);
      out.zfar = static_cast<float>(p.zfar);
    } else if (camera.type == "orthographic") {
      const tinygltf::OrthographicCamera& o = camera.orthographic;
      if (!(finite(o.xmag) && finite(o.ymag) && o.xmag != 0.0 && o.ymag != 0.0))
        ctx_.refuse(what + " needs xmag and ymag other than 0");
      // glTF: "SHOULD NOT be negative" (a mirrored view); drawn unmirrored.
      if (o.xmag < 0.0 || o.ymag < 0.0)
        ctx_.report.warnings.push_back(what + " has a negative xmag or ymag: drawn with their magnitudes");
      if (!(finite(o.znear) && finite(o.zfar) && o.znear >= 0.0 && o.zfar > o.znear))
        ctx_.refuse(what + " needs 0 <= znear < zfar");
      out.orthographic = true;
      out.xmag = static_cast<float>(std::abs(o.xmag));
      out.ymag = static_cast<float>(std::abs(o.ymag));
      out.znear = static_cast<float>(o.znear);
      out.zfar = static_cast<float>(o.zfar);
    } else {
      ctx_.refuse(what + " has unknown type '" + camera.type + "'");
    }
    scene_.cameras.push_back(std::move(out));
  }

  // The morph target count of a glTF mesh: every primitive must have the same (glTF 2.0 sec. 3.7.2.2), and the
  // mesh's default weights, when given, one per target.
  size_t morphTargetCount(int meshIndex) {
    auto found = targetCounts_.find(meshIndex);
    if (found != targetCounts_.end()) return found->second;
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<size_t>(meshIndex)];
    const std::string what = "mesh " + std::to_string(meshIndex);
    const size_t count = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
    for (size_t p = 1; p < mesh.primitives.size(); ++p)
      if (mesh.primitives[p].targets.size() != count)
        ctx_.refuse(what + " primitive " + std::to_string(p) + " has " +
                    std::to_string(mesh.primitives[p].targets.size()) + " morph targets but primitive 0 has " +
                    std::to_string(count) + " (glTF requires the same in every primitive)");
    if (!mesh.weights.empty() && mesh.weights.size() != count)
      ctx_.refuse(what + " has " + std::to_string(mesh.weights.size()) + " weights for " + std::to_string(count) +
                  " morph targets");
    if (!allFinite(mesh.weights)) ctx_.refuse(what + " has a weight that is not finite");
    targetCounts_[meshIndex] = count;
    return count;
  }

  // A node's rest morph weights: its own, else its mesh's, else zeros; one per morph target.
  std::vector<float> restWeights(const tinygltf::Node& source, int nodeIndex) {
    const size_t count = morphTargetCount(source.mesh);
    const std::vector<double>& mesh = model_.meshes[static_cast<size_t>(source.mesh)].weights;
    if (!source.weights.empty()) {
      if (source.weights.size() != count)
        ctx_.refuse("node " + std::to_string(nodeIndex) + " has " + std::to_string(source.weights.size()) +
                    " weights for its mesh's " + std::to_string(count) + " morph targets");
      if (!allFinite(source.weights))
        ctx_.refuse("node " + std::to_string(nodeIndex) + " has a weight that is not finite");
    }
    const std::vector<double>& chosen = !source.weights.empty() ? source.weights : mesh;
    std::vector<float> out(count, 0.0f);
    for (size_t i = 0; i < chosen.size() && i < count; ++i) out[i] = static_cast<float>(chosen[i]);
    return out;
  }

  // The Scene mesh of a glTF primitive drawn skinned or rigid (-1: nothing to draw), loaded on first use.
  int primitiveMesh(int meshIndex, size_t primitive, bool skinned) {
    const auto key = std::make_tuple(meshIndex, primitive, skinned);
    auto found = primitiveMeshes_.find(key);
    if (found != primitiveMeshes_.end()) return found->second;
    const tinygltf::Primitive& source = model_.meshes[static_cast<size_t>(meshIndex)].primitives[primitive];
    const std::string what = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primitive);
    bool skipped = false;
    Mesh mesh = loadPrimitive(ctx_, source, what, skinned, &skipped);
    if (skipped) {
      LineMesh lines = loadLinePrimitive(ctx_, source, what);
      if (!lines.positions.empty()) {
        lineMeshes_[key] = static_cast<int>(scene_.lineMeshes.size());
        scene_.lineMeshes.push_back(std::move(lines));
      }
    }
    int index = -1;
    if (!skipped && !mesh.indices.empty()) {
      if (!skinned && attributeAccessor(source, "JOINTS_0") >= 0)
        ctx_.report.warnings.push_back(what + " has JOINTS_0 but a node without a skin places it; drawn rigid");
      int maxJoint = -1;
      for (const glm::u16vec4& joints : mesh.joints)
        for (int c = 0; c < 4; ++c) maxJoint = std::max(maxJoint, static_cast<int>(joints[c]));
      index = static_cast<int>(scene_.meshes.size());
      scene_.meshes.push_back(std::move(mesh));
      maxJoint_.push_back(maxJoint);
    }
    primitiveMeshes_[key] = index;
    return index;
  }

  // A glTF skin as a Scene skin (loaded on first use): its joints must be nodes of the loaded hierarchy.
  int sceneSkin(int skinIndex) {
    auto found = skins_.find(skinIndex);
    if (found != skins_.end()) return found->second;
    const tinygltf::Skin& source = model_.skins[static_cast<size_t>(skinIndex)];
    const std::string what = "skin " + std::to_string(skinIndex);
    if (source.joints.empty()) ctx_.refuse(what + " has no joints");
    if (source.joints.size() > static_cast<size_t>(ctx_.limits.maxSkinJoints))
      ctx_.refuse(what + " has " + std::to_string(source.joints.size()) + " joints, over the limit of " +
                  std::to_string(ctx_.limits.maxSkinJoints));
    Skin skin;
    skin.name = source.name;
    for (size_t j = 0; j < source.joints.size(); ++j) {
      const int joint = source.joints[j];
      if (joint < 0 || static_cast<size_t>(joint) >= model_.nodes.size())
        ctx_.refuse(what + " joint " + std::to_string(j) + " is node " + std::to_string(joint) +
                    ", which does not exist");
      const std::vector<int>& copies = copies_[static_cast<size_t>(joint)];
      if (copies.empty())
        ctx_.refuse(what + " joint " + std::to_string(j) + " is node " + std::to_string(joint) +
                    ", which is not in the default scene");
      if (copies.size() > 1)
        ctx_.report.warnings.push_back(what + " joint " + std::to_string(j) + " is node " + std::to_string(joint) +
                                       ", reached by several paths; the first is used");
      skin.joints.push_back(copies.front());
    }
    skin.inverseBind.assign(skin.joints.size(), glm::mat4(1.0f));
    if (source.inverseBindMatrices >= 0) {
      const std::vector<double> matrices = readAccessor(ctx_, source.inverseBindMatrices,
                                                        what + " inverseBindMatrices", 16,
                                                        {TINYGLTF_COMPONENT_TYPE_FLOAT});
      if (matrices.size() / 16 < skin.joints.size())
        ctx_.refuse(what + " has " + std::to_string(matrices.size() / 16) + " inverse bind matrices for " +
                    std::to_string(skin.joints.size()) + " joints");
      if (!allFinite(matrices)) ctx_.refuse(what + " has an inverse bind matrix that is not finite");
      for (size_t j = 0; j < skin.joints.size(); ++j)
        for (int i = 0; i < 16; ++i)
          glm::value_ptr(skin.inverseBind[j])[i] = static_cast<float>(matrices[j * 16 + static_cast<size_t>(i)]);
    }
    // Only a hint of the joints' common root (glTF 2.0 sec. 3.7.3.2): kept where it is a loaded node.
    if (source.skeleton >= 0 && static_cast<size_t>(source.skeleton) < model_.nodes.size() &&
        !copies_[static_cast<size_t>(source.skeleton)].empty())
      skin.skeleton = copies_[static_cast<size_t>(source.skeleton)].front();
    const int index = static_cast<int>(scene_.skins.size());
    scene_.skins.push_back(std::move(skin));
    skins_[skinIndex] = index;
    return index;
  }

  // One instance per drawable primitive of every node with a mesh, in node order, at the node's rest world matrix.
  void placeInstances() {
    std::uint64_t triangles = 0;
    for (size_t n = 0; n < scene_.nodes.size(); ++n) {
      const int nodeIndex = sourceNode_[n];
      const tinygltf::Node& source = model_.nodes[static_cast<size_t>(nodeIndex)];
      if (source.mesh < 0) continue;
      if (source.skin >= 0 && static_cast<size_t>(source.skin) >= model_.skins.size())
        ctx_.refuse("node " + std::to_string(nodeIndex) + " refers to skin " + std::to_string(source.skin) +
                    ", which does not exist");
      const tinygltf::Mesh& mesh = model_.meshes[static_cast<size_t>(source.mesh)];
      bool anySkinned = false;
      for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        const bool skinned = source.skin >= 0 && attributeAccessor(mesh.primitives[p], "JOINTS_0") >= 0;
        const int meshIndex = primitiveMesh(source.mesh, p, skinned);
        const auto lines = lineMeshes_.find(std::make_tuple(source.mesh, p, skinned));
        if (lines != lineMeshes_.end()) {
          scene_.lineInstances.push_back({lines->second, restWorld_[n], static_cast<int>(n)});
          if (scene_.lineInstances.size() > ctx_.limits.maxInstances)
            ctx_.refuse("places more than " + std::to_string(ctx_.limits.maxInstances) + " point or line instances");
        }
        if (meshIndex < 0) continue;
        Instance instance;
        instance.mesh = meshIndex;
        instance.world = restWorld_[n];
        instance.node = static_cast<int>(n);
        if (skinned) {
          anySkinned = true;
          instance.skin = sceneSkin(source.skin);
          const size_t jointCount = scene_.skins[static_cast<size_t>(instance.skin)].joints.size();
          const int maxJoint = maxJoint_[static_cast<size_t>(meshIndex)];
          if (maxJoint >= static_cast<int>(jointCount))
            ctx_.refuse("mesh " + std::to_string(source.mesh) + " primitive " + std::to_string(p) +
                        " has joint index " + std::to_string(maxJoint) + " but skin " + std::to_string(source.skin) +
                        " has " + std::to_string(jointCount) + " joints");
        }
        scene_.instances.push_back(instance);
        triangles += scene_.meshes[static_cast<size_t>(meshIndex)].indices.size() / 3;
        if (scene_.instances.size() > ctx_.limits.maxInstances)
          ctx_.refuse("places more than " + std::to_string(ctx_.limits.maxInstances) + " mesh instances");
        if (triangles > ctx_.limits.maxSceneTriangles)
          ctx_.refuse("has more than " + std::to_string(ctx_.limits.maxSceneTriangles) + " triangles after instancing");
      }
      if (source.skin >= 0 && !anySkinned && !mesh.primitives.empty())
        ctx_.report.warnings.push_back("node " + std::to_string(nodeIndex) + " has skin " +
                                       std::to_string(source.skin) + " but its mesh has no JOINTS_0; drawn rigid");
    }
  }

  // Reads a sampler for a channel of `path` with `components` values per key (glTF 2.0 sec. 3.11, 5.6):
  // input float SCALAR times, finite and strictly increasing; output float VEC3 (translation, scale), VEC4 float
  // or normalised integers (rotation), SCALAR float or normalised integers (weights, one per morph target per key).
  AnimationSampler loadSampler(int animationIndex, int samplerIndex, AnimationPath path, int components) {
    const tinygltf::AnimationSampler& source =
        model_.animations[static_cast<size_t>(animationIndex)].samplers[static_cast<size_t>(samplerIndex)];
    const std::string what = "animation " + std::to_string(animationIndex) + " sampler " + std::to_string(samplerIndex);
    AnimationSampler sampler;
    sampler.components = components;
    if (source.interpolation == "LINEAR") sampler.interpolation = Interpolation::Linear;
    else if (source.interpolation == "STEP") sampler.interpolation = Interpolation::Step;
    else if (source.interpolation == "CUBICSPLINE") sampler.interpolation = Interpolation::CubicSpline;
    else ctx_.refuse(what + " has interpolation '" + source.interpolation + "', not LINEAR, STEP or CUBICSPLINE");

    // The budget is charged from the accessors' declared counts before reading them (readAccessor checks bounds).
    for (int accessor : {source.input, source.output}) {
      if (accessor < 0 || static_cast<size_t>(accessor) >= model_.accessors.size())
        ctx_.refuse(what + " refers to accessor " + std::to_string(accessor) + ", which does not exist");
      const tinygltf::Accessor& a = model_.accessors[static_cast<size_t>(accessor)];
      ctx_.budget.animationValues += std::uint64_t(a.count) * std::max(componentCount(a.type), 1);
    }
    if (ctx_.budget.animationValues > ctx_.limits.maxAnimationValues)
      ctx_.refuse(what + ": more than " + std::to_string(ctx_.limits.maxAnimationValues) +
                  " animation values in the scene");

    const std::vector<double> times = readAccessor(ctx_, source.input, what + " input", 1,
                                                   {TINYGLTF_COMPONENT_TYPE_FLOAT});
    if (times.empty()) ctx_.refuse(what + " input has no key times");
    for (size_t k = 0; k < times.size(); ++k) {
      if (!std::isfinite(times[k])) ctx_.refuse(what + " input time " + std::to_string(k) + " is not finite");
      if (k > 0 && !(times[k] > times[k - 1]))
        ctx_.refuse(what + " input time " + std::to_string(k) + " (" + std::to_string(times[k]) +
                    ") is not after the one before (" + std::to_string(times[k - 1]) + ")");
    }
    if (times.front() < 0.0)
      ctx_.report.warnings.push_back(what + " starts at " + std::to_string(times.front()) +
                                     " s (glTF requires times >= 0); what comes before 0 never plays");

    const bool vector = path != AnimationPath::Weights;
    std::vector<int> allowed = {TINYGLTF_COMPONENT_TYPE_FLOAT};
    if (path == AnimationPath::Rotation || path == AnimationPath::Weights)
      allowed.insert(allowed.end(), {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                     TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
    const std::vector<double> values =
        readAccessor(ctx_, source.output, what + " output", vector ? components : 1, allowed);
    const tinygltf::Accessor& output = model_.accessors[static_cast<size_t>(source.output)];
    if (output.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !output.normalized)
      ctx_.refuse(what + " output (accessor " + std::to_string(source.output) + ") has component type " +
                  componentTypeName(output.componentType) + " without normalized: true, which glTF does not allow");
    const int perKey = sampler.interpolation == Interpolation::CubicSpline ? 3 : 1;
    const std::uint64_t expected = std::uint64_t(times.size()) * perKey * std::uint64_t(components);
    if (values.size() != expected)
      ctx_.refuse(what + " has " + std::to_string(vector ? values.size() / components : values.size()) +
                  " output values for " + std::to_string(times.size()) + " key times (expected " +
                  std::to_string(vector ? expected / components : expected) + ": " +
                  (perKey == 3 ? "3 per key for CUBICSPLINE" : "1 per key") +
                  (vector ? "" : ", times " + std::to_string(components) + " morph targets") + ")");
    if (!allFinite(values)) ctx_.refuse(what + " output has a value that is not finite");
    if (path == AnimationPath::Rotation) {
      // Key rotations (not CUBICSPLINE tangents) must be quaternions a slerp can normalise.
      for (size_t k = 0; k < times.size(); ++k) {
        const size_t at = (k * perKey + (perKey == 3 ? 1 : 0)) * 4;
        const double length = std::sqrt(values[at] * values[at] + values[at + 1] * values[at + 1] +
                                        values[at + 2] * values[at + 2] + values[at + 3] * values[at + 3]);
        if (length < 1e-6) ctx_.refuse(what + " output rotation " + std::to_string(k) + " is a zero quaternion");
      }
    }
    sampler.times.assign(times.begin(), times.end());
    sampler.values.assign(values.begin(), values.end());
    return sampler;
  }

  void loadAnimations() {
    for (size_t a = 0; a < model_.animations.size(); ++a) {
      const tinygltf::Animation& source = model_.animations[a];
      const std::string what = "animation " + std::to_string(a);
      Animation animation;
      animation.name = source.name;
      struct LoadedSampler {
        int index;
        AnimationPath path;
        int components;
      };
      std::map<int, LoadedSampler> samplers;           // by glTF sampler
      std::map<std::pair<int, std::string>, size_t> targets;  // (node, path) -> the first channel on it
      int outsideHierarchy = 0, unknownPath = 0, withoutNode = 0;
      for (size_t c = 0; c < source.channels.size(); ++c) {
        const tinygltf::AnimationChannel& channel = source.channels[c];
        const std::string channelWhat = what + " channel " + std::to_string(c);
        if (channel.target_node < 0) {
          ++withoutNode;
          continue;
        }
        if (static_cast<size_t>(channel.target_node) >= model_.nodes.size())
          ctx_.refuse(channelWhat + " targets node " + std::to_string(channel.target_node) + ", which does not exist");
        AnimationPath path;
        if (channel.target_path == "translation") path = AnimationPath::Translation;
        else if (channel.target_path == "rotation") path = AnimationPath::Rotation;
        else if (channel.target_path == "scale") path = AnimationPath::Scale;
        else if (channel.target_path == "weights") path = AnimationPath::Weights;
        else {
          ++unknownPath;
          continue;
        }
        if (channel.sampler < 0 || static_cast<size_t>(channel.sampler) >= source.samplers.size())
          ctx_.refuse(channelWhat + " refers to sampler " + std::to_string(channel.sampler) +
                      ", which does not exist");
        // glTF 2.0 sec. 5.5: "Within one animation, each target ... MUST NOT be used more than once."
        const auto target = std::make_pair(channel.target_node, channel.target_path);
        if (targets.count(target))
          ctx_.refuse(channelWhat + " animates node " + std::to_string(channel.target_node) + " " +
                      channel.target_path + ", as channel " + std::to_string(targets[target]) + " does");
        targets[target] = c;
        const std::vector<int>& copies = copies_[static_cast<size_t>(channel.target_node)];
        if (copies.empty()) {
          ++outsideHierarchy;
          continue;
        }
        // glTF 2.0 sec. 3.5.2: a node targeted by an animation has TRS, never a matrix.
        if (scene_.nodes[static_cast<size_t>(copies.front())].hasMatrix)
          ctx_.refuse(channelWhat + " animates node " + std::to_string(channel.target_node) +
                      ", which has a matrix (glTF allows animating only TRS nodes)");
        int components = path == AnimationPath::Rotation ? 4 : 3;
        if (path == AnimationPath::Weights) {
          components = static_cast<int>(scene_.nodes[static_cast<size_t>(copies.front())].weights.size());
          if (components == 0)
            ctx_.refuse(channelWhat + " animates the weights of node " + std::to_string(channel.target_node) +
                        ", which has no morph targets");
        }
        auto loaded = samplers.find(channel.sampler);
        if (loaded == samplers.end()) {
          animation.samplers.push_back(loadSampler(static_cast<int>(a), channel.sampler, path, components));
          loaded = samplers
                       .emplace(channel.sampler,
                                LoadedSampler{static_cast<int>(animation.samplers.size()) - 1, path, components})
                       .first;
        } else if (loaded->second.components != components ||
                   (loaded->second.path == AnimationPath::Rotation) != (path == AnimationPath::Rotation)) {
          ctx_.refuse(channelWhat + " shares sampler " + std::to_string(channel.sampler) +
                      " with a channel that needs other values");
        }
        for (int node : copies) animation.channels.push_back({loaded->second.index, node, path});
      }
      if (outsideHierarchy > 0)
        ctx_.report.warnings.push_back(what + ": " + std::to_string(outsideHierarchy) +
                                       " channels target nodes outside the default scene; skipped");
      if (unknownPath > 0)
        ctx_.report.warnings.push_back(what + ": " + std::to_string(unknownPath) +
                                       " channels have a path other than translation, rotation, scale or weights; "
                                       "skipped");
      if (withoutNode > 0)
        ctx_.report.warnings.push_back(what + ": " + std::to_string(withoutNode) +
                                       " channels have no target node; skipped");
      scene_.animations.push_back(std::move(animation));
    }
  }

  const LoaderContext& ctx_;
  const tinygltf::Model& model_;
  Scene& scene_;
  std::vector<std::vector<int>> copies_;  // per glTF node: its Scene::nodes indices (several: reached by several paths)
  std::vector<int> sourceNode_;           // per Scene node: its glTF node
  std::vector<glm::mat4> restWorld_;      // per Scene node
  std::vector<int> path_;                 // glTF nodes from the root to the one visited, to detect cycles
  bool warnedSharedNode_ = false;
  bool warnedDirectional_ = false;
  std::map<int, size_t> targetCounts_;                        // per glTF mesh
  std::map<std::tuple<int, size_t, bool>, int> primitiveMeshes_;  // (mesh, primitive, skinned) -> Scene mesh
  std::vector<int> maxJoint_;                                 // per Scene mesh: its highest joint index, -1: none
  std::map<int, int> skins_;                                  // glTF skin -> Scene skin
  std::map<std::tuple<int, size_t, bool>, int> lineMeshes_;  // (mesh, primitive, skinned) -> Scene::lineMeshes
};

struct ImageLoadContext {
  const GltfLimits* limits;
  const tinygltf::Model* model;  // being filled by tinygltf: its buffers and buffer views are loaded before images
};

// tinygltf image callback: decodes to RGBA8 after checking the size, so a huge image header cannot exhaust memory.
bool loadImageRgba8(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                    const unsigned char* bytes, int size, void* userData) {
  const auto* context = static_cast<const ImageLoadContext*>(userData);
  const GltfLimits* limits = context->limits;
  // tinygltf 2.7 hands over an image's buffer view without checking that it lies inside its buffer (found by
  // fuzzing: a heap overflow in the PNG decoder). Check it here, before any byte is read.
  if (image->bufferView >= 0) {
    const auto& views = context->model->bufferViews;
    const auto& buffers = context->model->buffers;
    const bool inside = static_cast<size_t>(image->bufferView) < views.size() &&
                        views[static_cast<size_t>(image->bufferView)].buffer >= 0 &&
                        static_cast<size_t>(views[static_cast<size_t>(image->bufferView)].buffer) < buffers.size() &&
                        std::uint64_t(views[static_cast<size_t>(image->bufferView)].byteOffset) +
                                views[static_cast<size_t>(image->bufferView)].byteLength <=
                            buffers[static_cast<size_t>(views[static_cast<size_t>(image->bufferView)].buffer)]
                                .data.size();
    if (!inside) {
      if (err) *err += "image " + std::to_string(index) + ": its bufferView lies outside its buffer\n";
      return false;
    }
  }
  if (size <= 0) {
    if (err) *err += "image " + std::to_string(index) + ": no image data\n";
    return false;
  }
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes, size, &width, &height, &channels)) {
    if (err) *err += "image " + std::to_string(index) + ": unknown or corrupt image format\n";
    return false;
  }
  if (width < 1 || height < 1 || width > limits->maxImageDimension || height > limits->maxImageDimension) {
    if (err)
      *err += "image " + std::to_string(index) + " is " + std::to_string(width) + "x" + std::to_string(height) +
              ", over the limit of " + std::to_string(limits->maxImageDimension) + " per side\n";
    return false;
  }
  unsigned char* pixels = stbi_load_from_memory(bytes, size, &width, &height, &channels, 4);
  if (!pixels) {
    if (err) *err += "image " + std::to_string(index) + ": " + stbi_failure_reason() + "\n";
    return false;
  }
  image->width = width;
  image->height = height;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image.assign(pixels, pixels + size_t(width) * height * 4);
  stbi_image_free(pixels);
  return true;
}

// File access for tinygltf: on disk relative to the .gltf, or from the in-memory side files (web drops).
struct FileResolver {
  std::string baseDir;
  const std::map<std::string, std::vector<std::uint8_t>>* sideFiles = nullptr;
  std::uint64_t maxBytes = 0;
};

std::string relativeTo(const FileResolver& r, const std::string& path) {
  if (!r.baseDir.empty() && path.rfind(r.baseDir, 0) == 0) return path.substr(r.baseDir.size());
  return path;
}

bool fileExists(const std::string& path, void* user) {
  const auto* r = static_cast<const FileResolver*>(user);
  if (r->sideFiles) return r->sideFiles->count(relativeTo(*r, path)) != 0;
  return std::ifstream(path, std::ios::binary).good();
}

std::string expandPath(const std::string& path, void*) { return path; }

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const auto* r = static_cast<const FileResolver*>(user);
  if (r->sideFiles) {
    auto it = r->sideFiles->find(relativeTo(*r, path));
    if (it == r->sideFiles->end()) {
      if (err) *err += "file not provided: " + path + "\n";
      return false;
    }
    out->assign(it->second.begin(), it->second.end());
    return true;
  }
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) {
    if (err) *err += "cannot open " + path + "\n";
    return false;
  }
  const std::streamoff size = file.tellg();
  if (size < 0 || static_cast<std::uint64_t>(size) > r->maxBytes) {
    if (err) *err += path + " is larger than the limit\n";
    return false;
  }
  out->resize(static_cast<size_t>(size));
  file.seekg(0);
  file.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size));
  return file.good() || file.eof();
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not supported\n";
  return false;
}

// First line of a multi-line tinygltf message, trimmed.
std::string firstLine(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line.empty() ? "unknown error" : line;
}

// A required extension is loaded (compression, quantization), harmless, or the file is refused.
void refuseUnlessSupported(const Refusal& refuse, const std::string& extension) {
  if (kHarmlessRequiredExtensions.count(extension)) return;
  std::string why;
  if (compressionExtensionSupported(extension, &why)) return;
  refuse(why.empty() ? "requires unsupported extension " + extension : why);
}

// What the loader reads from the JSON apart from tinygltf: the asset's extensionsRequired, to name an extension this
// build cannot load when tinygltf fails on the file (a file that needs, say, Draco has accessors without buffer
// views, and the user should hear about the extension rather than about accessor 0), and per animation the channels
// whose target has no node (KHR_animation_pointer's), which tinygltf 2.7 drops with only an error line.
struct DocumentFacts {
  std::vector<std::string> requiredExtensions;
  std::vector<int> channelsWithoutNode;  // per animation
};

DocumentFacts scanDocument(std::string_view json) {
  DocumentFacts out;
  const nlohmann::json document = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (!document.is_object()) return out;
  if (document.contains("extensionsRequired") && document["extensionsRequired"].is_array())
    for (const auto& name : document["extensionsRequired"])
      if (name.is_string()) out.requiredExtensions.push_back(name.get<std::string>());
  if (document.contains("animations") && document["animations"].is_array()) {
    for (const auto& animation : document["animations"]) {
      int count = 0;
      if (animation.is_object() && animation.contains("channels") && animation["channels"].is_array())
        for (const auto& channel : animation["channels"])
          if (channel.is_object() && channel.contains("target") && channel["target"].is_object() &&
              !channel["target"].contains("node"))
            ++count;
      out.channelsWithoutNode.push_back(count);
    }
  }
  return out;
}

// tinygltf 2.7 checks a .glb's BIN chunk against the file's length without the chunk's own 8-byte header, and then
// copies a buffer from up to 8 bytes past the end of the file (found by the fuzzer: a heap-buffer-overflow in
// tinygltf::ParseBuffer). The chunk is checked here first, where tinygltf would accept it.
void checkGlbBinChunk(const Refusal& refuse, const std::vector<std::uint8_t>& glb) {
  if (glb.size() < 20 || std::memcmp(glb.data(), "glTF", 4) != 0) return;
  std::uint32_t length = 0, jsonLength = 0;
  std::memcpy(&length, glb.data() + 8, 4);
  std::memcpy(&jsonLength, glb.data() + 12, 4);
  const std::uint64_t binChunk = 20ull + jsonLength;
  if (length > glb.size() || binChunk + 12 > length) return;  // tinygltf refuses these, or there is no BIN chunk
  std::uint32_t binLength = 0;
  std::memcpy(&binLength, glb.data() + binChunk, 4);
  if (binChunk + 8 + binLength > length)
    refuse("the BIN chunk's " + std::to_string(binLength) + " bytes run past the end of the file (" +
           std::to_string(length) + " bytes)");
}

Scene loadWithResolver(const std::vector<std::uint8_t>& bytes, const std::string& name, FileResolver resolver,
                       GltfLoadReport* report, const GltfLimits& limits) {
  const Refusal refuse(name);
  if (bytes.empty()) refuse("file is empty");
  if (bytes.size() > limits.maxFileBytes) refuse("file is larger than " + std::to_string(limits.maxFileBytes) + " bytes");
  if (bytes.size() > 0xFFFFFFFFull) refuse("file is larger than 4 GiB");

  // tinygltf parses the JSON; the loader reads it again only where tinygltf's result leaves something out (most files,
  // and most fuzzer inputs, are parsed once): to mend a compressed file, to name a required extension when tinygltf
  // fails, to count the animation channels tinygltf dropped.
  const std::string_view json = gltfJsonText(bytes);
  // What tinygltf 2.7 refuses in compressed files, mended (GltfCompression.h).
  nlohmann::json compressed;
  if (mentionsCompression(json)) compressed = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  const std::vector<std::uint8_t> prepared = prepareCompressedDocument(bytes, compressed);
  const std::vector<std::uint8_t>& document = prepared.empty() ? bytes : prepared;
  checkGlbBinChunk(refuse, document);

  tinygltf::TinyGLTF gltf;
  resolver.maxBytes = limits.maxFileBytes;
  gltf.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &writeWholeFile, &resolver});
  tinygltf::Model model;
  ImageLoadContext imageContext{&limits, &model};
  gltf.SetImageLoader(&loadImageRgba8, &imageContext);

  std::string err, warn;
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  bool ok = false;
  try {
    ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn, document.data(),
                                            static_cast<unsigned>(document.size()), resolver.baseDir)
                : gltf.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(document.data()),
                                           static_cast<unsigned>(document.size()), resolver.baseDir);
  } catch (const std::exception& e) {
    err = std::string("malformed glTF: ") + e.what();
  }
  if (!ok) {
    // Not where the text is no JSON object (nlohmann failed in tinygltf, and would again), nor where extensionsRequired
    // is not in it (it could only be there spelt with escapes, backslash u).
    const bool notAnObject = err.rfind("[json.exception.", 0) == 0 || err.rfind("Root element is not a JSON", 0) == 0;
    if (!notAnObject && (json.find("extensionsRequired") != std::string_view::npos ||
                         json.find("\\u") != std::string_view::npos))
      for (const std::string& ext : scanDocument(json).requiredExtensions) refuseUnlessSupported(refuse, ext);
    refuse(firstLine(err.empty() ? warn : err));
  }

  GltfLoadReport localReport;
  GltfLoadReport& out = report ? *report : localReport;
  if (!warn.empty()) out.warnings.push_back(firstLine(warn));
  const bool droppedChannels = err.find("field is missing in animation.channels.target") != std::string::npos;
  const DocumentFacts facts = droppedChannels ? scanDocument(json) : DocumentFacts{};
  for (size_t a = 0; a < facts.channelsWithoutNode.size(); ++a)
    if (facts.channelsWithoutNode[a] > 0)
      out.warnings.push_back("animation " + std::to_string(a) + ": " + std::to_string(facts.channelsWithoutNode[a]) +
                             " channels have no target node (KHR_animation_pointer?); skipped");
  for (const std::string& ext : model.extensionsRequired) refuseUnlessSupported(refuse, ext);
  decompressGltfModel(model, name, limits, out);

  LoadBudget budget;
  const LoaderContext ctx{model, limits, refuse, out, budget};
  Scene scene;
  scene.name = name;
  loadMaterials(ctx, scene);
  SceneBuilder(ctx, scene).build();
  if (scene.instances.empty() && scene.lineInstances.empty())
    refuse("contains no triangle, line or point geometry in its default scene");
  const Bounds bounds = scene.worldBounds();
  const glm::vec3 extent = bounds.max - bounds.min;
  if (!std::isfinite(extent.x + extent.y + extent.z)) refuse("scene bounds are not finite after node transforms");
  return scene;
}

}  // namespace

Scene loadGltfFile(const std::string& path, GltfLoadReport* report, const GltfLimits& limits) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) throw InputError(path + ": cannot open file");
  const std::streamoff size = file.tellg();
  if (size < 0) throw InputError(path + ": cannot read file");
  if (static_cast<std::uint64_t>(size) > limits.maxFileBytes)
    throw InputError(path + ": file is larger than " + std::to_string(limits.maxFileBytes) + " bytes");
  std::vector<std::uint8_t> bytes(static_cast<size_t>(size));
  file.seekg(0);
  file.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (!file) throw InputError(path + ": cannot read file");
  FileResolver resolver;
  const size_t slash = path.find_last_of('/');
  resolver.baseDir = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
  return loadWithResolver(bytes, path, resolver, report, limits);
}

Scene loadGltfMemory(const std::vector<std::uint8_t>& bytes, const std::string& name,
                     const std::map<std::string, std::vector<std::uint8_t>>& sideFiles, GltfLoadReport* report,
                     const GltfLimits& limits) {
  FileResolver resolver;
  resolver.sideFiles = &sideFiles;
  return loadWithResolver(bytes, name, resolver, report, limits);
}

}  // namespace obscura
