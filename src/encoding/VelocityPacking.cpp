#include "encoding/VelocityPacking.h"

#include <algorithm>
#include <cmath>

namespace obscura::VelocityPacking {

std::uint16_t codeFromComponent(float v) {
  const float clamped = std::isfinite(v) ? std::clamp(v, -1.0f, 1.0f) : 0.0f;
  return static_cast<std::uint16_t>(std::floor(clamped * kStepsPerUnit + 0.5f) + 32768.0f);
}

float componentFromCode(std::uint16_t code) { return (static_cast<float>(code) - 32768.0f) / kStepsPerUnit; }

std::array<std::uint8_t, 4> bytesFromVelocity(glm::vec2 velocity) {
  const std::uint16_t x = codeFromComponent(velocity.x), y = codeFromComponent(velocity.y);
  return {static_cast<std::uint8_t>(x >> 8), static_cast<std::uint8_t>(x & 0xFF), static_cast<std::uint8_t>(y >> 8),
          static_cast<std::uint8_t>(y & 0xFF)};
}

glm::vec2 velocityFromBytes(const std::uint8_t* bytes) {
  return {componentFromCode(static_cast<std::uint16_t>(bytes[0] << 8 | bytes[1])),
          componentFromCode(static_cast<std::uint16_t>(bytes[2] << 8 | bytes[3]))};
}

}  // namespace obscura::VelocityPacking
