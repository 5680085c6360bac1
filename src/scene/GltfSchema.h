#pragma once
// The JSON types of the glTF 2.0 properties the loader reads, checked on the document before tinygltf parses it
// (part of scene/GltfLoader.h's loader: GltfReading.h lists the others). tinygltf 2.7 skips a property of the wrong
// type without a word (a material's pbrMetallicRoughness given as an array, a normal texture's scale as a string, a
// texture index of -1), and the file then draws with defaults. The Khronos glTF-Validator calls such a file invalid;
// the loader names what it ignored, so that no invalid file loads silently (docs/robustness.md).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace obscura::gltf {

// Each property of the document whose JSON type (or, for indices, sign) the glTF 2.0 schema does not allow, as
// "materials[0].pbrMetallicRoughness is not an object", in document order.
std::vector<std::string> schemaMismatches(const nlohmann::json& document);

}  // namespace obscura::gltf
