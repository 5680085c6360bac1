#pragma once
// glTF 2.0 loading (.gltf with external or embedded buffers, .glb) with tinygltf, validated so that any file either
// loads correctly or is refused with one line naming the file and the problem (InputError).
//
// Supported: the default scene's node hierarchy (matrix or TRS; kept in Scene::nodes, parents first, each instance
// naming its node), TRIANGLES primitives (strips and fans are converted; points and lines are skipped), indices
// u8/u16/u32 or none, POSITION, NORMAL (flat normals generated when missing, as the spec requires), TEXCOORD_0 (with
// the base colour's KHR_texture_transform applied), sparse accessors, baseColorFactor / baseColorTexture, alphaMode
// OPAQUE / MASK (BLEND is drawn opaque), doubleSided; and what moves (glTF 2.0 sec. 3.7.3 to 3.7.4, 3.11):
// - skins: joints, inverseBindMatrices (identity when absent), skeleton; JOINTS_0 (u8/u16) and WEIGHTS_0 (float or
//   normalised u8/u16). Weights are renormalised to sum to 1 (a warning counts those more than 1 % off); a vertex
//   whose weights are all zero follows its first joint with weight 1; a joint slot of weight zero is set to joint 0
//   (it contributes nothing, and a GLSL ES 1.00 uniform array must not be indexed out of range). JOINTS_1 /
//   WEIGHTS_1 are ignored with a warning (set 0 is renormalised). A jointed primitive placed by a node without a
//   skin is drawn rigid, its joints dropped, with a warning.
// - morph targets: POSITION and NORMAL deltas (TANGENT and others ignored), rest weights from the node, else the
//   mesh, else zeros. Where flat normals are generated, each target gets the normal deltas of its displaced faces.
// - animations: every animation's channels on translation, rotation, scale and weights, LINEAR / STEP /
//   CUBICSPLINE, outputs as float or (rotation, weights) normalised integers. Channels on nodes outside the loaded
//   hierarchy, with unknown paths, or without a target node (KHR_animation_pointer) are skipped with a warning.
// A node reached by several paths (glTF requires disjoint trees) gets one Scene node per path; animations move all
// of them, a skin joint takes the first (with a warning).
//
// Checked, before anything is allocated for an accessor: accessor and buffer-view bounds, strides, component types
// and element types; then index ranges, NaN/Inf positions, degenerate triangles (dropped; for skinned or morphed
// meshes only those with a repeated corner, since a pose can open the others), unsupported required extensions,
// node cycles, and the limits below. For what moves: joint indices within the skin (for weighted slots), weights
// finite and not negative, inverse bind matrices finite and enough of them, joints that are loaded nodes, morph
// target counts (per target the primitive's vertex count; the same target count in every primitive of a mesh, and
// in node and mesh weights), key times finite and strictly increasing, values finite (rotation keys not zero),
// sampler output counts (input count, x3 for CUBICSPLINE, x target count for weights), no channel on a matrix node,
// no weights channel on a node without morph targets, no two channels of one animation on the same node and path.
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
  std::uint64_t maxNodes = 1ull << 20;             // Scene::nodes, a node reached by several paths counted per path
  // Joints of one skin. A GLES 2 vertex shader holds far fewer joint matrices in uniforms (MAX_VERTEX_UNIFORM_VECTORS
  // is at least 128, three vec4 per joint matrix); the renderer decides how to place them. The limit only stops
  // absurd skins: real characters use tens to a few hundred joints.
  int maxSkinJoints = 1024;
  // Morph target deltas read over the scene: sum over primitives of targets x vertices (a file can point many
  // targets at one accessor, so the accessor limit alone does not bound it).
  std::uint64_t maxMorphTargetVertices = 1ull << 25;
  // Animation floats read over the scene (key times and values of every sampler), for the same reason.
  std::uint64_t maxAnimationValues = 1ull << 26;
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
