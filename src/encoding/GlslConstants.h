#pragma once
// Numeric constants shared by a CPU mirror and a shader. The CPU owns them (derived from their definitions where they
// are derived: matrix inverses and products GLSL ES 1.00 cannot compute); the shader carries them as literals printed
// by format() with nine significant digits, which read back as the identical binary32 value. A CPU test parses the
// embedded shader text with parse() and requires every literal to equal the CPU's float bit for bit, so the two
// cannot drift apart (tests/test_tonemap.cpp, tests/test_hdr_encoding.cpp).
//
// `obscura-hdr-study --glsl-constants` prints the blocks to paste after a change to a definition.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat3x3.hpp>

namespace obscura {

struct GlslConstant {
  std::string type;           // "float", "vec3" or "mat3"
  std::string name;           // as declared in the shader: `const <type> <name> = ...;`
  std::vector<float> values;  // mat3: column-major, as GLSL's and glm's constructors take them
};

GlslConstant glslMat3(const std::string& name, const glm::mat3& m);
GlslConstant glslFloat(const std::string& name, float value);

// `const mat3 NAME = mat3(...);` lines, one per constant, nine significant digits per number.
std::string formatGlslConstants(const std::vector<GlslConstant>& constants);
// The numbers of `const <type> NAME = ...;` in `source`, parsed as float; nullopt when there is no such declaration.
std::optional<std::vector<float>> parseGlslConstant(std::string_view source, const std::string& name);

}  // namespace obscura
