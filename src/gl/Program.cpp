#include "gl/Program.h"

#include <algorithm>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "base/Error.h"

namespace obscura::gl {
namespace {

std::string infoLog(GLuint object, bool isProgram) {
  GLint length = 0;
  if (isProgram)
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  else
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  if (length <= 1) return "(no log)";
  std::vector<char> log(static_cast<size_t>(length));
  if (isProgram)
    glGetProgramInfoLog(object, length, nullptr, log.data());
  else
    glGetShaderInfoLog(object, length, nullptr, log.data());
  return std::string(log.data());
}

ShaderHandle compile(GLenum stage, const std::string& source) {
  ShaderHandle shader(stage);
  const char* text = source.c_str();
  glShaderSource(shader.id(), 1, &text, nullptr);
  glCompileShader(shader.id());
  return shader;
}

void checkCompiled(const std::string& programName, GLenum stage, const ShaderHandle& shader) {
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    throw GlError("shader '" + programName + "' (" + (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                  ") failed to compile: " + infoLog(shader.id(), false));
  }
}

// The name without an array's "[0]".
std::string_view plain(std::string_view name) {
  if (name.size() > 3 && name.substr(name.size() - 3) == "[0]") name.remove_suffix(3);
  return name;
}

// Whether a value set as `given` fits a uniform of GL type `actual`: ints set ints, booleans and samplers.
bool fits(GLenum given, GLenum actual) {
  if (given == GL_INT) return actual == GL_INT || actual == GL_BOOL || actual == GL_SAMPLER_2D ||
                              actual == GL_SAMPLER_CUBE;
  return given == actual;
}

const char* typeName(GLenum type) {
  switch (type) {
    case GL_INT: return "int";
    case GL_BOOL: return "bool";
    case GL_SAMPLER_2D: return "sampler2D";
    case GL_SAMPLER_CUBE: return "samplerCube";
    case GL_FLOAT: return "float";
    case GL_FLOAT_VEC2: return "vec2";
    case GL_FLOAT_VEC3: return "vec3";
    case GL_FLOAT_VEC4: return "vec4";
    case GL_FLOAT_MAT3: return "mat3";
    case GL_FLOAT_MAT4: return "mat4";
    default: return "another type";
  }
}

}  // namespace

Program::Program(const std::string& name, const std::string& vertexSource, const std::string& fragmentSource,
                 bool strict)
    : Program(begin(name, vertexSource, fragmentSource, strict)) {
  finishLink();
}

Program Program::begin(const std::string& name, const std::string& vertexSource, const std::string& fragmentSource,
                       bool strict) {
  Program p;
  p.name_ = name;
  p.strict_ = strict;
  p.vertex_ = compile(GL_VERTEX_SHADER, vertexSource);
  p.fragment_ = compile(GL_FRAGMENT_SHADER, fragmentSource);
  p.program_ = ProgramHandle::create();
  glAttachShader(p.program_.id(), p.vertex_.id());
  glAttachShader(p.program_.id(), p.fragment_.id());
  glBindAttribLocation(p.program_.id(), kAttribPosition, "a_position");
  glBindAttribLocation(p.program_.id(), kAttribNormal, "a_normal");
  glBindAttribLocation(p.program_.id(), kAttribTexcoord, "a_texcoord");
  glLinkProgram(p.program_.id());
  return p;
}

void Program::finishLink() {
  if (linked_) return;
  GLint ok = GL_FALSE;
  glGetProgramiv(program_.id(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    // A stage that did not compile is named with its own log; otherwise the link's.
    checkCompiled(name_, GL_VERTEX_SHADER, vertex_);
    checkCompiled(name_, GL_FRAGMENT_SHADER, fragment_);
    throw GlError("shader program '" + name_ + "' failed to link: " + infoLog(program_.id(), true));
  }
  // The shader objects go with their handles; the program keeps what it linked.
  glDetachShader(program_.id(), vertex_.id());
  glDetachShader(program_.id(), fragment_.id());
  vertex_ = ShaderHandle();
  fragment_ = ShaderHandle();
  linked_ = true;

  // The active uniforms, once.
  GLint count = 0, longest = 0;
  glGetProgramiv(program_.id(), GL_ACTIVE_UNIFORMS, &count);
  glGetProgramiv(program_.id(), GL_ACTIVE_UNIFORM_MAX_LENGTH, &longest);
  std::vector<char> text(static_cast<size_t>(std::max(longest, 1)) + 4);
  for (GLint i = 0; i < count; ++i) {
    Uniform u;
    GLsizei length = 0;
    glGetActiveUniform(program_.id(), static_cast<GLuint>(i), static_cast<GLsizei>(text.size()), &length, &u.size,
                       &u.type, text.data());
    u.name.assign(text.data(), static_cast<size_t>(length));
    if (u.name.compare(0, 3, "gl_") == 0) continue;  // built-in uniforms (gl_DepthRange) are not set
    if (u.size > 1 && plain(u.name).size() == u.name.size()) u.name += "[0]";
    u.plainLength = plain(u.name).size();
    u.location = glGetUniformLocation(program_.id(), u.name.c_str());
    uniforms_.push_back(std::move(u));
  }
  std::sort(uniforms_.begin(), uniforms_.end(), [](const Uniform& a, const Uniform& b) {
    return std::string_view(a.name).substr(0, a.plainLength) < std::string_view(b.name).substr(0, b.plainLength);
  });
}

const Program::Uniform* Program::find(std::string_view name) const {
  name = plain(name);
  const auto it = std::lower_bound(uniforms_.begin(), uniforms_.end(), name, [](const Uniform& u, std::string_view n) {
    return std::string_view(u.name).substr(0, u.plainLength) < n;
  });
  if (it == uniforms_.end() || std::string_view(it->name).substr(0, it->plainLength) != name) return nullptr;
  return &*it;
}

void Program::missing(std::string_view name) const {
  throw GlError("shader program '" + name_ + "' has no active uniform '" + std::string(name) +
                "' (misspelt, or unused and removed by the compiler)");
}

const Program::Uniform* Program::prepare(std::string_view name, GLenum type, const void* value, size_t words,
                                         int count) const {
  const Uniform* u = find(name);
  if (!u) {
    if (strict_) missing(name);
    return nullptr;
  }
  if (strict_ && (!fits(type, u->type) || count > u->size))
    throw GlError("shader program '" + name_ + "': uniform '" + u->name + "' is a " + typeName(u->type) +
                  (u->size > 1 ? "[" + std::to_string(u->size) + "]" : std::string()) + ", set as " +
                  (count > 1 ? std::to_string(count) + " x " : std::string()) + typeName(type));
  if (words > u->value.size()) return u;  // longer arrays are uploaded every time
  if (u->known && std::memcmp(u->value.data(), value, words * 4) == 0) return nullptr;
  std::memcpy(u->value.data(), value, words * 4);
  u->known = true;
  return u;
}

void Program::set(std::string_view name, int value) const {
  if (const Uniform* u = prepare(name, GL_INT, &value, 1)) glUniform1i(u->location, value);
}
void Program::set(std::string_view name, float value) const {
  if (const Uniform* u = prepare(name, GL_FLOAT, &value, 1)) glUniform1f(u->location, value);
}
void Program::set(std::string_view name, const glm::vec2& v) const {
  if (const Uniform* u = prepare(name, GL_FLOAT_VEC2, &v.x, 2)) glUniform2f(u->location, v.x, v.y);
}
void Program::set(std::string_view name, const glm::vec3& v) const {
  if (const Uniform* u = prepare(name, GL_FLOAT_VEC3, &v.x, 3)) glUniform3f(u->location, v.x, v.y, v.z);
}
void Program::set(std::string_view name, const glm::vec4& v) const {
  if (const Uniform* u = prepare(name, GL_FLOAT_VEC4, &v.x, 4)) glUniform4f(u->location, v.x, v.y, v.z, v.w);
}
void Program::set(std::string_view name, const glm::mat3& m) const {
  if (const Uniform* u = prepare(name, GL_FLOAT_MAT3, glm::value_ptr(m), 9))
    glUniformMatrix3fv(u->location, 1, GL_FALSE, glm::value_ptr(m));
}
void Program::set(std::string_view name, const glm::mat4& m) const {
  if (const Uniform* u = prepare(name, GL_FLOAT_MAT4, glm::value_ptr(m), 16))
    glUniformMatrix4fv(u->location, 1, GL_FALSE, glm::value_ptr(m));
}
void Program::set(std::string_view name, const float* values, int count) const {
  if (const Uniform* u = prepare(name, GL_FLOAT, values, static_cast<size_t>(count), count))
    glUniform1fv(u->location, count, values);
}
void Program::set(std::string_view name, const glm::vec2* values, int count) const {
  if (const Uniform* u = prepare(name, GL_FLOAT_VEC2, values, 2 * static_cast<size_t>(count), count))
    glUniform2fv(u->location, count, &values[0].x);
}
void Program::set(std::string_view name, const glm::vec3* values, int count) const {
  if (const Uniform* u = prepare(name, GL_FLOAT_VEC3, values, 3 * static_cast<size_t>(count), count))
    glUniform3fv(u->location, count, &values[0].x);
}
void Program::set(std::string_view name, const glm::vec4* values, int count) const {
  if (const Uniform* u = prepare(name, GL_FLOAT_VEC4, values, 4 * static_cast<size_t>(count), count))
    glUniform4fv(u->location, count, &values[0].x);
}

GLint Program::uniform(const char* name) const {
  const GLint location = optionalUniform(name);
  if (location < 0 && strict_) missing(name);
  return location;
}

GLint Program::optionalUniform(const char* name) const {
  const Uniform* u = find(name);
  return u ? u->location : -1;
}

std::vector<std::string> Program::uniformNames() const {
  std::vector<std::string> names;
  for (const Uniform& u : uniforms_) names.push_back(u.name);
  return names;
}

void Program::set(GLint location, const glm::mat3& m) {
  if (location >= 0) glUniformMatrix3fv(location, 1, GL_FALSE, glm::value_ptr(m));
}
void Program::set(GLint location, const glm::mat4& m) {
  if (location >= 0) glUniformMatrix4fv(location, 1, GL_FALSE, glm::value_ptr(m));
}

}  // namespace obscura::gl
