// obscura-shaders: writes every program variant the renderer can build, exactly as it is handed to the driver, so
// glslangValidator can check it as GLSL ES 1.00 (tests/check_shaders_glslang.sh does).
//
//   obscura-shaders --list
//   obscura-shaders --dump DIR     writes DIR/<variant>.vert and DIR/<variant>.frag
#include <cctype>
#include <cstdio>
#include <fstream>
#include <string>

#include "FetchFloorPass.h"
#include "renderer/Renderer.h"

namespace {
// The frame's programs and the benchmark's floor pass.
std::vector<obscura::ProgramSpec> everyProgram() {
  std::vector<obscura::ProgramSpec> specs = obscura::Renderer::allProgramSpecs();
  for (const obscura::ProgramSpec& spec : obscura::FetchFloorPass::programSpecs()) specs.push_back(spec);
  return specs;
}

std::string fileName(const std::string& name) {
  std::string out;
  for (char c : name) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.') ? c : '_';
  return out;
}
}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "--list" && argc == 2) {
    for (const obscura::ProgramSpec& spec : everyProgram()) std::printf("%s\n", spec.name.c_str());
    return 0;
  }
  if (mode == "--dump" && argc == 3) {
    const std::string dir = argv[2];
    for (const obscura::ProgramSpec& spec : everyProgram()) {
      const std::string base = dir + "/" + fileName(spec.name);
      std::ofstream(base + ".vert") << spec.vertexSource();
      std::ofstream(base + ".frag") << spec.fragmentSource();
      if (!std::ofstream(base + ".frag", std::ios::app)) {
        std::fprintf(stderr, "obscura-shaders: cannot write %s\n", base.c_str());
        return 2;
      }
    }
    return 0;
  }
  std::fprintf(stderr, "usage: obscura-shaders --list | --dump DIR\n");
  return 2;
}
