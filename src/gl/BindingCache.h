#pragma once
// The binding cache: the texture units, the program, the vertex array object and the viewport as the core asks for
// them, bound only when a call depends on them and only where they differ from what the context holds.
//
// Every pass leaves the baseline state (gl/PipelineState.h) for the next one: it unbinds its textures, its program
// and its vertex array when it ends, and the next pass binds its own again, often the same ones. On the web a WebGL
// call costs the page a few microseconds of host time, whatever it does: the default frame made 195, 109 of them
// these bindings, and makes 129 with the cache (docs/benchmarks.md, "The binding cache, built").
//
// Within a DeferredBindings scope (one frame of the renderer) these setters only record what is wanted:
// glActiveTexture, glBindTexture (2D and cube map), glUseProgram, glBindVertexArrayOES and glViewport (each pass
// sets its target's, mostly the rectangle of the pass before). Every other GL call first makes the bindings it
// depends on (bindingUse, by the entry point's name: a uniform needs the program, a draw or a query everything, a
// clear nothing). So every draw, upload and query sees the state it would have seen without the cache, and an unbind
// followed by the same bind costs nothing.
//
// Outside a scope the setters call GL at once. A scope starts knowing nothing of the context (whoever drew between
// frames may have bound anything) and makes everything wanted when it ends, so the caller finds the state the core
// asked for last: the baseline. Deleting a bound texture or vertex array unbinds it, as GL does.
//
// Included by gl/GlApi.h, after the GL headers; include that.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace obscura::gl {

// What a GL call depends on among the bindings the cache holds back.
enum BindingUse : unsigned {
  kUsesNone = 0,
  kUsesTextures = 1,     // the active unit and the textures bound (uploads, parameters, mipmaps)
  kUsesProgram = 2,      // the program in use (uniforms)
  kUsesVertexArray = 4,  // the vertex array object (buffer bindings, attribute arrays)
  kUsesViewport = 8,     // the viewport (draws, and the query of it)
  kUsesAll = 15,         // draws, queries, reads, and every call not listed below
};

namespace detail {
// Calls that depend on none of the cached bindings: per-frame state of the framebuffer, rasteriser and blending, and
// names made. A call missing from these lists counts as kUsesAll, which is always correct: glGetError among them, so
// that an error a held-back binding raises is reported where it is asked for.
inline constexpr std::string_view kCallsUsingNone[] = {
    "glBindFramebuffer", "glBindRenderbuffer", "glBlendColor", "glBlendEquation", "glBlendEquationSeparate",
    "glBlendFunc", "glBlendFuncSeparate", "glClear", "glClearColor", "glClearDepthf", "glClearStencil", "glColorMask",
    "glCullFace", "glDepthFunc", "glDepthMask", "glDepthRangef", "glDisable", "glEnable", "glFrontFace",
    "glHint", "glLineWidth", "glPixelStorei", "glPolygonOffset", "glSampleCoverage", "glScissor", "glStencilFunc",
    "glStencilFuncSeparate", "glStencilMask", "glStencilMaskSeparate", "glStencilOp", "glStencilOpSeparate",
    "glGenBuffers", "glGenFramebuffers", "glGenRenderbuffers", "glGenTextures", "glGenVertexArraysOES",
    "glCreateProgram", "glCreateShader", "glShaderSource", "glCompileShader", "glGetUniformLocation",
    "glGetAttribLocation"};
inline constexpr std::string_view kCallsUsingTextures[] = {
    "glTexImage2D", "glTexSubImage2D", "glTexParameterf", "glTexParameterfv", "glTexParameteri", "glTexParameteriv",
    "glGenerateMipmap", "glCopyTexImage2D", "glCopyTexSubImage2D", "glCompressedTexImage2D", "glCompressedTexSubImage2D"};
inline constexpr std::string_view kCallsUsingVertexArray[] = {
    "glBindBuffer", "glBufferData", "glBufferSubData", "glEnableVertexAttribArray", "glDisableVertexAttribArray"};

template <std::size_t N>
constexpr bool listed(std::string_view name, const std::string_view (&calls)[N]) {
  for (std::string_view call : calls)
    if (call == name) return true;
  return false;
}
}  // namespace detail

// The bindings a GL entry point, by name, depends on: the lists above, glVertexAttrib* (the pointers are the vertex
// array's) and glUniform* (the program's).
constexpr unsigned bindingUse(std::string_view name) {
  if (detail::listed(name, detail::kCallsUsingNone)) return kUsesNone;
  if (detail::listed(name, detail::kCallsUsingTextures)) return kUsesTextures;
  if (detail::listed(name, detail::kCallsUsingVertexArray) || name.substr(0, 14) == "glVertexAttrib")
    return kUsesVertexArray;
  if (name.substr(0, 9) == "glUniform") return kUsesProgram;
  return kUsesAll;
}

namespace bindings {
// Which kinds of binding (BindingUse bits) are wanted and not yet made; read inline by every wrapped call.
inline unsigned g_pending = 0;
void makePending(unsigned uses);
// Makes the wanted bindings of the kinds in `uses`, where they differ from the context's.
inline void make(unsigned uses) {
  if (g_pending & uses) makePending(uses);
}

void activeTexture(GLenum unit);
void bindTexture(GLenum target, GLuint texture);
void useProgram(GLuint program);
void bindVertexArray(GLuint vertexArray);
void viewport(GLint x, GLint y, GLsizei width, GLsizei height);
void deleteTextures(GLsizei count, const GLuint* textures);
void deleteVertexArrays(GLsizei count, const GLuint* vertexArrays);

// The binding calls asked for, and those made, since the process started (tests and benchmarks compare them).
struct Counts {
  std::uint64_t asked = 0, made = 0;
};
Counts counts();
// Whether the scopes made from now on defer (on by default): off, every setter calls GL at once, as before the
// cache. Tests compare the two.
void setDeferring(bool deferring);
}  // namespace bindings

// The scope within which the setters defer (one frame of the renderer). Nests: the outermost one counts.
class DeferredBindings {
 public:
  DeferredBindings();
  ~DeferredBindings();
  DeferredBindings(const DeferredBindings&) = delete;
  DeferredBindings& operator=(const DeferredBindings&) = delete;

 private:
  bool defers_;
};

}  // namespace obscura::gl
