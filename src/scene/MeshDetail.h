#pragma once
// Levels of detail of a triangle mesh: coarser index lists over the same vertices, each with the geometric error it
// makes, so that a frame can draw a distant mesh with fewer triangles and no visible change (gpu/GpuScene.h picks
// the level per instance from the error it projects to pixels: gbuffer.lod).
//
// On a weak GPU the geometry passes cost by the triangle as well as by the pixel: 2CylinderEngine's 110k triangles
// drawn into 640x360 pixels spend half the G-buffer pass on triangles smaller than a pixel (docs/benchmarks.md,
// "Levels of detail"). The levels come from meshoptimizer's simplifier (0.22, third_party/meshoptimizer), which
// collapses edges under a quadric error bound (Garland and Heckbert 1997), keeps attribute seams and open borders in
// place, and here weighs the vertex normals too.
#include <cstdint>
#include <vector>

#include "scene/Scene.h"

namespace obscura {

// The coarser levels worth drawing, finest first, each with at most 80 % of the previous one's triangles and a
// larger error; empty for a mesh too small to gain from them (under kDetailMinTriangles), or one that deforms
// (skinned or morphed: the simplifier's error holds for the rest pose alone).
// A floor chosen, not measured: boxes, steps and the built-in scene's smaller primitives are left whole, which
// gain nothing from a level; the frames these levels serve are bound by files of tens of thousands of triangles.
inline constexpr std::size_t kDetailMinTriangles = 1024;
// Without the normals, a fillet or rounded edge within the bound collapses and its normals' turn is spread over the
// faces beside it: GTAO reads that as occlusion (obscura-tune --evaluate, GTAO medium at gbuffer.lod 0.5: MAE
// 0.0453 with weight 0, 0.0442 with 1, 0.0434 in full detail; the engine's level at 1/256 of each mesh's extent keeps
// 51 % of its triangles, against 42 % without). docs/benchmarks.md, "Levels of detail".
inline constexpr float kDetailNormalWeight = 1.0f;
std::vector<DetailLevel> detailLevels(const Mesh& mesh);
// Gives each mesh of the scene that has none its detailLevels: once per scene, where it is loaded (the glTF loader
// and the built-in scene call it; a scene built by hand calls it itself), so that every renderer made on it (a new
// option, a lost context, the page's vertex arrays) uploads the same levels without making them again.
void addDetailLevels(Scene& scene);

}  // namespace obscura
