#pragma once
// Film grain (shaders_es2/grain/grain.glsl): smooth value noise of cells `size` pixels wide (lib/hash.glsl's hash at
// the cells' corners, blended by smoothstep), a new pattern each frame (the frame index moves the noise by a hash of
// itself), added to the display colour with the weight intensity x (1 - sqrt(luma)): more in the shadows and
// mid-tones than in the highlights (Unity's post-processing stack's luminance response). The noise has mean 0, so it
// changes no brightness on average.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "frame/Parameters.h"

namespace obscura {

struct GrainSettings : ParameterAccess<GrainSettings> {
  bool enabled = false;
  float intensity = 0.12f;
  float size = 1.5f;  // pixels

  static const std::vector<Parameter<GrainSettings>>& parameters();
  void validate() const { validateParameters("grain"); }
};

// The shader's u_grain for frame `index`, the noise at a pixel (CPU mirror), and the grained display colour.
glm::vec4 grainUniform(const GrainSettings& settings, std::uint64_t frameIndex);
float grainNoise(glm::vec2 p);
glm::vec3 grained(const glm::vec3& srgb, glm::vec2 pixel, const glm::vec4& uniform);

}  // namespace obscura
