#pragma once
// What every process would otherwise compute before its first frame, made when the library is built instead
// (tools/bake_environment.cpp writes BakedEnvironment.inc into the build's generated/ folder, which BuiltinSky.cpp
// includes): the split sum's BRDF table (environmentBrdfTable(), about 2 million samples), and the built-in sky of
// the default sun prefiltered (about 4 million GGX samples). Making them took 2.5 s of the page's start-up on this
// machine's CPU (docs/resolution.md, "Start-up"); reading them back takes milliseconds. A sky for another sun (a
// change of lighting.sun-elevation) is still made and prefiltered when asked for.
#include <cstdint>
#include <vector>

#include "environment/Environment.h"

namespace obscura {

struct PreparedEnvironment {
  PrefilteredEnvironment specular;
  ShIrradiance irradiance;
};

// The sky of the default sun (kBuiltinSunElevation, kBuiltinSunAzimuth), encoded for `filtering`: its image (level 0,
// ProceduralSky::image: milliseconds) made now, its levels 1 .. 5 and its irradiance from the build (environment/
// EnvironmentCache.cpp keeps it once per process and filtering). Its RGB9E5 levels and irradiance are the same, to the
// bit, as prepareEnvironment(ProceduralSky{...}.image(...)) made by the compiler that built the baking tool; the
// filtered (RGBM) levels are encoded from the RGB9E5 ones, within a level of 255 of those made from the exact levels.
PreparedEnvironment builtinSky(EnvironmentFiltering filtering);
// What builtinSky() holds, made from scratch: the image's prefiltered levels and irradiance (the baking tool's work).
PreparedEnvironment prepareEnvironment(const EnvironmentImage& image, EnvironmentFiltering filtering);
// The sun the baked sky was made for (unit).
glm::vec3 builtinSkySun();

}  // namespace obscura
