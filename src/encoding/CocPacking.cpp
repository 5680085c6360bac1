#include "encoding/CocPacking.h"

#include <algorithm>
#include <cmath>

namespace obscura::CocPacking {
namespace {

float fraction(float coc, float range) {
  if (std::isnan(coc) || !(range > 0.0f)) return 0.0f;
  return std::clamp(coc / range, -1.0f, 1.0f);  // an infinite CoC clamps like a large one
}

}  // namespace

std::uint16_t codeFromCoc(float coc, float range) {
  return static_cast<std::uint16_t>(std::floor(fraction(coc, range) * kSteps16 + 0.5f) + 32768.0f);
}

float cocFromCode(std::uint16_t code, float range) {
  return (static_cast<float>(code) - 32768.0f) * (range / kSteps16);
}

std::array<std::uint8_t, 4> bytesFromCoc(float coc, float range) {
  const std::uint16_t code = codeFromCoc(coc, range);
  return {static_cast<std::uint8_t>(code >> 8), static_cast<std::uint8_t>(code & 0xFF), 0, 0};
}

float cocFromBytes(const std::uint8_t* bytes, float range) {
  return cocFromCode(static_cast<std::uint16_t>(bytes[0] << 8 | bytes[1]), range);
}

std::uint8_t halfCodeFromCoc(float coc, float range) {
  return static_cast<std::uint8_t>(std::floor(fraction(coc, range) * kSteps8 + 0.5f) + 128.0f);
}

float cocFromHalfCode(std::uint8_t code, float range) {
  return (static_cast<float>(code) - 128.0f) * (range / kSteps8);
}

}  // namespace obscura::CocPacking
