#include "environment/BuiltinSky.h"

#include <cstring>

#include "base/TimeSpent.h"

namespace obscura {
namespace {

#include "BakedEnvironment.inc"  // kBrdfTable, kSkySun, kSkyIrradiance, kSkyLevels (tools/bake_environment.cpp)

}  // namespace

const std::vector<std::uint8_t>& environmentBrdfTable() {
  static const std::vector<std::uint8_t> table(std::begin(kBrdfTable), std::end(kBrdfTable));
  return table;
}

glm::vec3 builtinSkySun() { return {kSkySun[0], kSkySun[1], kSkySun[2]}; }

PreparedEnvironment prepareEnvironment(const EnvironmentImage& image, EnvironmentFiltering filtering) {
  return {PrefilteredEnvironment::of(image, 4096, filtering), ShIrradiance::project(image)};
}

PreparedEnvironment builtinSky(EnvironmentFiltering filtering) {
  const TimedScope timed("built-in sky");
  std::array<EnvironmentImage, kEnvironmentLevels> levels;
  levels[0] = ProceduralSky{builtinSkySun()}.image(kEnvironmentWidth, kEnvironmentHeight);
  size_t texel = 0;
  for (int level = 1; level < kEnvironmentLevels; ++level) {
    levels[level] = EnvironmentImage(kEnvironmentWidth >> level, kEnvironmentHeight >> level);
    for (glm::vec3& c : levels[level].texels) {
      HdrTexel encoded;
      std::memcpy(encoded.data(), &kSkyLevels[4 * texel++], 4);
      c = decodeHdr(encoded);
    }
  }
  PreparedEnvironment prepared;
  prepared.specular = PrefilteredEnvironment::fromLevels(std::move(levels), filtering);
  for (size_t i = 0; i < 9; ++i)
    prepared.irradiance.coefficients[i] = {kSkyIrradiance[3 * i], kSkyIrradiance[3 * i + 1],
                                           kSkyIrradiance[3 * i + 2]};
  return prepared;
}

}  // namespace obscura
