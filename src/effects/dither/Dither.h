#pragma once
// Dithering before 8-bit quantisation (shaders_es2/dither/dither.glsl), on by default. A smooth gradient darker than a
// few codes per hundred pixels (a dim sky, a fog ramp) quantises into visible bands; noise added before the
// quantisation turns them into grain that the eye averages. Triangular noise (the sum of two uniform ones, minus 1)
// of one 8-bit step's amplitude is the least that makes the quantisation error's mean and variance independent of the
// signal (Lipshitz, Wannamaker and Vanderkooy 1992, "Quantization and dither: a theoretical survey"), the dither
// Filament's and Babylon's post-processing add; the same noise on the three channels keeps it grey. A new pattern
// each frame (the frame index moves the hash).
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "frame/Parameters.h"

namespace obscura {

struct DitherSettings : ParameterAccess<DitherSettings> {
  bool enabled = true;

  static const std::vector<Parameter<DitherSettings>>& parameters();
  void validate() const { validateParameters("dither"); }
};

// The shader's u_ditherSeed for frame `index`, and the offset added at a pixel (CPU mirror): in (-1, 1) / 255.
glm::vec2 ditherSeed(std::uint64_t frameIndex);
float ditherOffset(glm::vec2 pixel, glm::vec2 seed);

}  // namespace obscura
