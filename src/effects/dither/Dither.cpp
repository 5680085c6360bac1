#include "effects/dither/Dither.h"

#include "frame/PixelHash.h"

namespace obscura {

const std::vector<Parameter<DitherSettings>>& DitherSettings::parameters() {
  using S = DitherSettings;
  static const std::vector<Parameter<S>> table = {
      switchParameter<S>("dither", "dithering before 8-bit quantisation on or off (triangular noise of one step: no "
                         "banding on dark gradients)",
                         &S::enabled)
          .primary()};
  return table;
}

glm::vec2 ditherSeed(std::uint64_t frameIndex) {
  const float f = static_cast<float>(frameIndex % 65536);
  return {1000.0f * hash12({f, 0.25f}), 1000.0f * hash12({0.25f, f})};
}

float ditherOffset(glm::vec2 pixel, glm::vec2 seed) {
  const float r1 = hash12(pixel + seed), r2 = hash12(pixel + seed + glm::vec2(57.31f, 113.7f));
  return (r1 + r2 - 1.0f) / 255.0f;
}

}  // namespace obscura
