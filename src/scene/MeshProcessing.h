#pragma once
// CPU-side mesh work the loaders and the GPU upload share.
#include <cstdint>
#include <vector>

#include "scene/Scene.h"

namespace obscura {

// glTF 2.0 (sec. 3.7.2.1): "When normals are not specified, client implementations MUST calculate flat normals".
// Unwelds the mesh so each triangle has its own three vertices carrying the face normal. Joints, weights and morph
// target displacements follow their vertices; each morph target gets normal displacements, the change of each face's
// normal when the target is fully applied (empty for a target that turns no face).
void generateFlatNormals(Mesh& mesh);

// Smooth normals by area-weighted averaging over shared vertices (used by the built-in scene's generators).
void generateSmoothNormals(Mesh& mesh);

// Splits a mesh into pieces whose indices all fit in 16 bits (fewer than 65536 distinct vertices each), for
// contexts without OES_element_index_uint (core WebGL 1). Triangles stay whole and in order; a mesh that already
// fits comes back as one piece. Joints, weights and morph targets follow their vertices.
std::vector<Mesh> splitForShortIndices(const Mesh& mesh, std::uint32_t maxVertices = 65535);

}  // namespace obscura
