// GLSL ES 1.00's counting of uniform vectors (Appendix A, section 7; gl/UniformPacking.h) on cases worked by hand
// from the appendix's rules.
#include <gtest/gtest.h>

#include "gl/UniformPacking.h"

using obscura::gl::packedUniformRows;
using obscura::gl::UniformShape;
using obscura::gl::uniformsFit;

TEST(UniformPacking, WholeRowsForFourColumnsAndMatrices) {
  EXPECT_EQ(packedUniformRows({}), 0);
  EXPECT_EQ(packedUniformRows({{GL_FLOAT_VEC4, 7}}), 7);
  EXPECT_EQ(packedUniformRows({{GL_FLOAT_MAT4, 1}, {GL_FLOAT_VEC4, 1}}), 5);
  EXPECT_EQ(packedUniformRows({{GL_FLOAT_MAT3, 1}}), 3);
  EXPECT_EQ(packedUniformRows({{GL_FLOAT_MAT4, 2}}), 8);
  EXPECT_EQ(packedUniformRows({{GL_SAMPLER_2D, 1}, {GL_FLOAT_VEC4, 1}}), 1);  // samplers take no vectors
}

TEST(UniformPacking, FloatsFillTheFourthColumnOfThreeColumnRows) {
  // Nine vec3 take nine rows; nine floats beside them take the fourth column; a tenth needs a row of its own.
  EXPECT_EQ(packedUniformRows({{GL_FLOAT_VEC3, 9}}), 9);
  std::vector<UniformShape> shapes = {{GL_FLOAT_VEC3, 9}};
  for (int i = 0; i < 9; ++i) shapes.push_back({GL_FLOAT, 1});
  EXPECT_EQ(packedUniformRows(shapes), 9);
  shapes.push_back({GL_FLOAT, 1});
  EXPECT_EQ(packedUniformRows(shapes), 10);
  // A float array keeps one column: three floats beside one vec3 need three rows (column 3 of rows 0 .. 2).
  EXPECT_EQ(packedUniformRows({{GL_FLOAT_VEC3, 1}, {GL_FLOAT, 3}}), 3);
  // Four floats share one row.
  EXPECT_EQ(packedUniformRows({{GL_FLOAT, 1}, {GL_FLOAT, 1}, {GL_FLOAT, 1}, {GL_FLOAT, 1}}), 1);
}

TEST(UniformPacking, TwoColumnVariablesTakeColumnsZeroOneThenTwoThree) {
  EXPECT_EQ(packedUniformRows({{GL_FLOAT_VEC2, 1}, {GL_FLOAT_VEC2, 1}}), 1);
  EXPECT_EQ(packedUniformRows({{GL_FLOAT_VEC2, 3}}), 3);  // an array stays in one pair of columns
  EXPECT_EQ(packedUniformRows({{GL_FLOAT_VEC2, 3}, {GL_FLOAT_VEC2, 3}}), 3);
  // A vec3 row leaves one column: no room for a vec2, which takes a row below.
  EXPECT_EQ(packedUniformRows({{GL_FLOAT_VEC3, 1}, {GL_FLOAT_VEC2, 1}}), 2);
}

TEST(UniformPacking, FitIsMonotonicInTheRowCount) {
  const std::vector<UniformShape> shapes = {{GL_FLOAT_MAT4, 1}, {GL_FLOAT_VEC3, 4}, {GL_FLOAT_VEC2, 3}, {GL_FLOAT, 6}};
  const int rows = packedUniformRows(shapes);
  EXPECT_FALSE(uniformsFit(shapes, rows - 1));
  for (int r = rows; r < rows + 4; ++r) EXPECT_TRUE(uniformsFit(shapes, r)) << r;
  // The matrix's 4 rows, the vec3s' 4 below, the vec2 array's 3 in columns 0-1 below those; the floats fit in the
  // free columns beside them.
  EXPECT_EQ(rows, 4 + 4 + 3);
}

// The declarations activeUniformsByStage reads each stage's text for: a precision or none, arrays, several names in
// one declaration, and none of what a comment or a longer identifier mentions.
TEST(UniformPacking, DeclaredUniformsAreTheNamesOfEachDeclaration) {
  const std::string source = R"(
precision highp float;
uniform sampler2D u_source;
uniform mediump vec4 u_taps[8], u_weights[2 * 4];
uniform float u_near,u_far;
// uniform float u_commented;
/* uniform vec2 u_blocked; */
float uniformity;
varying vec2 v_uv;
void main() { gl_FragColor = texture2D(u_source, v_uv) * u_taps[0] * uniformity; }
)";
  const std::set<std::string> expected = {"u_source", "u_taps", "u_weights", "u_near", "u_far"};
  EXPECT_EQ(obscura::gl::declaredUniforms(source), expected);
}
