#pragma once
// CPU-side mesh work the loaders and the GPU upload share.
#include <cstdint>
#include <vector>

#include "scene/Scene.h"

namespace obscura {

// glTF 2.0 (sec. 3.7.2.1): "When normals are not specified, client implementations MUST calculate flat normals".
// Unwelds the mesh so each triangle has its own three vertices carrying the face normal. Texture coordinates, colours,
// joints, weights and morph target displacements follow their vertices; each morph target gets normal
// displacements, the change of each face's normal when the target is fully applied (empty for a target that turns no
// face), and no tangent displacements (the tangents are generated for the flat normals).
void generateFlatNormals(Mesh& mesh);

// Smooth normals by area-weighted averaging over shared vertices (used by the built-in scene's generators).
void generateSmoothNormals(Mesh& mesh);

// Per-vertex tangents (Mesh::tangents) for normal mapping where the file has none, as glTF 2.0 asks (sec. 3.7.2.1:
// "client implementations SHOULD calculate tangents using default MikkTSpace algorithms"). Written by hand after
// mikktspace.c (no packaged MikkTSpace library here): each corner's face tangent dP/du and bitangent dP/dv,
// projected onto the vertex normal's plane and normalised, accumulated per vertex weighted by the corner's angle,
// then orthogonalised against the normal (Gram-Schmidt); w is the bitangent's sign. Unlike mikktspace.c it does not
// split a vertex whose corners' tangent frames disagree (a uv seam shared by one vertex): glTF files already split
// their vertices at uv seams. A vertex without usable uv gradients gets any unit vector perpendicular to its normal.
// `texCoord`: the set whose gradients the tangents follow (the normal texture's: 0 TEXCOORD_0, 1 TEXCOORD_1).
void generateTangents(Mesh& mesh, int texCoord = 0);
glm::vec3 anyPerpendicular(const glm::vec3& unitNormal);

// The triangles listed (by triangle number) as a mesh of their own: the vertices they use, renumbered in order of
// first use, with every per-vertex array (normals, texcoords, joints, weights, morph target deltas) carried along.
Mesh extractTriangles(const Mesh& mesh, const std::vector<std::uint32_t>& triangles);

// Splits a mesh into pieces whose indices all fit in 16 bits (fewer than 65536 distinct vertices each), for
// contexts without OES_element_index_uint (core WebGL 1). Triangles stay whole and in order; a mesh that already
// fits comes back as one piece. Joints, weights and morph targets follow their vertices.
std::vector<Mesh> splitForShortIndices(const Mesh& mesh, std::uint32_t maxVertices = 65535);

// A piece of a skinned mesh whose joints fit a uniform palette of a vertex stage: its joint indices are renumbered
// into `palette`, which lists the skin joint each palette entry is.
struct PalettePiece {
  Mesh mesh;
  std::vector<int> palette;
};
// Splits a skinned mesh into pieces that each use at most `paletteSize` joints (counting only joints with a non-zero
// weight), greedily in triangle order, so that any skeleton can be drawn from uniforms alone (GLES 2 guarantees 128
// vertex uniform vectors: about 40 joints as 3x4 matrices, half that with the previous frame's palette). Empty when
// a single triangle needs more than `paletteSize` joints (at most 12 can: 3 vertices x 4 influences).
std::vector<PalettePiece> splitForJointPalette(const Mesh& mesh, int paletteSize);

}  // namespace obscura
