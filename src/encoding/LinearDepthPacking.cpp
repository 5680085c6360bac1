#include "encoding/LinearDepthPacking.h"

#include <algorithm>
#include <cmath>

namespace obscura::LinearDepthPacking {

std::uint16_t codeFromDepth(float linearDepth) {
  const float d = std::clamp(linearDepth, 0.0f, 1.0f);
  return static_cast<std::uint16_t>(std::floor(d * 65535.0f + 0.5f));
}

float depthFromCode(std::uint16_t code) { return static_cast<float>(code) * (1.0f / 65535.0f); }

std::array<std::uint8_t, 2> bytesFromCode(std::uint16_t code) {
  const float c = static_cast<float>(code);
  const float high = std::floor(c * (1.0f / 256.0f));
  const float low = c - high * 256.0f;
  return {static_cast<std::uint8_t>(high), static_cast<std::uint8_t>(low)};
}

std::uint16_t codeFromBytes(std::uint8_t high, std::uint8_t low) {
  return static_cast<std::uint16_t>(high * 256u + low);
}

float channelFromByte(std::uint8_t byte) { return (static_cast<float>(byte) + 0.25f) * (1.0f / 255.0f); }

std::uint8_t byteFromChannel(float channel) {
  return static_cast<std::uint8_t>(std::floor(std::clamp(channel, 0.0f, 1.0f) * 255.0f + 0.5f));
}

}  // namespace obscura::LinearDepthPacking
