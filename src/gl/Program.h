#pragma once
// A linked GLSL ES 1.00 program. Compile and link failures throw GlError naming the program and quoting the driver's
// log.
//
// Its uniforms are resolved once, when it is linked: the active uniforms' names, locations, types and sizes are
// read from GL into a table, and passes set them by name (set("u_exposure", 1.5f)) on the program in use. A set
// whose value the uniform already holds makes no GL call: a uniform keeps its value in its program, so constants
// (sampler units, a preset's step table) are uploaded once, and a cached frame repeats few of its values.
//
// A strict program (what the Renderer builds when RendererOptions::checkGlErrors is on: the tests, the page's
// debug-gl) refuses a name it does not have and a value of the wrong type, so a misspelt name or a uniform the
// compiler dropped is an error rather than a value silently going nowhere. A lenient one ignores them.
//
// Per-draw uniforms (GpuScene's, set for every instance) may take a location once (uniform(), optionalUniform())
// and be set by location with the static setters; such a uniform must not also be set by name (its cached value
// would be stale).
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "gl/GlObjects.h"

namespace obscura::gl {

// Vertex attribute slots shared by every geometry program (bound before linking).
enum AttributeSlot : GLuint { kAttribPosition = 0, kAttribNormal = 1, kAttribTexcoord = 2 };

class Program {
 public:
  Program() = default;
  // Compiles and links now. `name` is used in error messages only (e.g. "sao[samples=11]").
  Program(const std::string& name, const std::string& vertexSource, const std::string& fragmentSource,
          bool strict = false);

  // The same in two steps, so that the driver may compile while the caller does other work: begin() issues the
  // compiles and the link and asks GL nothing; finishLink() checks them (GlError, as the constructor) and reads the
  // uniforms. A driver that compiles elsewhere (a browser's GPU process; one with KHR_parallel_shader_compile) works
  // in between, and GL waits only where a status or a uniform is asked for. A program begun has no uniforms and must
  // not be used until finished (frame/ProgramCache.h: Rehearsal, and Renderer::prepare).
  static Program begin(const std::string& name, const std::string& vertexSource, const std::string& fragmentSource,
                       bool strict = false);
  void finishLink();
  bool linked() const { return linked_; }

  GLuint id() const { return program_.id(); }
  const std::string& name() const { return name_; }
  bool strict() const { return strict_; }
  explicit operator bool() const { return program_.id() != 0; }

  void use() const { glUseProgram(program_.id()); }

  // Whether the program has an active uniform of this name (an array by its plain name or its element 0's).
  bool has(std::string_view name) const { return find(name) != nullptr; }
  // The elements of an active uniform array (1 for a plain uniform), or 0 where the program has none by that name.
  int arraySize(std::string_view name) const {
    const Uniform* u = find(name);
    return u ? u->size : 0;
  }
  // Sets a uniform by name on the program in use (use() first). Strict: GlError for a name it lacks or a value of
  // another type; lenient: ignored. Samplers take their unit as an int.
  void set(std::string_view name, int value) const;
  void set(std::string_view name, float value) const;
  void set(std::string_view name, const glm::vec2& v) const;
  void set(std::string_view name, const glm::vec3& v) const;
  void set(std::string_view name, const glm::vec4& v) const;
  void set(std::string_view name, const glm::mat3& m) const;
  void set(std::string_view name, const glm::mat4& m) const;
  // A uniform array from its element 0 (`name` plain or "name[0]"): `count` elements, at most its size.
  void set(std::string_view name, const float* values, int count) const;
  void set(std::string_view name, const glm::vec2* values, int count) const;
  void set(std::string_view name, const glm::vec3* values, int count) const;
  void set(std::string_view name, const glm::vec4* values, int count) const;

  // The location of an active uniform (for an array, of its element 0: "u_offsets[0]"), for uniforms set per draw
  // by location. A strict program throws GlError when it has none by that name; otherwise -1, which glUniform*
  // ignores. Call once, not per frame.
  GLint uniform(const char* name) const;
  // The location, or -1 without complaint: for uniforms a variant may legitimately lack.
  GLint optionalUniform(const char* name) const;

  // Set by location on the program in use (use() first).
  // A location of -1 (a uniform the program does not have) makes no GL call: GL would ignore it, but a browser still
  // pays for the call.
  static void set(GLint location, int value) {
    if (location >= 0) glUniform1i(location, value);
  }
  static void set(GLint location, float value) {
    if (location >= 0) glUniform1f(location, value);
  }
  static void set(GLint location, const glm::vec2& v) {
    if (location >= 0) glUniform2f(location, v.x, v.y);
  }
  static void set(GLint location, const glm::vec3& v) {
    if (location >= 0) glUniform3f(location, v.x, v.y, v.z);
  }
  static void set(GLint location, const glm::vec4& v) {
    if (location >= 0) glUniform4f(location, v.x, v.y, v.z, v.w);
  }
  // A uniform array of vec3 or vec4 (location of its element 0).
  static void set(GLint location, const glm::vec3* v, int count) {
    if (location >= 0) glUniform3fv(location, count, &v[0].x);
  }
  static void set(GLint location, const glm::vec4* v, int count) {
    if (location >= 0) glUniform4fv(location, count, &v[0].x);
  }
  static void set(GLint location, const glm::mat3& m);
  static void set(GLint location, const glm::mat4& m);

  // The active uniforms' names (arrays as "name[0]"), for tests and tools.
  std::vector<std::string> uniformNames() const;

 private:
  // One active uniform, and the value last set by name (up to a mat4's 16 words; longer arrays are not remembered).
  struct Uniform {
    std::string name;  // as GL reports it; an array's as "name[0]"
    size_t plainLength = 0;  // the name without "[0]"
    GLint location = -1;
    GLenum type = 0;
    GLint size = 1;  // array elements
    mutable bool known = false;
    mutable std::array<std::uint32_t, 16> value{};
  };
  const Uniform* find(std::string_view name) const;
  // The uniform to set, or null (lenient, not there); checks the name and type where strict. `words`: the value's
  // size, and whether it is unchanged (then null too, after noting nothing).
  const Uniform* prepare(std::string_view name, GLenum type, const void* value, size_t words, int count = 1) const;
  [[noreturn]] void missing(std::string_view name) const;

  std::string name_;
  bool strict_ = false;
  bool linked_ = false;
  ProgramHandle program_;
  ShaderHandle vertex_, fragment_;  // between begin() and finishLink() only: their compile logs, on failure
  std::vector<Uniform> uniforms_;  // sorted by name
};

}  // namespace obscura::gl
