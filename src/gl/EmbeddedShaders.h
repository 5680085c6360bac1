#pragma once
// The shader files of shaders_es2/, embedded at build time by cmake/EmbedShaders.cmake.
#include <string_view>
#include <vector>

namespace obscura {

struct EmbeddedShader {
  std::string_view path;  // relative to shaders_es2/, e.g. "ao/sao.frag", "lib/packing.glsl"
  std::string_view text;
};

const std::vector<EmbeddedShader>& embeddedShaders();

}  // namespace obscura
