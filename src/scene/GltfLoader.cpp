#include "scene/GltfLoader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <set>
#include <string_view>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <stb_image.h>
#include <tiny_gltf.h>

#include "base/Error.h"
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

struct LoaderContext {
  const tinygltf::Model& model;
  const GltfLimits& limits;
  Refusal refuse;
  GltfLoadReport& report;
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

// Removes triangles with repeated vertices or zero area; they cover no pixels and break normal generation.
size_t dropDegenerateTriangles(Mesh& mesh) {
  std::vector<std::uint32_t> kept;
  kept.reserve(mesh.indices.size());
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    if (a == b || b == c || a == c) continue;
    const glm::vec3 cross = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    if (!(glm::dot(cross, cross) > 0.0f)) continue;
    kept.insert(kept.end(), {a, b, c});
  }
  const size_t dropped = (mesh.indices.size() - kept.size()) / 3;
  mesh.indices = std::move(kept);
  return dropped;
}

// KHR_texture_transform on the base colour texture, as the matrix that maps TEXCOORD_0 to the coordinates sampled:
// uv' = T(offset) * R(rotation) * S(scale) * uv. The extension's README lists R as the usual counter-clockwise matrix,
// but in glTF's UV space (v pointing down) the sample model TextureTransformTest, Babylon.js and three.js all use
// u' = cos r u + sin r v, v' = -sin r u + cos r v (KhronosGroup/glTF issue #1563); so does this.
// Identity when the material has no such extension. Scales and offsets that are not finite are refused.
glm::mat3 baseColorUvTransform(const LoaderContext& ctx, int materialIndex, const std::string& what) {
  if (materialIndex < 0 || static_cast<size_t>(materialIndex) >= ctx.model.materials.size()) return glm::mat3(1.0f);
  const tinygltf::TextureInfo& info = ctx.model.materials[static_cast<size_t>(materialIndex)]
                                          .pbrMetallicRoughness.baseColorTexture;
  const auto it = info.extensions.find("KHR_texture_transform");
  if (info.index < 0 || it == info.extensions.end() || !it->second.IsObject()) return glm::mat3(1.0f);
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

Mesh loadPrimitive(const LoaderContext& ctx, const tinygltf::Primitive& primitive, const std::string& what,
                   bool* skipped) {
  Mesh mesh;
  *skipped = false;
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    if (mode < 0 || mode > 6) ctx.refuse(what + " has primitive mode " + std::to_string(mode) + ", not a glTF mode");
    *skipped = true;  // points and lines have no surface to occlude
    return mesh;
  }
  auto attribute = [&](const char* name) {
    auto it = primitive.attributes.find(name);
    return it == primitive.attributes.end() ? -1 : it->second;
  };
  const int positionAccessor = attribute("POSITION");
  if (positionAccessor < 0) ctx.refuse(what + " has no POSITION attribute");
  mesh.positions = toVectors<3>(readAccessor(ctx, positionAccessor, what + " POSITION", 3,
                                             {TINYGLTF_COMPONENT_TYPE_FLOAT}));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      ctx.refuse(what + " POSITION " + std::to_string(i) + " is not finite (NaN or Inf)");
  }
  const size_t vertexCount = mesh.positions.size();

  const int normalAccessor = attribute("NORMAL");
  bool normalsUsable = false;
  if (normalAccessor >= 0) {
    mesh.normals = toVectors<3>(readAccessor(ctx, normalAccessor, what + " NORMAL", 3, {TINYGLTF_COMPONENT_TYPE_FLOAT}));
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
    mesh.texcoords = toVectors<2>(readAccessor(ctx, uvAccessor, what + " TEXCOORD_0", 2,
                                               {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}));
    // glTF 2.0 (3.7.2.1) allows integer texture coordinates only normalised; raw integers would be read as
    // coordinates hundreds of textures wide.
    const tinygltf::Accessor& uvs = ctx.model.accessors[static_cast<size_t>(uvAccessor)];
    if (uvs.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !uvs.normalized)
      ctx.refuse(what + " TEXCOORD_0 (accessor " + std::to_string(uvAccessor) + ") has component type " +
                 componentTypeName(uvs.componentType) + " without normalized: true, which glTF does not allow");
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

  mesh.indices = triangleIndices(ctx, primitive, vertexCount, what);
  const size_t dropped = dropDegenerateTriangles(mesh);
  if (dropped > 0)
    ctx.report.warnings.push_back(what + ": dropped " + std::to_string(dropped) + " degenerate triangles");
  if (primitive.material >= 0 && static_cast<size_t>(primitive.material) >= ctx.model.materials.size())
    ctx.refuse(what + " refers to material " + std::to_string(primitive.material) + ", which does not exist");
  mesh.material = primitive.material;
  if (!normalsUsable) generateFlatNormals(mesh);
  return mesh;
}

glm::mat4 nodeTransform(const LoaderContext& ctx, const tinygltf::Node& node, int index) {
  auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  if (node.matrix.size() == 16) {
    if (!finite(node.matrix)) ctx.refuse("node " + std::to_string(index) + " has a non-finite matrix");
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(node.matrix[static_cast<size_t>(i)]);
    return m;
  }
  if (!node.matrix.empty()) ctx.refuse("node " + std::to_string(index) + " has a matrix of " +
                                       std::to_string(node.matrix.size()) + " numbers, expected 16");
  glm::mat4 m(1.0f);
  if (!node.translation.empty()) {
    if (node.translation.size() != 3 || !finite(node.translation))
      ctx.refuse("node " + std::to_string(index) + " has an invalid translation");
    m = glm::translate(m, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4 || !finite(node.rotation))
      ctx.refuse("node " + std::to_string(index) + " has an invalid rotation");
    glm::quat q(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
    const float length = glm::length(q);
    if (length < 1e-6f) ctx.refuse("node " + std::to_string(index) + " has a zero rotation quaternion");
    m *= glm::mat4_cast(q / length);
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3 || !finite(node.scale))
      ctx.refuse("node " + std::to_string(index) + " has an invalid scale");
    m = glm::scale(m, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
  }
  return m;
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
    if (source.alphaMode == "MASK") material.alphaMode = AlphaMode::Mask;
    else if (source.alphaMode == "BLEND") material.alphaMode = AlphaMode::Blend;
    material.alphaCutoff = std::isfinite(source.alphaCutoff) ? static_cast<float>(source.alphaCutoff) : 0.5f;
    material.doubleSided = source.doubleSided;
    scene.materials.push_back(material);
  }
}

void loadNodes(const LoaderContext& ctx, Scene& scene) {
  const tinygltf::Model& model = ctx.model;
  // Each glTF (mesh, primitive) becomes one Mesh; remember where each glTF mesh's primitives start.
  std::vector<std::vector<int>> primitiveMeshes(model.meshes.size());
  std::vector<bool> loaded(model.meshes.size(), false);
  int skippedPrimitives = 0;  // points and lines
  auto meshPieces = [&](int meshIndex) -> const std::vector<int>& {
    if (!loaded[static_cast<size_t>(meshIndex)]) {
      loaded[static_cast<size_t>(meshIndex)] = true;
      const tinygltf::Mesh& source = model.meshes[static_cast<size_t>(meshIndex)];
      for (size_t p = 0; p < source.primitives.size(); ++p) {
        bool skipped = false;
        Mesh mesh = loadPrimitive(ctx, source.primitives[p],
                                  "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(p), &skipped);
        if (skipped) ++skippedPrimitives;
        if (skipped || mesh.indices.empty()) continue;
        primitiveMeshes[static_cast<size_t>(meshIndex)].push_back(static_cast<int>(scene.meshes.size()));
        scene.meshes.push_back(std::move(mesh));
      }
    }
    return primitiveMeshes[static_cast<size_t>(meshIndex)];
  };

  std::uint64_t triangles = 0;
  std::vector<int> path;  // nodes from the root to the current one, to detect cycles
  std::function<void(int, const glm::mat4&)> visit = [&](int nodeIndex, const glm::mat4& parent) {
    if (nodeIndex < 0 || static_cast<size_t>(nodeIndex) >= model.nodes.size())
      ctx.refuse("node " + std::to_string(nodeIndex) + " is referenced but does not exist");
    if (std::find(path.begin(), path.end(), nodeIndex) != path.end())
      ctx.refuse("node hierarchy has a cycle through node " + std::to_string(nodeIndex));
    if (static_cast<int>(path.size()) >= ctx.limits.maxNodeDepth)
      ctx.refuse("node hierarchy is deeper than " + std::to_string(ctx.limits.maxNodeDepth) + " levels");
    const tinygltf::Node& node = model.nodes[static_cast<size_t>(nodeIndex)];
    const glm::mat4 world = parent * nodeTransform(ctx, node, nodeIndex);
    if (node.mesh >= 0) {
      if (static_cast<size_t>(node.mesh) >= model.meshes.size())
        ctx.refuse("node " + std::to_string(nodeIndex) + " refers to mesh " + std::to_string(node.mesh) +
                   ", which does not exist");
      for (int meshIndex : meshPieces(node.mesh)) {
        scene.instances.push_back({meshIndex, world});
        triangles += scene.meshes[static_cast<size_t>(meshIndex)].indices.size() / 3;
        if (scene.instances.size() > ctx.limits.maxInstances)
          ctx.refuse("places more than " + std::to_string(ctx.limits.maxInstances) + " mesh instances");
        if (triangles > ctx.limits.maxSceneTriangles)
          ctx.refuse("has more than " + std::to_string(ctx.limits.maxSceneTriangles) + " triangles after instancing");
      }
    }
    path.push_back(nodeIndex);
    for (int child : node.children) visit(child, world);
    path.pop_back();
  };

  std::vector<int> roots;
  if (!model.scenes.empty()) {
    int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (static_cast<size_t>(sceneIndex) >= model.scenes.size())
      ctx.refuse("default scene " + std::to_string(sceneIndex) + " does not exist");
    roots = model.scenes[static_cast<size_t>(sceneIndex)].nodes;
  } else {
    // No scene: show every node that is nobody's child.
    std::vector<bool> isChild(model.nodes.size(), false);
    for (const tinygltf::Node& node : model.nodes)
      for (int child : node.children)
        if (child >= 0 && static_cast<size_t>(child) < isChild.size()) isChild[static_cast<size_t>(child)] = true;
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (!isChild[i]) roots.push_back(static_cast<int>(i));
  }
  for (int root : roots) visit(root, glm::mat4(1.0f));
  if (scene.instances.empty() && skippedPrimitives > 0)
    ctx.refuse("has only point or line primitives (" + std::to_string(skippedPrimitives) +
               "), which have no surfaces to shade");
}

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

// The asset's extensionsRequired, read before tinygltf parses the rest: a file that needs, say, Draco has
// accessors without buffer views, and the user should hear about the extension rather than about accessor 0.
std::vector<std::string> requiredExtensions(const std::vector<std::uint8_t>& bytes) {
  std::string_view json(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (bytes.size() >= 20 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
    std::uint32_t chunkLength = 0, chunkType = 0;
    std::memcpy(&chunkLength, bytes.data() + 12, 4);
    std::memcpy(&chunkType, bytes.data() + 16, 4);
    if (chunkType != 0x4E4F534Au || chunkLength > bytes.size() - 20) return {};  // "JSON"; tinygltf will complain
    json = json.substr(20, chunkLength);
  }
  const nlohmann::json document = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  std::vector<std::string> out;
  if (document.is_object() && document.contains("extensionsRequired") && document["extensionsRequired"].is_array())
    for (const auto& name : document["extensionsRequired"])
      if (name.is_string()) out.push_back(name.get<std::string>());
  return out;
}

Scene loadWithResolver(const std::vector<std::uint8_t>& bytes, const std::string& name, FileResolver resolver,
                       GltfLoadReport* report, const GltfLimits& limits) {
  const Refusal refuse(name);
  if (bytes.empty()) refuse("file is empty");
  if (bytes.size() > limits.maxFileBytes) refuse("file is larger than " + std::to_string(limits.maxFileBytes) + " bytes");
  if (bytes.size() > 0xFFFFFFFFull) refuse("file is larger than 4 GiB");

  for (const std::string& ext : requiredExtensions(bytes))
    if (!kHarmlessRequiredExtensions.count(ext)) refuse("requires unsupported extension " + ext);

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
    ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()),
                                            resolver.baseDir)
                : gltf.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                           static_cast<unsigned>(bytes.size()), resolver.baseDir);
  } catch (const std::exception& e) {
    refuse(std::string("malformed glTF: ") + e.what());
  }
  if (!ok) refuse(firstLine(err.empty() ? warn : err));

  GltfLoadReport localReport;
  GltfLoadReport& out = report ? *report : localReport;
  if (!warn.empty()) out.warnings.push_back(firstLine(warn));
  for (const std::string& ext : model.extensionsRequired) {
    if (!kHarmlessRequiredExtensions.count(ext)) refuse("requires unsupported extension " + ext);
  }

  const LoaderContext ctx{model, limits, refuse, out};
  Scene scene;
  scene.name = name;
  loadMaterials(ctx, scene);
  loadNodes(ctx, scene);
  if (scene.instances.empty()) refuse("contains no triangle geometry in its default scene");
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
