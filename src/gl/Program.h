#pragma once
// A linked GLSL ES 1.00 program with a cache of uniform locations. Compile and link failures throw GlError naming
// the program and quoting the driver's log.
#include <string>
#include <unordered_map>

#include <glm/glm.hpp>

#include "gl/GlObjects.h"

namespace obscura::gl {

// Vertex attribute slots shared by every geometry program (bound before linking).
enum AttributeSlot : GLuint { kAttribPosition = 0, kAttribNormal = 1, kAttribTexcoord = 2 };

class Program {
 public:
  Program() = default;
  // `name` is used in error messages only (e.g. "sao[samples=11]").
  Program(const std::string& name, const std::string& vertexSource, const std::string& fragmentSource);

  GLuint id() const { return program_.id(); }
  const std::string& name() const { return name_; }
  explicit operator bool() const { return program_.id() != 0; }

  void use() const { glUseProgram(program_.id()); }
  // -1 when the uniform does not exist or was optimised away (GL ignores sets to -1).
  GLint uniform(const char* name) const;

  void set(const char* name, int value) const { glUniform1i(uniform(name), value); }
  void set(const char* name, float value) const { glUniform1f(uniform(name), value); }
  void set(const char* name, const glm::vec2& v) const { glUniform2f(uniform(name), v.x, v.y); }
  void set(const char* name, const glm::vec3& v) const { glUniform3f(uniform(name), v.x, v.y, v.z); }
  void set(const char* name, const glm::vec4& v) const { glUniform4f(uniform(name), v.x, v.y, v.z, v.w); }
  void set(const char* name, const glm::mat3& m) const;
  void set(const char* name, const glm::mat4& m) const;

 private:
  std::string name_;
  ProgramHandle program_;
  mutable std::unordered_map<std::string, GLint> uniforms_;
};

}  // namespace obscura::gl
