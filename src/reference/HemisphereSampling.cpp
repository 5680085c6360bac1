#include "reference/HemisphereSampling.h"

#include <algorithm>
#include <cmath>

namespace obscura::HemisphereSampling {

std::uint32_t hash32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

std::uint32_t reverseBits(std::uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffU) << 8) | ((i & 0xff00ff00U) >> 8);
  i = ((i & 0x0f0f0f0fU) << 4) | ((i & 0xf0f0f0f0U) >> 4);
  i = ((i & 0x33333333U) << 2) | ((i & 0xccccccccU) >> 2);
  i = ((i & 0x55555555U) << 1) | ((i & 0xaaaaaaaaU) >> 1);
  return i;
}

glm::vec2 shiftedHammersley(std::uint32_t i, int log2Count, std::uint32_t shiftX, std::uint32_t shiftY) {
  // i / N as a 0.32 fixed-point fraction; its low bits are zero, so the shift also jitters within each stratum.
  const std::uint32_t x = (log2Count == 0 ? 0u : i << (32 - log2Count)) ^ shiftX;
  const std::uint32_t y = reverseBits(i) ^ shiftY;
  // 2^-32, and the largest float below 1 so that rounding never yields 1.
  constexpr double kScale = 1.0 / 4294967296.0;
  constexpr float kBelowOne = 0x1.fffffep-1f;
  return {std::min(static_cast<float>(x * kScale), kBelowOne), std::min(static_cast<float>(y * kScale), kBelowOne)};
}

glm::vec2 concentricDisk(const glm::vec2& u) {
  const glm::vec2 p = 2.0f * u - 1.0f;
  if (p.x == 0.0f && p.y == 0.0f) return {0.0f, 0.0f};
  constexpr float kQuarterPi = 0.785398163397448f;
  float r, theta;
  if (std::abs(p.x) > std::abs(p.y)) {
    r = p.x;
    theta = kQuarterPi * (p.y / p.x);
  } else {
    r = p.y;
    theta = 2.0f * kQuarterPi - kQuarterPi * (p.x / p.y);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}

glm::vec3 cosineHemisphere(const glm::vec2& u) {
  const glm::vec2 d = concentricDisk(u);
  return {d.x, d.y, std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y))};
}

void orthonormalBasis(const glm::vec3& n, glm::vec3* t, glm::vec3* b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  *t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  *b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

}  // namespace obscura::HemisphereSampling
