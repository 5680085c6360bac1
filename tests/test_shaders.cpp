// Every program variant the renderer can build compiles and links on the headless context; a broken shader is
// reported with the program's name and the driver's log. (tests/check_shaders_glslang.sh validates the same text
// with glslangValidator as GLSL ES 1.00.)
#include <gtest/gtest.h>

#include <algorithm>

#include "TestSupport.h"
#include "base/Error.h"
#include "core/ShaderLibrary.h"

using namespace obscura;

TEST(Shaders, EveryVariantCompilesAndLinks) {
  test::context();
  const std::vector<ProgramSpec> specs = Renderer::allProgramSpecs();
  EXPECT_GE(specs.size(), 20u);
  const gl::GlCaps& caps = test::context().caps();
  for (const ProgramSpec& spec : specs) {
    // Variants that need an extension build only where the context has it (the page tests them in the browser).
    if (!std::all_of(spec.extensions.begin(), spec.extensions.end(), [&](const std::string& e) { return caps.has(e); }))
      continue;
    try {
      const gl::Program program = spec.build();
      EXPECT_NE(program.id(), 0u) << spec.name;
    } catch (const GlError& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

TEST(Shaders, CompileFailureNamesTheProgramAndQuotesTheLog) {
  test::context();
  try {
    gl::Program("broken[test]", ShaderLibrary::composeText("void main() { gl_Position = vec4(0.0); }", {}, {}),
                ShaderLibrary::composeText("void main() { gl_FragColor = undefined_symbol; }", {}, {}));
    FAIL() << "a broken shader compiled";
  } catch (const GlError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("broken[test]"), std::string::npos) << message;
    EXPECT_NE(message.find("fragment"), std::string::npos) << message;
    EXPECT_NE(message.find("undefined_symbol"), std::string::npos) << message;
  }
}

TEST(Shaders, LinkFailureNamesTheProgramAndQuotesTheLog) {
  test::context();
  try {
    // Each stage compiles; the fragment stage reads a varying the vertex stage never declares: a link error.
    gl::Program("unlinkable[test]",
                ShaderLibrary::composeText("void main() { gl_Position = vec4(0.0); }", {}, {}),
                ShaderLibrary::composeText("precision mediump float;\nvarying vec3 v_missing;\n"
                                           "void main() { gl_FragColor = vec4(v_missing, 1.0); }",
                                           {}, {}));
    FAIL() << "a program whose stages disagree linked";
  } catch (const GlError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'unlinkable[test]' failed to link: "), std::string::npos) << message;
    EXPECT_GT(message.size(), std::string("shader program 'unlinkable[test]' failed to link: ").size() + 5)
        << "no driver log quoted: " << message;
  }
}

TEST(Shaders, SourcesAreGlslEs100WithoutForbiddenFeatures) {
  for (const ProgramSpec& spec : Renderer::allProgramSpecs()) {
    for (std::string source : {spec.vertexSource(), spec.fragmentSource()}) {
      // Look at code only: drop // comments (the sources use no block comments).
      std::string code;
      for (size_t start = 0; start < source.size();) {
        const size_t end = std::min(source.find('\n', start), source.size());
        const std::string line = source.substr(start, end - start);
        code += line.substr(0, line.find("//")) + "\n";
        start = end + 1;
      }
      source = code;
      EXPECT_EQ(source.rfind("#version 100\n", 0), 0u) << spec.name;
      // No bitwise operators, no texelFetch, no integer textures: GLSL ES 1.00 has none of them.
      for (const char* forbidden : {"texelFetch", "textureSize", "<<", ">>", " ^ ", " | ", " & ", "uint", "flat "})
        EXPECT_EQ(source.find(forbidden), std::string::npos) << spec.name << " uses '" << forbidden << "'";
    }
  }
}
