// obscura-bake-environment OUT.inc: what src/environment/BuiltinSky.h serves without computing it, computed once when
// the library is built: the split sum's BRDF table and the built-in sky of the default sun prefiltered (levels 1 .. 5)
// with its irradiance. The build runs it (CMakeLists.txt; in the web build as WebAssembly under node) and compiles its
// output into the environment library. It is built from src/environment/Environment.cpp with
// OBSCURA_BOOTSTRAP_ENVIRONMENT, where environmentBrdfTable() computes the table instead of reading this file.
//
// The sky's texels are written in the RGB9E5 encoding (4 bytes: encoding/HdrEncoding.h, 0.1 % mean error, what the
// texture holds anyway), the irradiance's and the sun's floats as hexadecimal literals (exact).
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "environment/Environment.h"

using namespace obscura;

namespace {

void writeBytes(std::FILE* out, const char* name, const std::vector<std::uint8_t>& bytes) {
  std::fprintf(out, "constexpr std::uint8_t %s[%zu] = {", name, bytes.size());
  for (size_t i = 0; i < bytes.size(); ++i)
    std::fprintf(out, "%s%u", i == 0 ? "\n    " : i % 32 == 0 ? ",\n    " : ",", bytes[i]);
  std::fprintf(out, "};\n");
}

void writeFloats(std::FILE* out, const char* name, const std::vector<float>& values) {
  std::fprintf(out, "constexpr float %s[%zu] = {", name, values.size());
  for (size_t i = 0; i < values.size(); ++i)
    std::fprintf(out, "%s%af", i == 0 ? "\n    " : i % 4 == 0 ? ",\n    " : ", ", values[i]);
  std::fprintf(out, "};\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: obscura-bake-environment OUT.inc\n");
    return 2;
  }
  try {
    const std::vector<std::uint8_t> brdf = computeEnvironmentBrdfTable();
    const glm::vec3 sun = sunDirection(kBuiltinSunElevation, kBuiltinSunAzimuth);
    const EnvironmentImage image = ProceduralSky{sun}.image(kEnvironmentWidth, kEnvironmentHeight);
    const PrefilteredEnvironment specular = PrefilteredEnvironment::of(image);
    const ShIrradiance irradiance = ShIrradiance::project(image);
    std::vector<std::uint8_t> levels;
    for (int level = 1; level < kEnvironmentLevels; ++level)
      for (const HdrTexel& t : specular.encodedLevel(level)) levels.insert(levels.end(), t.begin(), t.end());
    std::vector<float> sh;
    for (const glm::vec3& c : irradiance.coefficients) sh.insert(sh.end(), {c.x, c.y, c.z});

    const std::string path = argv[1], temporary = path + ".part";
    std::FILE* out = std::fopen(temporary.c_str(), "w");
    if (!out) throw std::runtime_error("cannot write " + temporary);
    std::fprintf(out, "// Made by obscura-bake-environment (tools/bake_environment.cpp) when the library was built; "
                      "do not edit.\n");
    writeBytes(out, "kBrdfTable", brdf);
    writeFloats(out, "kSkySun", {sun.x, sun.y, sun.z});
    writeFloats(out, "kSkyIrradiance", sh);
    std::fprintf(out, "// The built-in sky's levels 1 .. %d, RGB9E5, rows from the zenith.\n", kEnvironmentLevels - 1);
    writeBytes(out, "kSkyLevels", levels);
    const bool written = std::fclose(out) == 0;
    if (!written || std::rename(temporary.c_str(), path.c_str()) != 0)
      throw std::runtime_error("cannot write " + path);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "obscura-bake-environment: %s\n", e.what());
    return 1;
  }
}
