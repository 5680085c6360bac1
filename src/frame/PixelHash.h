#pragma once
// The hash of shaders_es2/lib/hash.glsl (Dave Hoskins, "Hash without Sine", 2014: hash12), in float as the shader
// computes it: a 2D point to [0, 1). The stages that add noise (film grain, dithering) use it; their tests check its
// statistics, which a last-bit difference between the CPU and a GPU does not change.
#include <cmath>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace obscura {

inline float fractOf(float x) { return x - std::floor(x); }

inline float hash12(glm::vec2 p) {
  glm::vec3 p3(fractOf(p.x * 0.1031f), fractOf(p.y * 0.1031f), fractOf(p.x * 0.1031f));
  const float d = p3.x * (p3.y + 33.33f) + p3.y * (p3.z + 33.33f) + p3.z * (p3.x + 33.33f);
  p3 += glm::vec3(d);
  return fractOf((p3.x + p3.y) * p3.z);
}

}  // namespace obscura
