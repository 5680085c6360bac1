#include "scene/GltfCompression.h"

#include <algorithm>
#include <cstring>
#include <memory>
#include <set>
#include <string_view>
#include <type_traits>

#include <nlohmann/json.hpp>

#if OBSCURA_HAS_DRACO
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wpedantic"
#endif
#include <draco/compression/decode.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
#endif
#if OBSCURA_HAS_MESHOPT
#include <meshoptimizer.h>
#endif

#include "base/Error.h"

namespace obscura {
namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";
constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr const char* kQuantization = "KHR_mesh_quantization";

[[noreturn]] void refuse(const std::string& file, const std::string& problem) {
  throw InputError(file + ": " + problem);
}

// A non-negative integer member of a tinygltf extension object, or `fallback` when absent.
std::int64_t integerMember(const tinygltf::Value& object, const char* key, std::int64_t fallback, bool* valid) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsNumber()) {
    *valid = false;
    return fallback;
  }
  const double number = value.GetNumberAsDouble();
  if (!(number >= 0.0 && number <= 9.0e15) || number != static_cast<double>(static_cast<std::int64_t>(number))) {
    *valid = false;
    return fallback;
  }
  return static_cast<std::int64_t>(number);
}

std::string stringMember(const tinygltf::Value& object, const char* key, const std::string& fallback) {
  if (!object.Has(key) || !object.Get(key).IsString()) return fallback;
  return object.Get(key).Get<std::string>();
}

// Decoded bytes over the whole file, against the same limit as the file itself: a few bytes of meshopt stream can
// claim gigabytes of output.
struct DecodeBudget {
  std::uint64_t bytes = 0;
  std::uint64_t limit = 0;
  void take(const std::string& file, const std::string& what, std::uint64_t amount) {
    bytes += amount;
    if (bytes > limit)
      refuse(file, what + " decodes to more than " + std::to_string(limit) + " bytes over the file, over the limit");
  }
};

// The bytes [offset, offset + length) of buffer `index`, checked.
const unsigned char* bufferRange(const tinygltf::Model& model, const std::string& file, const std::string& what,
                                 std::int64_t index, std::uint64_t offset, std::uint64_t length) {
  if (index < 0 || static_cast<std::uint64_t>(index) >= model.buffers.size())
    refuse(file, what + " refers to buffer " + std::to_string(index) + ", which does not exist");
  const tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(index)];
  if (offset > buffer.data.size() || length > buffer.data.size() - offset)
    refuse(file, what + " spans bytes " + std::to_string(offset) + ".." + std::to_string(offset + length) +
                     " but buffer " + std::to_string(index) + " holds " + std::to_string(buffer.data.size()) +
                     " bytes");
  return buffer.data.data() + offset;
}

// ---------------------------------------------------------------------------------------------------------------------
// EXT_meshopt_compression
// (https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Vendor/EXT_meshopt_compression)

void decodeMeshoptViews(tinygltf::Model& model, const std::string& file, const GltfLimits& limits,
                        DecodeBudget& budget) {
  const size_t viewCount = model.bufferViews.size();  // views appended below are decoded ones
  for (size_t v = 0; v < viewCount; ++v) {
    const auto found = model.bufferViews[v].extensions.find(kMeshopt);
    if (found == model.bufferViews[v].extensions.end()) continue;
    const std::string what = "bufferView " + std::to_string(v) + " " + kMeshopt;
    const tinygltf::Value& ext = found->second;
    if (!ext.IsObject()) refuse(file, what + " is not an object");
    bool valid = true;
    const std::int64_t buffer = integerMember(ext, "buffer", -1, &valid);
    const std::int64_t byteOffset = integerMember(ext, "byteOffset", 0, &valid);
    const std::int64_t byteLength = integerMember(ext, "byteLength", -1, &valid);
    const std::int64_t byteStride = integerMember(ext, "byteStride", -1, &valid);
    const std::int64_t count = integerMember(ext, "count", -1, &valid);
    const std::string mode = stringMember(ext, "mode", "");
    const std::string filter = stringMember(ext, "filter", "NONE");
    if (!valid || buffer < 0 || byteLength < 0 || byteStride <= 0 || count < 0)
      refuse(file, what + " lacks buffer, byteLength, byteStride or count, or has one that is not a count");
    if (static_cast<std::uint64_t>(count) > limits.maxAccessorElements)
      refuse(file, what + " has " + std::to_string(count) + " elements, over the limit of " +
                       std::to_string(limits.maxAccessorElements));
    const unsigned char* source = bufferRange(model, file, what, buffer, static_cast<std::uint64_t>(byteOffset),
                                              static_cast<std::uint64_t>(byteLength));
    const size_t elements = static_cast<size_t>(count), stride = static_cast<size_t>(byteStride);
    const size_t length = static_cast<size_t>(byteLength);
    budget.take(file, what, std::uint64_t(elements) * stride);
#if OBSCURA_HAS_MESHOPT
    std::vector<unsigned char> decoded(elements * stride);
    int status = 0;
    if (mode == "ATTRIBUTES") {
      if (stride % 4 != 0 || stride > 256)
        refuse(file, what + ": ATTRIBUTES byteStride must be a multiple of 4 up to 256");
      status = meshopt_decodeVertexBuffer(decoded.data(), elements, stride, source, length);
    } else if (mode == "TRIANGLES" || mode == "INDICES") {
      if (stride != 2 && stride != 4) refuse(file, what + ": " + mode + " byteStride must be 2 or 4");
      if (mode == "TRIANGLES" && elements % 3 != 0) refuse(file, what + ": TRIANGLES count is not a multiple of 3");
      status = mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(decoded.data(), elements, stride, source, length)
                                   : meshopt_decodeIndexSequence(decoded.data(), elements, stride, source, length);
    } else {
      refuse(file, what + " has mode '" + mode + "', expected ATTRIBUTES, TRIANGLES or INDICES");
    }
    if (status != 0) refuse(file, what + ": the compressed data is malformed (meshopt error " +
                                      std::to_string(status) + ")");
    // The filters decode in place; each has the strides the extension allows.
    if (filter == "OCTAHEDRAL") {
      if (mode != "ATTRIBUTES" || (stride != 4 && stride != 8))
        refuse(file, what + ": OCTAHEDRAL needs byteStride 4 or 8");
      meshopt_decodeFilterOct(decoded.data(), elements, stride);
    } else if (filter == "QUATERNION") {
      if (mode != "ATTRIBUTES" || stride != 8) refuse(file, what + ": QUATERNION needs byteStride 8");
      meshopt_decodeFilterQuat(decoded.data(), elements, stride);
    } else if (filter == "EXPONENTIAL") {
      if (mode != "ATTRIBUTES") refuse(file, what + ": EXPONENTIAL needs mode ATTRIBUTES");
      meshopt_decodeFilterExp(decoded.data(), elements, stride);
    } else if (filter != "NONE") {
      refuse(file, what + " has filter '" + filter + "', expected NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    }
    tinygltf::Buffer out;
    out.data = std::move(decoded);
    model.buffers.push_back(std::move(out));
    tinygltf::BufferView& view = model.bufferViews[v];
    view.buffer = static_cast<int>(model.buffers.size()) - 1;
    view.byteOffset = 0;
    view.byteLength = elements * stride;
    if (mode == "ATTRIBUTES") view.byteStride = stride;
    view.extensions.erase(kMeshopt);
#else
    (void)source;
    (void)elements;
    (void)stride;
    (void)length;
    refuse(file, what + ": this build has no meshoptimizer decoder");
#endif
  }
}

// ---------------------------------------------------------------------------------------------------------------------
// KHR_draco_mesh_compression
// (https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_draco_mesh_compression)

#if OBSCURA_HAS_DRACO
// A new buffer holding `data` and a buffer view over all of it; returns the view's index.
int appendBufferView(tinygltf::Model& model, std::vector<unsigned char> data, int byteStride) {
  tinygltf::Buffer buffer;
  buffer.data = std::move(data);
  tinygltf::BufferView view;
  view.buffer = static_cast<int>(model.buffers.size());
  view.byteOffset = 0;
  view.byteLength = buffer.data.size();
  view.byteStride = static_cast<size_t>(byteStride);
  model.buffers.push_back(std::move(buffer));
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

int accessorComponents(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
  }
}

template <typename T>
constexpr draco::DataType dracoTypeOf() {
  if constexpr (std::is_same_v<T, std::int8_t>) return draco::DT_INT8;
  if constexpr (std::is_same_v<T, std::uint8_t>) return draco::DT_UINT8;
  if constexpr (std::is_same_v<T, std::int16_t>) return draco::DT_INT16;
  if constexpr (std::is_same_v<T, std::uint16_t>) return draco::DT_UINT16;
  if constexpr (std::is_same_v<T, std::uint32_t>) return draco::DT_UINT32;
  if constexpr (std::is_same_v<T, float>) return draco::DT_FLOAT32;
  return draco::DT_INVALID;
}

template <typename T>
std::vector<unsigned char> convertDracoAttribute(const draco::PointAttribute& attribute, size_t points,
                                                 int components, bool* ok) {
  std::vector<unsigned char> out(points * sizeof(T) * static_cast<size_t>(components));
  const size_t valueBytes = sizeof(T) * static_cast<size_t>(components);
  if (attribute.data_type() == dracoTypeOf<T>() && attribute.num_components() == components) {
    // Stored as the accessor declares it: ConvertValue would copy each component unchanged, so the values are copied
    // as bytes (at once where every point has its own value in order), each checked to lie inside the buffer.
    const std::uint8_t* begin = attribute.buffer()->data();
    const std::uint8_t* end = begin + attribute.buffer()->data_size();
    auto inside = [&](const std::uint8_t* at, size_t bytes) {
      return at >= begin && at <= end && bytes <= static_cast<size_t>(end - at);
    };
    if (attribute.is_mapping_identity() && attribute.byte_stride() == static_cast<std::int64_t>(valueBytes) &&
        points <= attribute.size()) {
      const std::uint8_t* first = attribute.GetAddress(draco::AttributeValueIndex(0));
      if (!inside(first, out.size())) {
        *ok = false;
        return {};
      }
      std::memcpy(out.data(), first, out.size());
      return out;
    }
    for (size_t p = 0; p < points; ++p) {
      const draco::AttributeValueIndex index = attribute.mapped_index(draco::PointIndex(static_cast<std::uint32_t>(p)));
      const std::uint8_t* at = index.value() < attribute.size() ? attribute.GetAddress(index) : nullptr;
      if (!at || !inside(at, valueBytes)) {
        *ok = false;
        return {};
      }
      std::memcpy(out.data() + p * valueBytes, at, valueBytes);
    }
    return out;
  }
  std::vector<T> value(static_cast<size_t>(components));
  for (size_t p = 0; p < points; ++p) {
    const draco::AttributeValueIndex index = attribute.mapped_index(draco::PointIndex(static_cast<std::uint32_t>(p)));
    if (index.value() >= attribute.size() ||
        !attribute.ConvertValue<T>(index, static_cast<std::int8_t>(components), value.data())) {
      *ok = false;
      return {};
    }
    std::memcpy(out.data() + p * value.size() * sizeof(T), value.data(), value.size() * sizeof(T));
  }
  return out;
}

std::vector<unsigned char> convertDracoAttribute(const draco::PointAttribute& attribute, size_t points,
                                                 int componentType, int components, bool* ok) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return convertDracoAttribute<std::int8_t>(attribute, points, components, ok);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return convertDracoAttribute<std::uint8_t>(attribute, points, components, ok);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return convertDracoAttribute<std::int16_t>(attribute, points, components, ok);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return convertDracoAttribute<std::uint16_t>(attribute, points, components, ok);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return convertDracoAttribute<std::uint32_t>(attribute, points, components, ok);
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return convertDracoAttribute<float>(attribute, points, components, ok);
    default: *ok = false; return {};
  }
}
#endif

void decodeDracoPrimitives(tinygltf::Model& model, const std::string& file, const GltfLimits& limits,
                           GltfLoadReport& report, DecodeBudget& budget) {
  std::set<int> decodedAccessors;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
      const auto found = primitive.extensions.find(kDraco);
      if (found == primitive.extensions.end()) continue;
      const std::string what = "mesh " + std::to_string(m) + " primitive " + std::to_string(p) + " " + kDraco;
      const tinygltf::Value& ext = found->second;
      if (!ext.IsObject() || !ext.Has("attributes") || !ext.Get("attributes").IsObject())
        refuse(file, what + " has no attributes object");
      bool valid = true;
      const std::int64_t viewIndex = integerMember(ext, "bufferView", -1, &valid);
      if (!valid || viewIndex < 0 || static_cast<std::uint64_t>(viewIndex) >= model.bufferViews.size())
        refuse(file, what + " refers to a bufferView that does not exist");
      const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(viewIndex)];
      const unsigned char* source = bufferRange(model, file, what, view.buffer, view.byteOffset, view.byteLength);
#if OBSCURA_HAS_DRACO
      draco::DecoderBuffer stream;
      stream.Init(reinterpret_cast<const char*>(source), view.byteLength);
      draco::Decoder decoder;
      const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
      std::unique_ptr<draco::PointCloud> cloud;
      size_t faces = 0;
      std::vector<std::uint32_t> indices;
      if (mode == TINYGLTF_MODE_POINTS) {
        auto decoded = decoder.DecodePointCloudFromBuffer(&stream);
        if (!decoded.ok()) refuse(file, what + ": " + decoded.status().error_msg_string());
        cloud = std::move(decoded).value();
      } else if (mode == TINYGLTF_MODE_TRIANGLES) {
        auto decoded = decoder.DecodeMeshFromBuffer(&stream);
        if (!decoded.ok()) refuse(file, what + ": " + decoded.status().error_msg_string());
        std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
        faces = mesh->num_faces();
        if (faces > limits.maxAccessorElements / 3)
          refuse(file, what + " decodes to " + std::to_string(faces) + " triangles, over the limit");
        indices.reserve(faces * 3);
        for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
          for (int k = 0; k < 3; ++k) indices.push_back(mesh->face(f)[k].value());
        cloud = std::move(mesh);
      } else {
        refuse(file, what + " is on a primitive of mode " + std::to_string(mode) +
                         "; the extension compresses triangles and points only");
      }
      const size_t points = cloud->num_points();
      if (points > limits.maxAccessorElements)
        refuse(file, what + " decodes to " + std::to_string(points) + " vertices, over the limit");
      for (std::uint32_t index : indices)
        if (index >= points)
          refuse(file, what + " decodes to an index past its " + std::to_string(points) + " vertices");

      if (primitive.indices >= 0 && !decodedAccessors.count(primitive.indices)) {
        if (static_cast<size_t>(primitive.indices) >= model.accessors.size())
          refuse(file, what + " has indices accessor " + std::to_string(primitive.indices) + ", which does not exist");
        tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(primitive.indices)];
        if (accessor.count != indices.size())
          report.warnings.push_back(what + ": indices accessor declares " + std::to_string(accessor.count) +
                                    " indices, the compressed mesh holds " + std::to_string(indices.size()));
        std::vector<unsigned char> bytes(indices.size() * 4);
        if (!indices.empty()) std::memcpy(bytes.data(), indices.data(), bytes.size());
        budget.take(file, what, bytes.size());
        accessor.bufferView = appendBufferView(model, std::move(bytes), 0);
        accessor.byteOffset = 0;
        accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        accessor.count = indices.size();
        accessor.sparse.isSparse = false;
        decodedAccessors.insert(primitive.indices);
      }

      const tinygltf::Value& attributes = ext.Get("attributes");
      for (const std::string& name : attributes.Keys()) {
        const auto attribute = primitive.attributes.find(name);
        if (attribute == primitive.attributes.end())
          refuse(file, what + " compresses " + name + ", which the primitive does not list");
        const int accessorIndex = attribute->second;
        if (decodedAccessors.count(accessorIndex)) continue;
        if (accessorIndex < 0 || static_cast<size_t>(accessorIndex) >= model.accessors.size())
          refuse(file, what + " " + name + " refers to an accessor that does not exist");
        const tinygltf::Value& idValue = attributes.Get(name);
        if (!idValue.IsNumber() || idValue.GetNumberAsDouble() < 0 || idValue.GetNumberAsDouble() > 4.0e9)
          refuse(file, what + " " + name + " has an attribute id that is not a count");
        const draco::PointAttribute* source_attribute =
            cloud->GetAttributeByUniqueId(static_cast<std::uint32_t>(idValue.GetNumberAsDouble()));
        if (!source_attribute) refuse(file, what + " " + name + " names an attribute the compressed data lacks");
        tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(accessorIndex)];
        const int components = accessorComponents(accessor.type);
        if (components == 0 || components > source_attribute->num_components())
          refuse(file, what + " " + name + " has " + std::to_string(source_attribute->num_components()) +
                           " components, fewer than its accessor's");
        if (accessor.count != points)
          report.warnings.push_back(what + ": " + name + " accessor declares " + std::to_string(accessor.count) +
                                    " vertices, the compressed data holds " + std::to_string(points));
        bool converted = true;
        std::vector<unsigned char> bytes =
            convertDracoAttribute(*source_attribute, points, accessor.componentType, components, &converted);
        if (!converted) refuse(file, what + " " + name + " cannot be converted to its accessor's component type");
        budget.take(file, what, bytes.size());
        accessor.bufferView = appendBufferView(model, std::move(bytes), 0);
        accessor.byteOffset = 0;
        accessor.count = points;
        accessor.sparse.isSparse = false;
        decodedAccessors.insert(accessorIndex);
      }
      primitive.extensions.erase(kDraco);
#else
      (void)source;
      (void)limits;
      (void)report;
      (void)budget;
      refuse(file, what + ": this build has no Draco decoder");
#endif
    }
  }
}

bool listed(const std::vector<std::string>& names, const char* name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

bool hasDracoDecoder() { return OBSCURA_HAS_DRACO != 0; }
bool hasMeshoptDecoder() { return OBSCURA_HAS_MESHOPT != 0; }

bool compressionExtensionSupported(const std::string& extension, std::string* why) {
  if (extension == kQuantization) return true;
  if (extension == kDraco && !hasDracoDecoder()) {
    *why = "requires KHR_draco_mesh_compression, and this build has no Draco decoder (in the browser, obscura.js "
           "decodes it with the draco3d package)";
    return false;
  }
  if (extension == kMeshopt && !hasMeshoptDecoder()) {
    *why = "requires EXT_meshopt_compression, and this build has no meshoptimizer decoder (in the browser, "
           "obscura.js decodes it with the meshoptimizer package)";
    return false;
  }
  return extension == kDraco || extension == kMeshopt;
}

std::string_view gltfJsonText(const std::vector<std::uint8_t>& bytes) {
  const char* text = reinterpret_cast<const char*>(bytes.data());
  if (bytes.size() < 20 || std::memcmp(bytes.data(), "glTF", 4) != 0) return std::string_view(text, bytes.size());
  std::uint32_t chunkLength = 0, chunkType = 0;
  std::memcpy(&chunkLength, bytes.data() + 12, 4);
  std::memcpy(&chunkType, bytes.data() + 16, 4);
  if (chunkType != 0x4E4F534Au || chunkLength > bytes.size() - 20) return {};  // "JSON"
  return std::string_view(text + 20, chunkLength);
}

bool mentionsCompression(std::string_view json) {
  return json.find(kMeshopt) != std::string_view::npos || json.find(kDraco) != std::string_view::npos;
}

std::vector<std::uint8_t> prepareCompressedDocument(const std::vector<std::uint8_t>& bytes, nlohmann::json& document) {
  const bool binary = bytes.size() >= 20 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  const std::string_view view = gltfJsonText(bytes);
  const size_t jsonLength = view.size();
  if (!mentionsCompression(view) || !document.is_object()) return {};
  bool changed = false;
  if (document.contains("buffers") && document["buffers"].is_array()) {
    for (auto& buffer : document["buffers"]) {
      if (!buffer.is_object() || buffer.contains("uri") || !buffer.contains("extensions")) continue;
      const auto& extensions = buffer["extensions"];
      if (!extensions.is_object() || !extensions.contains(kMeshopt) || !extensions[kMeshopt].is_object()) continue;
      const auto& ext = extensions[kMeshopt];
      if (!ext.contains("fallback") || ext["fallback"] != true) continue;
      // The data exists only compressed; views into it are decoded into buffers of their own (decodeMeshoptViews),
      // and one that is not compressed is refused as lying outside its (3-byte) buffer. tinygltf 2.7 refuses an
      // empty data uri, hence 3 zero bytes.
      buffer["uri"] = "data:application/octet-stream;base64,AAAA";
      buffer["byteLength"] = 3;
      changed = true;
    }
  }
  // tinygltf 2.7 refuses a primitive whose indices accessor has no bufferView, which is how Draco primitives come
  // (the indices exist only compressed): point it at the Draco stream's view until decodeDracoPrimitives replaces it.
  if (hasDracoDecoder() && document.contains("meshes") && document["meshes"].is_array() &&
      document.contains("accessors") && document["accessors"].is_array()) {
    auto& accessors = document["accessors"];
    for (auto& mesh : document["meshes"]) {
      if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
      for (auto& primitive : mesh["primitives"]) {
        if (!primitive.is_object() || !primitive.contains("extensions") || !primitive["extensions"].is_object() ||
            !primitive["extensions"].contains(kDraco) || !primitive.contains("indices"))
          continue;
        const auto& ext = primitive["extensions"][kDraco];
        const auto& indices = primitive["indices"];
        if (!ext.is_object() || !ext.contains("bufferView") || !ext["bufferView"].is_number_unsigned() ||
            !indices.is_number_unsigned() || indices.get<std::uint64_t>() >= accessors.size())
          continue;
        auto& accessor = accessors[indices.get<size_t>()];
        if (!accessor.is_object() || accessor.contains("bufferView")) continue;
        accessor["bufferView"] = ext["bufferView"];
        changed = true;
      }
    }
  }
  if (!changed) return {};
  std::string json = document.dump();
  if (!binary) return std::vector<std::uint8_t>(json.begin(), json.end());
  while (json.size() % 4 != 0) json.push_back(' ');
  const size_t rest = 20 + jsonLength;  // the chunks after the JSON (BIN), copied as they are
  const size_t tailBegin = std::min(bytes.size(), rest);
  std::vector<std::uint8_t> out(12 + 8 + json.size() + (bytes.size() - tailBegin));
  std::memcpy(out.data(), bytes.data(), 8);  // magic and version
  // The header's total length moves by what the JSON chunk grew, and no more: a header that disagreed with the file
  // still disagrees, and tinygltf refuses the mended file as it would the original (found by the fuzzer: set to the
  // new size, it made a truncated BIN chunk look whole).
  std::uint32_t declared = 0;
  std::memcpy(&declared, bytes.data() + 8, 4);
  const std::uint64_t mendedTotal = std::uint64_t(declared) + json.size() - jsonLength;
  const std::uint32_t total = static_cast<std::uint32_t>(std::min<std::uint64_t>(mendedTotal, 0xFFFFFFFFu));
  const std::uint32_t length = static_cast<std::uint32_t>(json.size());
  const std::uint32_t type = 0x4E4F534Au;
  std::memcpy(out.data() + 8, &total, 4);
  std::memcpy(out.data() + 12, &length, 4);
  std::memcpy(out.data() + 16, &type, 4);
  std::memcpy(out.data() + 20, json.data(), json.size());
  if (tailBegin < bytes.size())
    std::memcpy(out.data() + 20 + json.size(), bytes.data() + tailBegin, bytes.size() - tailBegin);
  return out;
}

void decompressGltfModel(tinygltf::Model& model, const std::string& file, const GltfLimits& limits,
                         GltfLoadReport& report) {
  DecodeBudget budget;
  budget.limit = limits.maxFileBytes;
  const bool meshopt = listed(model.extensionsUsed, kMeshopt) || listed(model.extensionsRequired, kMeshopt);
  const bool draco = listed(model.extensionsUsed, kDraco) || listed(model.extensionsRequired, kDraco);
  // Without the decoder, a file that only *uses* an extension has uncompressed fallbacks: load those.
  if (meshopt && (hasMeshoptDecoder() || listed(model.extensionsRequired, kMeshopt)))
    decodeMeshoptViews(model, file, limits, budget);
  if (draco && (hasDracoDecoder() || listed(model.extensionsRequired, kDraco)))
    decodeDracoPrimitives(model, file, limits, report, budget);
}

bool usesMeshQuantization(const tinygltf::Model& model) {
  return listed(model.extensionsUsed, kQuantization) || listed(model.extensionsRequired, kQuantization);
}

AttributeTypes quantizedAttributeTypes(const std::string& use, bool quantized) {
  constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE, kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT, kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
  // glTF 2.0 core (3.7.2.1), then KHR_mesh_quantization's table.
  if (use == "TEXCOORD") {
    if (!quantized) return {{kFloat, kUByte, kUShort}, {kUByte, kUShort}};
    return {{kFloat, kByte, kUByte, kShort, kUShort}, {}};
  }
  if (!quantized) return {{kFloat}, {}};
  if (use == "POSITION" || use == "MORPH_POSITION") {
    if (use == "MORPH_POSITION") return {{kFloat, kByte, kShort}, {}};
    return {{kFloat, kByte, kUByte, kShort, kUShort}, {}};
  }
  if (use == "NORMAL" || use == "MORPH_NORMAL") return {{kFloat, kByte, kShort}, {kByte, kShort}};
  return {{kFloat}, {}};
}

}  // namespace obscura
