#pragma once
// glTF 2.0 loading (.gltf with external or embedded buffers, .glb) with tinygltf, validated so that any file either
// loads correctly or is refused with one line naming the file and the problem (InputError).
//
// Supported: the default scene's node hierarchy (matrix or TRS), TRIANGLES primitives (strips and fans are
// converted; points and lines are skipped), indices u8/u16/u32 or none, POSITION, NORMAL (flat normals generated when
// missing, as the spec requires), TEXCOORD_0 (with the base colour's KHR_texture_transform applied), sparse
// accessors, baseColorFactor / baseColorTexture, alphaMode OPAQUE / MASK (BLEND is drawn opaque), doubleSided.
//
// Checked, before anything is allocated for an accessor: accessor and buffer-view bounds, strides, component types
// and element types; then index ranges, NaN/Inf positions, degenerate triangles (dropped), unsupported required
// extensions, node cycles, and the limits below.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "scene/Scene.h"

namespace obscura {

// Documented limits against absurd inputs (a file asking for a billion vertices is refused, not attempted).
struct GltfLimits {
  std::uint64_t maxFileBytes = 1ull << 30;        // 1 GiB
  std::uint64_t maxAccessorElements = 1ull << 25;  // 33.5 M elements in one accessor
  std::uint64_t maxSceneTriangles = 1ull << 25;    // 33.5 M triangles after instancing
  std::uint64_t maxInstances = 1ull << 20;         // mesh primitives placed by nodes
  int maxImageDimension = 16384;                   // texels per side
  int maxNodeDepth = 256;
};

struct GltfLoadReport {
  std::vector<std::string> warnings;  // things repaired or ignored (e.g. "dropped 12 degenerate triangles")
};

// Loads a .gltf or .glb file; external buffers and images are resolved next to it.
Scene loadGltfFile(const std::string& path, GltfLoadReport* report = nullptr, const GltfLimits& limits = {});

// Loads from memory. `name` is used in messages and decides .glb vs .gltf by content (the "glTF" magic).
// `sideFiles` maps relative URIs (e.g. "Box0.bin") to their bytes, for a .gltf dropped with its buffers on the web.
Scene loadGltfMemory(const std::vector<std::uint8_t>& bytes, const std::string& name,
                     const std::map<std::string, std::vector<std::uint8_t>>& sideFiles = {},
                     GltfLoadReport* report = nullptr, const GltfLimits& limits = {});

}  // namespace obscura
