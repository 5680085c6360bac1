#include "gl/UniformPacking.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <set>
#include <sstream>

#include "gl/ShaderLibrary.h"

namespace obscura::gl {

namespace {

constexpr int kColumns = 4;

struct Shape {
  int columns;  // components per row: 4, 3, 2 or 1
  int rows;     // rows of one element (a matrix's columns)
};

Shape shapeOf(GLenum type) {
  switch (type) {
    case GL_FLOAT_MAT4: return {4, 4};
    case GL_FLOAT_MAT3: return {3, 3};
    case GL_FLOAT_MAT2: return {4, 2};  // a whole row per column, as ANGLE's packer counts it
    case GL_FLOAT_VEC4: case GL_INT_VEC4: case GL_BOOL_VEC4: return {4, 1};
    case GL_FLOAT_VEC3: case GL_INT_VEC3: case GL_BOOL_VEC3: return {3, 1};
    case GL_FLOAT_VEC2: case GL_INT_VEC2: case GL_BOOL_VEC2: return {2, 1};
    case GL_SAMPLER_2D: case GL_SAMPLER_CUBE: return {0, 0};
    default: return {1, 1};  // float, int, bool
  }
}

// The appendix's order: mat4, mat2, vec4, mat3, vec3, vec2, float; within a type the larger arrays first.
int sortOrder(GLenum type) {
  switch (type) {
    case GL_FLOAT_MAT4: return 0;
    case GL_FLOAT_MAT2: return 1;
    case GL_FLOAT_MAT3: return 3;
    default: break;
  }
  switch (shapeOf(type).columns) {
    case 4: return 2;
    case 3: return 4;
    case 2: return 5;
    default: return 6;
  }
}

bool isIdentifierCharacter(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

}  // namespace

// The algorithm of Appendix A, section 7, step by step (ANGLE's VariablePacker implements the same reading).
bool uniformsFit(const std::vector<UniformShape>& uniforms, int maxRows) {
  if (maxRows < 0) return false;
  std::vector<UniformShape> sorted;
  for (const UniformShape& u : uniforms)
    if (shapeOf(u.type).columns > 0) sorted.push_back(u);
  std::stable_sort(sorted.begin(), sorted.end(), [](const UniformShape& a, const UniformShape& b) {
    const int oa = sortOrder(a.type), ob = sortOrder(b.type);
    return oa != ob ? oa < ob : a.arraySize > b.arraySize;
  });
  std::vector<std::array<bool, kColumns>> used(static_cast<size_t>(maxRows), std::array<bool, kColumns>{});
  auto rowsOf = [](const UniformShape& u) { return shapeOf(u.type).rows * std::max(u.arraySize, 1); };
  auto fill = [&](int top, int rows, int column, int columns) {
    for (int r = top; r < top + rows; ++r)
      for (int c = column; c < column + columns; ++c) used[static_cast<size_t>(r)][static_cast<size_t>(c)] = true;
  };

  // Four- and three-column variables take successive rows from the top, aligned to the first column.
  int top = 0;
  for (const UniformShape& u : sorted) {
    if (shapeOf(u.type).columns < 3) continue;
    const int rows = rowsOf(u);
    if (top + rows > maxRows) return false;
    fill(top, rows, 0, shapeOf(u.type).columns);
    top += rows;
  }
  // Two-column variables: successive rows in columns 0-1 below those; when no rows are left, columns 2-3 from the
  // bottom.
  const int available = maxRows - top;
  int left01 = available, left23 = available;
  for (const UniformShape& u : sorted) {
    if (shapeOf(u.type).columns != 2) continue;
    const int rows = rowsOf(u);
    if (rows <= left01) left01 -= rows;
    else if (rows <= left23) left23 -= rows;
    else return false;
  }
  fill(top, available - left01, 0, 2);
  fill(maxRows - (available - left23), available - left23, 2, 2);
  // One-column variables, largest first: in the column whose free run leaves the least space, at that run's top.
  for (const UniformShape& u : sorted) {
    if (shapeOf(u.type).columns != 1) continue;
    const int rows = rowsOf(u);
    int bestColumn = -1, bestTop = 0, bestSize = maxRows + 1;
    for (int c = 0; c < kColumns; ++c) {
      for (int r = 0; r < maxRows;) {
        if (used[static_cast<size_t>(r)][static_cast<size_t>(c)]) {
          ++r;
          continue;
        }
        int end = r;
        while (end < maxRows && !used[static_cast<size_t>(end)][static_cast<size_t>(c)]) ++end;
        const int size = end - r;
        if (size >= rows && size < bestSize) {
          bestColumn = c;
          bestTop = r;
          bestSize = size;
        }
        r = end;
      }
    }
    if (bestColumn < 0) return false;
    fill(bestTop, rows, bestColumn, 1);
  }
  return true;
}

std::set<std::string> declaredUniforms(const std::string& source) {
  const std::string text = ShaderLibrary::withoutComments(source);
  std::set<std::string> names;
  const std::string keyword = "uniform";
  for (size_t at = text.find(keyword); at != std::string::npos; at = text.find(keyword, at + keyword.size())) {
    const size_t after = at + keyword.size();
    if ((at > 0 && isIdentifierCharacter(text[at - 1])) || (after < text.size() && isIdentifierCharacter(text[after])))
      continue;
    const size_t end = text.find(';', after);
    std::string declaration = text.substr(after, end == std::string::npos ? std::string::npos : end - after);
    // Array sizes out, commas to spaces: "[precision] type name name2".
    std::string words;
    int depth = 0;
    for (char c : declaration) {
      if (c == '[') ++depth;
      if (depth == 0) words += c == ',' ? ' ' : c;
      if (c == ']') --depth;
    }
    std::istringstream tokens(words);
    std::string word;
    tokens >> word;
    if (word == "lowp" || word == "mediump" || word == "highp") tokens >> word;  // then the type
    while (tokens >> word) names.insert(word);
  }
  return names;
}

int packedUniformRows(const std::vector<UniformShape>& uniforms) {
  int rows = 0;
  while (!uniformsFit(uniforms, rows)) ++rows;
  return rows;
}

StageUniforms activeUniformsByStage(GLuint program, const std::string& vertexSource,
                                    const std::string& fragmentSource) {
  StageUniforms out;
  GLint count = 0, longest = 0;
  glGetProgramiv(program, GL_ACTIVE_UNIFORMS, &count);
  glGetProgramiv(program, GL_ACTIVE_UNIFORM_MAX_LENGTH, &longest);
  std::vector<char> buffer(static_cast<size_t>(std::max(longest, 1)));
  const std::set<std::string> inVertex = declaredUniforms(vertexSource), inFragment = declaredUniforms(fragmentSource);
  for (GLint index = 0; index < count; ++index) {
    GLsizei length = 0;
    GLint size = 0;
    GLenum type = 0;
    glGetActiveUniform(program, static_cast<GLuint>(index), longest, &length, &size, &type, buffer.data());
    std::string name(buffer.data(), static_cast<size_t>(length));
    if (const size_t bracket = name.find('['); bracket != std::string::npos) name.resize(bracket);
    const UniformShape shape{type, size};
    if (inVertex.count(name)) out.vertex.push_back(shape);
    if (inFragment.count(name)) out.fragment.push_back(shape);
  }
  return out;
}

}  // namespace obscura::gl
