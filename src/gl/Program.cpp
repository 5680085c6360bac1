#include "gl/Program.h"

#include <glm/gtc/type_ptr.hpp>
#include <vector>

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

ShaderHandle compile(const std::string& programName, GLenum stage, const std::string& source) {
  ShaderHandle shader(stage);
  const char* text = source.c_str();
  glShaderSource(shader.id(), 1, &text, nullptr);
  glCompileShader(shader.id());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    throw GlError("shader '" + programName + "' (" + (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                  ") failed to compile: " + infoLog(shader.id(), false));
  }
  return shader;
}

}  // namespace

Program::Program(const std::string& name, const std::string& vertexSource, const std::string& fragmentSource,
                 bool strict)
    : name_(name), strict_(strict) {
  ShaderHandle vertex = compile(name, GL_VERTEX_SHADER, vertexSource);
  ShaderHandle fragment = compile(name, GL_FRAGMENT_SHADER, fragmentSource);
  program_ = ProgramHandle::create();
  glAttachShader(program_.id(), vertex.id());
  glAttachShader(program_.id(), fragment.id());
  glBindAttribLocation(program_.id(), kAttribPosition, "a_position");
  glBindAttribLocation(program_.id(), kAttribNormal, "a_normal");
  glBindAttribLocation(program_.id(), kAttribTexcoord, "a_texcoord");
  glLinkProgram(program_.id());
  GLint ok = GL_FALSE;
  glGetProgramiv(program_.id(), GL_LINK_STATUS, &ok);
  // The shader objects are released when `vertex` and `fragment` go out of scope; the program keeps them alive.
  glDetachShader(program_.id(), vertex.id());
  glDetachShader(program_.id(), fragment.id());
  if (ok != GL_TRUE) throw GlError("shader program '" + name + "' failed to link: " + infoLog(program_.id(), true));
}

GLint Program::uniform(const char* name) const {
  const GLint location = optionalUniform(name);
  if (location < 0 && strict_)
    throw GlError("shader program '" + name_ + "' has no active uniform '" + name +
                  "' (misspelt, or unused and removed by the compiler)");
  return location;
}

GLint Program::optionalUniform(const char* name) const { return glGetUniformLocation(program_.id(), name); }

void Program::set(GLint location, const glm::mat3& m) { glUniformMatrix3fv(location, 1, GL_FALSE, glm::value_ptr(m)); }
void Program::set(GLint location, const glm::mat4& m) { glUniformMatrix4fv(location, 1, GL_FALSE, glm::value_ptr(m)); }

}  // namespace obscura::gl
