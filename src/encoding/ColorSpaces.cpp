#include "encoding/ColorSpaces.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/matrix.hpp>

namespace obscura::ColorSpaces {
namespace {
glm::dvec3 xyzAtUnitLuminance(const glm::dvec2& xy) { return {xy.x / xy.y, 1.0, (1.0 - xy.x - xy.y) / xy.y}; }
}  // namespace

glm::dmat3 rgbToXyz(const Primaries& p) {
  const glm::dmat3 primaries(xyzAtUnitLuminance(p.red), xyzAtUnitLuminance(p.green), xyzAtUnitLuminance(p.blue));
  const glm::dvec3 scale = glm::inverse(primaries) * xyzAtUnitLuminance(p.white);
  return glm::dmat3(primaries[0] * scale.x, primaries[1] * scale.y, primaries[2] * scale.z);
}

glm::dmat3 srgbToRec2020() { return glm::inverse(rgbToXyz(kBt2020)) * rgbToXyz(kBt709); }

glm::vec3 hsvColor(float hue, float saturation) {
  const glm::vec3 k(0.0f, 2.0f / 3.0f, 1.0f / 3.0f);
  glm::vec3 rgb;
  for (int i = 0; i < 3; ++i) {
    const float p = std::abs((hue + k[i]) - std::floor(hue + k[i])) * 6.0f - 3.0f;
    rgb[i] = std::clamp(std::abs(p) - 1.0f, 0.0f, 1.0f);
  }
  return glm::mix(glm::vec3(1.0f), rgb, saturation);
}

}  // namespace obscura::ColorSpaces
