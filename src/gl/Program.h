#pragma once
// A linked GLSL ES 1.00 program. Compile and link failures throw GlError naming the program and quoting the driver's
// log.
//
// Uniform locations are resolved once, when a pass builds its program (uniform()), and set by location every frame.
// A strict program (what the Renderer builds when RendererOptions::checkGlErrors is on: the tests, the page's
// debug-gl) refuses to resolve a uniform it does not have, so a misspelt name or a uniform the compiler dropped is an
// error rather than a value silently going nowhere.
#include <string>

#include <glm/glm.hpp>

#include "gl/GlObjects.h"

namespace obscura::gl {

// Vertex attribute slots shared by every geometry program (bound before linking).
enum AttributeSlot : GLuint { kAttribPosition = 0, kAttribNormal = 1, kAttribTexcoord = 2 };

class Program {
 public:
  Program() = default;
  // `name` is used in error messages only (e.g. "sao[samples=11]").
  Program(const std::string& name, const std::string& vertexSource, const std::string& fragmentSource,
          bool strict = false);

  GLuint id() const { return program_.id(); }
  const std::string& name() const { return name_; }
  bool strict() const { return strict_; }
  explicit operator bool() const { return program_.id() != 0; }

  void use() const { glUseProgram(program_.id()); }
  // The location of an active uniform (for an array, of its element 0: "u_offsets[0]"). A strict program throws
  // GlError when it has none by that name; otherwise -1, which glUniform* ignores. Call once, not per frame.
  GLint uniform(const char* name) const;
  // The location, or -1 without complaint: for uniforms a variant may legitimately lack.
  GLint optionalUniform(const char* name) const;

  // Set on the program in use (use() first).
  static void set(GLint location, int value) { glUniform1i(location, value); }
  static void set(GLint location, float value) { glUniform1f(location, value); }
  static void set(GLint location, const glm::vec2& v) { glUniform2f(location, v.x, v.y); }
  static void set(GLint location, const glm::vec3& v) { glUniform3f(location, v.x, v.y, v.z); }
  static void set(GLint location, const glm::vec4& v) { glUniform4f(location, v.x, v.y, v.z, v.w); }
  // A uniform array of vec3 or vec4 (location of its element 0).
  static void set(GLint location, const glm::vec3* v, int count) { glUniform3fv(location, count, &v[0].x); }
  static void set(GLint location, const glm::vec4* v, int count) { glUniform4fv(location, count, &v[0].x); }
  static void set(GLint location, const glm::mat3& m);
  static void set(GLint location, const glm::mat4& m);

 private:
  std::string name_;
  bool strict_ = false;
  ProgramHandle program_;
};

}  // namespace obscura::gl
