#pragma once
// Compressed and quantized glTF geometry (the loader's buffer and accessor decoding; materials live elsewhere):
// - KHR_draco_mesh_compression: each compressed primitive is decoded with Debian's libdraco and its accessors are
//   pointed at the decoded data (in the component type each accessor declares; indices as UNSIGNED_INT).
// - EXT_meshopt_compression: each compressed buffer view is decoded with Debian's libmeshoptimizer (ATTRIBUTES,
//   TRIANGLES and INDICES modes; NONE, OCTAHEDRAL, QUATERNION and EXPONENTIAL filters) into a buffer of its own.
//   Fallback buffers (no uri: the data exists only compressed) are given a 3-byte data uri before tinygltf parses
//   the file, since tinygltf 2.7 would look for a file with an empty name.
// - KHR_mesh_quantization: the integer component types it allows for POSITION, NORMAL, TEXCOORD_n and morph target
//   deltas (quantizedAttributeTypes; the loader reads any type through readComponent).
// A build without a decoder (the WebAssembly build: web/obscura.js decodes both extensions with the npm decoders
// before the file reaches it) refuses a file that requires the extension, naming the missing decoder.
// Every offset, length and count is checked against its buffer and the limits before a decoder runs: a file
// either decodes to accessors the loader checks as usual, or is refused with one line.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <tiny_gltf.h>

#include "scene/GltfLoader.h"

namespace obscura {

// Which decoders this build has.
bool hasDracoDecoder();
bool hasMeshoptDecoder();

// Whether this build can load a file that lists `extension` in extensionsRequired (one of the three above). Sets
// `why` to a one-line reason where it cannot.
bool compressionExtensionSupported(const std::string& extension, std::string* why);

// The JSON text of a file: all of a .gltf, the first chunk of a .glb (empty where that chunk is not JSON or does not
// lie inside the file: tinygltf will say so).
std::string_view gltfJsonText(const std::vector<std::uint8_t>& bytes);
// Whether `json` names either compression extension: prepareCompressedDocument has nothing to mend otherwise.
bool mentionsCompression(std::string_view json);

// Before tinygltf parses the file: returns the file (.gltf JSON or .glb) with what tinygltf 2.7 would refuse in a
// compressed file mended (EXT_meshopt_compression's fallback buffers given 3 bytes of data uri; a Draco primitive's
// indices accessor without a bufferView given the Draco stream's until it is decoded), or an empty vector when
// there is nothing to change. `document` is gltfJsonText(bytes) parsed (null where mentionsCompression() is false:
// the loader parses the text for this only where there is something to mend); it is changed.
std::vector<std::uint8_t> prepareCompressedDocument(const std::vector<std::uint8_t>& bytes, nlohmann::json& document);

// After tinygltf parses it: decodes every EXT_meshopt_compression buffer view and KHR_draco_mesh_compression
// primitive in place. `file` starts every refusal (InputError); warnings go to `report`.
void decompressGltfModel(tinygltf::Model& model, const std::string& file, const GltfLimits& limits,
                         GltfLoadReport& report);

// The component types (TINYGLTF_COMPONENT_TYPE_*) a vertex attribute may have: `use` is "POSITION", "NORMAL",
// "TEXCOORD", "MORPH_POSITION" or "MORPH_NORMAL". With `quantized` (the file uses KHR_mesh_quantization) the
// extension's integer types are added. `normalizedOnly` lists those that must be normalized.
struct AttributeTypes {
  std::vector<int> allowed;
  std::vector<int> normalizedOnly;
};
AttributeTypes quantizedAttributeTypes(const std::string& use, bool quantized);
bool usesMeshQuantization(const tinygltf::Model& model);

}  // namespace obscura
