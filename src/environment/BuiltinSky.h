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

// The sky of the default sun (kBuiltinSunElevation, kBuiltinSunAzimuth), made once per process: its image (level 0,
// ProceduralSky::image: milliseconds) now, its levels 1 .. 5 and its irradiance from the build. The same, to the bit,
// as prepareEnvironment(ProceduralSky{...}.image(...)) made by the compiler that built the baking tool.
const PreparedEnvironment& builtinSky();
// What builtinSky() holds, made from scratch: the image's prefiltered levels and irradiance (the baking tool's work).
PreparedEnvironment prepareEnvironment(const EnvironmentImage& image);
// The sun the baked sky was made for (unit).
glm::vec3 builtinSkySun();

}  // namespace obscura
