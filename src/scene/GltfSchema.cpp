#include "scene/GltfSchema.h"

namespace obscura::gltf {
namespace {

using nlohmann::json;

// A property's type in the glTF 2.0 JSON schema, as far as the loader reads it.
enum class Type {
  Any,
  Object,    // with the fields of a Shape
  Array,     // of `element`
  Number,
  Index,     // an integer >= 0 (glTF's glTFid)
  Integer,   // an integer >= 0 (counts, offsets, enums)
  String,
  Boolean,
  IndexMap,  // an object whose values are indices (a primitive's attributes)
};

struct Shape;
struct Field {
  const char* key;
  Type type;
  Type element = Type::Any;     // Array: its elements' type
  int length = 0;               // Array: its fixed length (0: any)
  const Shape* shape = nullptr;  // Object, or an Array of objects: their fields
};
struct Shape {
  std::vector<Field> fields;
};

const Shape kTextureInfo{{{"index", Type::Index}, {"texCoord", Type::Integer}}};
const Shape kNormalTextureInfo{{{"index", Type::Index}, {"texCoord", Type::Integer}, {"scale", Type::Number}}};
const Shape kOcclusionTextureInfo{{{"index", Type::Index}, {"texCoord", Type::Integer}, {"strength", Type::Number}}};
const Shape kPbr{{{"baseColorFactor", Type::Array, Type::Number, 4},
                  {"baseColorTexture", Type::Object, Type::Any, 0, &kTextureInfo},
                  {"metallicFactor", Type::Number},
                  {"roughnessFactor", Type::Number},
                  {"metallicRoughnessTexture", Type::Object, Type::Any, 0, &kTextureInfo}}};
const Shape kMaterial{{{"pbrMetallicRoughness", Type::Object, Type::Any, 0, &kPbr},
                       {"normalTexture", Type::Object, Type::Any, 0, &kNormalTextureInfo},
                       {"occlusionTexture", Type::Object, Type::Any, 0, &kOcclusionTextureInfo},
                       {"emissiveTexture", Type::Object, Type::Any, 0, &kTextureInfo},
                       {"emissiveFactor", Type::Array, Type::Number, 3},
                       {"alphaMode", Type::String},
                       {"alphaCutoff", Type::Number},
                       {"doubleSided", Type::Boolean}}};
const Shape kNode{{{"camera", Type::Index},
                   {"children", Type::Array, Type::Index},
                   {"skin", Type::Index},
                   {"matrix", Type::Array, Type::Number, 16},
                   {"mesh", Type::Index},
                   {"rotation", Type::Array, Type::Number, 4},
                   {"scale", Type::Array, Type::Number, 3},
                   {"translation", Type::Array, Type::Number, 3},
                   {"weights", Type::Array, Type::Number}}};
const Shape kScene{{{"nodes", Type::Array, Type::Index}}};
const Shape kTexture{{{"sampler", Type::Index}, {"source", Type::Index}}};
const Shape kSampler{{{"magFilter", Type::Integer},
                      {"minFilter", Type::Integer},
                      {"wrapS", Type::Integer},
                      {"wrapT", Type::Integer}}};
const Shape kImage{{{"uri", Type::String}, {"mimeType", Type::String}, {"bufferView", Type::Index}}};
const Shape kPrimitive{{{"attributes", Type::IndexMap},
                        {"indices", Type::Index},
                        {"material", Type::Index},
                        {"mode", Type::Integer},
                        {"targets", Type::Array, Type::IndexMap}}};
const Shape kMesh{{{"primitives", Type::Array, Type::Object, 0, &kPrimitive}, {"weights", Type::Array, Type::Number}}};
const Shape kAccessor{{{"bufferView", Type::Index},
                       {"byteOffset", Type::Integer},
                       {"componentType", Type::Integer},
                       {"normalized", Type::Boolean},
                       {"count", Type::Integer},
                       {"type", Type::String},
                       {"max", Type::Array, Type::Number},
                       {"min", Type::Array, Type::Number}}};
const Shape kBufferView{{{"buffer", Type::Index},
                         {"byteOffset", Type::Integer},
                         {"byteLength", Type::Integer},
                         {"byteStride", Type::Integer},
                         {"target", Type::Integer}}};
const Shape kBuffer{{{"uri", Type::String}, {"byteLength", Type::Integer}}};
const Shape kSkin{{{"inverseBindMatrices", Type::Index}, {"skeleton", Type::Index}, {"joints", Type::Array, Type::Index}}};
const Shape kChannelTarget{{{"node", Type::Index}, {"path", Type::String}}};
const Shape kChannel{{{"sampler", Type::Index}, {"target", Type::Object, Type::Any, 0, &kChannelTarget}}};
const Shape kAnimationSampler{{{"input", Type::Index}, {"interpolation", Type::String}, {"output", Type::Index}}};
const Shape kAnimation{{{"channels", Type::Array, Type::Object, 0, &kChannel},
                        {"samplers", Type::Array, Type::Object, 0, &kAnimationSampler}}};
const Shape kDocument{{{"scene", Type::Index},
                       {"scenes", Type::Array, Type::Object, 0, &kScene},
                       {"nodes", Type::Array, Type::Object, 0, &kNode},
                       {"meshes", Type::Array, Type::Object, 0, &kMesh},
                       {"materials", Type::Array, Type::Object, 0, &kMaterial},
                       {"textures", Type::Array, Type::Object, 0, &kTexture},
                       {"samplers", Type::Array, Type::Object, 0, &kSampler},
                       {"images", Type::Array, Type::Object, 0, &kImage},
                       {"accessors", Type::Array, Type::Object, 0, &kAccessor},
                       {"bufferViews", Type::Array, Type::Object, 0, &kBufferView},
                       {"buffers", Type::Array, Type::Object, 0, &kBuffer},
                       {"skins", Type::Array, Type::Object, 0, &kSkin},
                       {"animations", Type::Array, Type::Object, 0, &kAnimation},
                       {"extensionsUsed", Type::Array, Type::String},
                       {"extensionsRequired", Type::Array, Type::String}}};

const char* described(Type type) {
  switch (type) {
    case Type::Object: return "an object";
    case Type::Array: return "an array";
    case Type::Number: return "a number";
    case Type::Index: return "an index (an integer >= 0)";
    case Type::Integer: return "an integer >= 0";
    case Type::String: return "a string";
    case Type::Boolean: return "a boolean";
    case Type::IndexMap: return "an object of indices";
    case Type::Any: return "anything";
  }
  return "?";
}

bool isNonNegativeInteger(const json& v) {
  return v.is_number_unsigned() || (v.is_number_integer() && v.get<std::int64_t>() >= 0);
}

void check(const json& value, Type type, const Shape* shape, Type element, int length, const std::string& path,
           std::vector<std::string>& out);

// Every object may have a name, extensions (each an object) and extras.
void checkObject(const json& value, const Shape& shape, const std::string& path, std::vector<std::string>& out) {
  if (value.contains("name") && !value["name"].is_string()) out.push_back(path + ".name is not a string");
  if (value.contains("extensions")) {
    const json& extensions = value["extensions"];
    if (!extensions.is_object()) {
      out.push_back(path + ".extensions is not an object");
    } else {
      for (auto it = extensions.begin(); it != extensions.end(); ++it)
        if (!it.value().is_object()) out.push_back(path + ".extensions." + it.key() + " is not an object");
    }
  }
  for (const Field& field : shape.fields)
    if (value.contains(field.key))
      check(value[field.key], field.type, field.shape, field.element, field.length, path + "." + field.key, out);
}

void check(const json& value, Type type, const Shape* shape, Type element, int length, const std::string& path,
           std::vector<std::string>& out) {
  bool ok = true;
  switch (type) {
    case Type::Any: return;
    case Type::Object: ok = value.is_object(); break;
    case Type::Array: ok = value.is_array(); break;
    case Type::Number: ok = value.is_number(); break;
    case Type::Index:
    case Type::Integer: ok = isNonNegativeInteger(value); break;
    case Type::String: ok = value.is_string(); break;
    case Type::Boolean: ok = value.is_boolean(); break;
    case Type::IndexMap: ok = value.is_object(); break;
  }
  if (!ok) {
    out.push_back(path + " is not " + described(type));
    return;
  }
  if (type == Type::Object && shape) checkObject(value, *shape, path, out);
  if (type == Type::IndexMap)
    for (auto it = value.begin(); it != value.end(); ++it)
      check(it.value(), Type::Index, nullptr, Type::Any, 0, path + "." + it.key(), out);
  if (type == Type::Array) {
    if (length > 0 && value.size() != static_cast<size_t>(length))
      out.push_back(path + " has " + std::to_string(value.size()) + " elements, not " + std::to_string(length));
    for (size_t i = 0; i < value.size(); ++i)
      check(value[i], element, shape, Type::Any, 0, path + "[" + std::to_string(i) + "]", out);
  }
}

}  // namespace

std::vector<std::string> schemaMismatches(const json& document) {
  std::vector<std::string> out;
  if (!document.is_object()) return out;
  for (const Field& field : kDocument.fields)
    if (document.contains(field.key))
      check(document[field.key], field.type, field.shape, field.element, field.length, field.key, out);
  return out;
}

}  // namespace obscura::gltf
