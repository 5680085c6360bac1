#include "encoding/EnvironmentEncoding.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace obscura {
namespace {

std::uint8_t byteOf(float x) { return static_cast<std::uint8_t>(std::clamp(std::lround(x * 255.0f), 0L, 255L)); }
float brightest(const glm::vec3& c) { return std::max(c.r, std::max(c.g, c.b)); }

}  // namespace

const std::vector<EnvironmentEncodingKind>& allEnvironmentEncodings() {
  static const std::vector<EnvironmentEncodingKind> kinds = {
      EnvironmentEncodingKind::Linear, EnvironmentEncodingKind::Sqrt, EnvironmentEncodingKind::Rgbm};
  return kinds;
}

const char* environmentEncodingName(EnvironmentEncodingKind kind) {
  switch (kind) {
    case EnvironmentEncodingKind::Linear: return "linear";
    case EnvironmentEncodingKind::Sqrt: return "sqrt";
    case EnvironmentEncodingKind::Rgbm: return "rgbm";
  }
  return "?";
}

float environmentLevelScale(EnvironmentEncodingKind, const std::vector<glm::vec3>& texels) {
  float top = 0.0f;
  for (const glm::vec3& c : texels) top = std::max(top, brightest(c));
  return top > 0.0f ? top : 1.0f;
}

EnvironmentTexel encodeEnvironment(EnvironmentEncodingKind kind, const glm::vec3& linear, float scale) {
  const glm::vec3 x = glm::clamp(linear / scale, glm::vec3(0.0f), glm::vec3(1.0f));
  switch (kind) {
    case EnvironmentEncodingKind::Linear: return {byteOf(x.r), byteOf(x.g), byteOf(x.b), 255};
    case EnvironmentEncodingKind::Sqrt:
      return {byteOf(std::sqrt(x.r)), byteOf(std::sqrt(x.g)), byteOf(std::sqrt(x.b)), 255};
    case EnvironmentEncodingKind::Rgbm: {
      // M quantised up, so that every channel / M <= 1 (three.js's LinearToRGBM); at least one step.
      const float m = std::max(std::ceil(brightest(x) * 255.0f), 1.0f) / 255.0f;
      return {byteOf(x.r / m), byteOf(x.g / m), byteOf(x.b / m), static_cast<std::uint8_t>(std::lround(m * 255.0f))};
    }
  }
  return {0, 0, 0, 0};
}

std::vector<EnvironmentTexel> encodeEnvironmentLevel(EnvironmentEncodingKind kind,
                                                     const std::vector<glm::vec3>& texels, float scale) {
  std::vector<EnvironmentTexel> out;
  out.reserve(texels.size());
  for (const glm::vec3& c : texels) out.push_back(encodeEnvironment(kind, c, scale));
  return out;
}

glm::vec3 decodeEnvironmentChannels(EnvironmentEncodingKind kind, const glm::vec4& c, float scale) {
  switch (kind) {
    case EnvironmentEncodingKind::Linear: return glm::vec3(c) * scale;
    case EnvironmentEncodingKind::Sqrt: return glm::vec3(c) * glm::vec3(c) * scale;
    case EnvironmentEncodingKind::Rgbm: return glm::vec3(c) * (c.a * scale);
  }
  return glm::vec3(0.0f);
}

glm::vec3 decodeEnvironment(EnvironmentEncodingKind kind, const EnvironmentTexel& t, float scale) {
  return decodeEnvironmentChannels(kind, glm::vec4(t[0], t[1], t[2], t[3]) / 255.0f, scale);
}

}  // namespace obscura
