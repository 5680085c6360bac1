#pragma once
// A generated skinned mesh with as many joints as asked: a vertical tube on a chain of joints that bends, for the
// skinning tests (tests/test_skinning.cpp, test_velocity.cpp) and the skinning benchmark (obscura-bench section 7),
// where the joint count is the variable (a palette of 16 joints at GLES 2's minimum uniforms; skeletons of 40 or 64).
#include <glm/vec3.hpp>

#include "scene/Scene.h"

namespace obscura {

struct SkinnedTubeShape {
  float radius = 0.3f, height = 4.0f;
  int joints = 3;
  int rings = 64, sides = 16;
  float bendRadians = 1.2f;  // the whole chain's bend about z at the end of the animation (spread over the joints)
  float slide = 0.5f;        // the root's travel along +x over the animation
  float seconds = 1.0f;      // the animation's duration: LINEAR keys at 0 and `seconds`
};

// Adds the tube to `scene` standing at `base`: a mesh (each vertex blended between the two joints whose segment
// centres are nearest), a chain of nodes (the root at `base`, each next one a segment up), a skin, an instance, and
// the bend's channels to the animation `animation` (created, named "bend", when the scene has fewer). Returns the
// instance's index.
int addSkinnedTube(Scene& scene, const SkinnedTubeShape& shape, const glm::vec3& base, int animation = 0);

}  // namespace obscura
