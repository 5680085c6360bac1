#pragma once
// Mesh generators for the built-in scene and the tests' synthetic scenes. Metres; faces wind counter-clockwise
// seen from outside; normals are unit length; texture coordinates are set.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/Scene.h"

namespace obscura {

// Appends a quad a, b, c, d (counter-clockwise seen from the front) with its own four vertices and a flat normal.
void addQuad(Mesh& mesh, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
             const glm::vec2& uvScale = glm::vec2(1.0f));
// Axis-aligned box from lo to hi, flat faces; uvPerMetre > 0 tiles texture coordinates by size.
Mesh makeBox(const glm::vec3& lo, const glm::vec3& hi, float uvPerMetre = 0.0f);
// UV sphere centred at the origin, smooth normals.
Mesh makeSphere(float radius, int slices, int stacks);
// Capped cylinder standing on y = 0 around the y axis, smooth sides.
Mesh makeCylinder(float radius, float height, int slices);
// Tube standing on y = 0 around the y axis: `length` of straight side in `rings` rings of vertices (so that a skin
// can bend it smoothly), then a hemisphere of the same radius on top; open at the bottom, like makeCylinder, for it
// stands on something. Smooth normals; its top is at length + radius.
Mesh makeRoundedTube(float radius, float length, int slices, int rings);
// Semicircular arch ring in the xy plane, centre at the origin, opening downwards, `depth` thick along z.
Mesh makeArchRing(float innerRadius, float outerRadius, float depth, int segments);

}  // namespace obscura
