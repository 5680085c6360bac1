#include "core/ColorSpaces.h"

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

}  // namespace obscura::ColorSpaces
