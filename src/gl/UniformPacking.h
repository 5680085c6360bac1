#pragma once
// How many uniform vectors a program's stage takes, counted as GLSL ES 1.00 says a context must count them (Appendix
// A, section 7, "Counting of Varyings and Uniforms"): the variables are packed into rows of four columns, the widest
// first, and a stage that does not fit in GL_MAX_{VERTEX,FRAGMENT}_UNIFORM_VECTORS rows may fail to link. Drivers may
// pack better but need not, so a program meant for every GLES 2 context must fit by this count (tests/
// test_shaders.cpp holds every program of the renderer to the minimums: 128 vertex and 16 fragment vectors).
#include <set>
#include <string>
#include <vector>

#include "gl/GlApi.h"

namespace obscura::gl {

struct UniformShape {
  GLenum type;        // GL_FLOAT_VEC3, GL_FLOAT_MAT4, ... (samplers take no vectors)
  int arraySize = 1;  // 1 for a variable that is not an array
};

// Whether the variables fit in maxRows rows by the appendix's algorithm.
bool uniformsFit(const std::vector<UniformShape>& uniforms, int maxRows);
// The fewest rows they fit in.
int packedUniformRows(const std::vector<UniformShape>& uniforms);

// The names a stage's text declares as uniforms ("uniform [precision] type name[N], name2;"), comments left out: one
// scan of the text (a regular expression per uniform over the composed sources took most of the shader suite's time).
std::set<std::string> declaredUniforms(const std::string& source);

// The active uniforms of a linked program, by stage: a uniform counts in each stage whose source declares it (the
// sources as they were compiled: ProgramSpec::vertexSource and fragmentSource).
struct StageUniforms {
  std::vector<UniformShape> vertex, fragment;
};
StageUniforms activeUniformsByStage(GLuint program, const std::string& vertexSource,
                                    const std::string& fragmentSource);

}  // namespace obscura::gl
