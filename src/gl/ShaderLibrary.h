#pragma once
// Builds GLSL ES 1.00 program text from the embedded shaders_es2/ files.
//
// A shader file holds no #version line; the library prepends "#version 100", the variant's #extension and #define
// lines, then the file with every `#include "lib/x.glsl"` line replaced by that file's text (each library file is
// included at most once per shader). Web and native therefore compile exactly the same text, and
// `obscura-shaders --dump DIR` writes it out for glslangValidator.
#include <string>
#include <utility>
#include <vector>

#include "gl/Program.h"

namespace obscura {

// One compilable program: two files and the variant's compile-time constants.
struct ProgramSpec {
  ProgramSpec() = default;
  ProgramSpec(std::string name_, std::string vertexFile_, std::string fragmentFile_,
              std::vector<std::pair<std::string, std::string>> defines_ = {}, std::vector<std::string> extensions_ = {},
              std::string fragmentText_ = "")
      : name(std::move(name_)), vertexFile(std::move(vertexFile_)), fragmentFile(std::move(fragmentFile_)),
        defines(std::move(defines_)), extensions(std::move(extensions_)), fragmentText(std::move(fragmentText_)) {}

  std::string name;  // for messages and dumps, e.g. "sao[samples=11,turns=4,falloff=sao2012]"
  std::string vertexFile, fragmentFile;
  std::vector<std::pair<std::string, std::string>> defines;
  std::vector<std::string> extensions;  // enabled with "#extension NAME : require" in the fragment stage
  // Fragment shader text that is not an embedded file (a tool's own program: obscura-bench's floor pass); used
  // instead of fragmentFile when set, composed the same way (its includes come from shaders_es2/lib).
  std::string fragmentText;

  std::string vertexSource() const;
  std::string fragmentSource() const;
  // Compiles and links; a strict program refuses to resolve uniforms it lacks (gl/Program.h).
  gl::Program build(bool strict = false) const;
  // Issues the compiles and the link without waiting for them (gl::Program::begin; finishLink before use).
  gl::Program begin(bool strict = false) const;
};

namespace ShaderLibrary {
// The raw text of one embedded file; throws GlError if there is no such file.
std::string_view file(const std::string& path);
// The full source of one stage: header, defines, then the file with includes expanded.
std::string compose(const std::string& path, const std::vector<std::pair<std::string, std::string>>& defines,
                    const std::vector<std::string>& extensions);
// The text with its comments out (a // comment to its line's end, a /* */ block to one space): the code alone, for
// what reads shader text (gl::declaredUniforms, the shader tests' checks).
std::string withoutComments(const std::string& source);
// The same for shader text that is not an embedded file (tests use it to call the library functions).
std::string composeText(const std::string& text, const std::vector<std::pair<std::string, std::string>>& defines,
                        const std::vector<std::string>& extensions);
}  // namespace ShaderLibrary

}  // namespace obscura
