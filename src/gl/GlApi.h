#pragma once
// The one door to OpenGL ES 2.0 for all of Obscura.
//
// The core includes <GLES2/gl2.h> (and gl2ext.h for guarded extensions) and nothing else, so it cannot call a
// desktop-GL entry point: the same code links for WebGL 1.
//
// The entry points as linked or loaded are in namespace obscura::gl::raw. On the web, Emscripten provides the GLES 2
// functions directly. Natively, one process may hold an OSMesa context or an EGL (GLES 2) context, each with its own
// dispatch, so the prototypes are switched off and the entry points are function pointers, filled from the current
// context's GetProcAddress (loadGles2).
//
// Code in namespace obscura calls glFoo(...) unqualified, and reaches the wrappers of namespace obscura::gles: each
// makes the bindings its call depends on (gl/BindingCache.h) and calls the raw entry point; the binding setters go
// to the cache.
#if defined(__EMSCRIPTEN__)
#define OBSCURA_GL_DIRECT 1
#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>
// Emscripten's GL library maps glDrawBuffersEXT onto WEBGL_draw_buffers (it enables the extension itself).
extern "C" void glDrawBuffersEXT(GLsizei n, const GLenum* buffers);
// And the OES_vertex_array_object entry points onto the extension (WebGLVertexArrayObjectOES), which it enables on
// contexts made with enableExtensionsByDefault (platform/WebCanvas.cpp, apps/obscura_web_geometry.cpp).
extern "C" void glGenVertexArraysOES(GLsizei n, GLuint* arrays);
extern "C" void glDeleteVertexArraysOES(GLsizei n, const GLuint* arrays);
extern "C" void glBindVertexArrayOES(GLuint array);
namespace obscura::gl::raw {
#define OBSCURA_GL_FN(type, name) using ::name;
#define OBSCURA_GL_CACHED_FN(type, name) using ::name;
#include "gl/GlFunctionList.inl"
#undef OBSCURA_GL_FN
#undef OBSCURA_GL_CACHED_FN
using ::glBindVertexArrayOES;
using ::glDeleteVertexArraysOES;
using ::glDrawBuffersEXT;
using ::glGenVertexArraysOES;
}  // namespace obscura::gl::raw
#else
#define OBSCURA_GL_DIRECT 0
#define GL_GLES_PROTOTYPES 0
#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>
namespace obscura::gl::raw {
#define OBSCURA_GL_FN(type, name) extern type name;
#define OBSCURA_GL_CACHED_FN(type, name) extern type name;
#include "gl/GlFunctionList.inl"
#undef OBSCURA_GL_FN
#undef OBSCURA_GL_CACHED_FN
// Extension entry points: loaded when the context has them, null otherwise (GlCaps says which are usable).
extern PFNGLDRAWBUFFERSEXTPROC glDrawBuffersEXT;
// OES_vertex_array_object on a GLES 2 context; on a desktop context (OSMesa) the same names point at the core
// (GL 3.0, ARB_vertex_array_object) functions, which GlCaps::query chooses (selectVertexArrayEntryPoints).
extern PFNGLGENVERTEXARRAYSOESPROC glGenVertexArraysOES;
extern PFNGLDELETEVERTEXARRAYSOESPROC glDeleteVertexArraysOES;
extern PFNGLBINDVERTEXARRAYOESPROC glBindVertexArrayOES;
}  // namespace obscura::gl::raw
#endif

#include <type_traits>

#include "gl/BindingCache.h"
#include "gl/GlLoader.h"

namespace obscura::gl {
// A raw entry point called after the bindings it depends on are made: `Raw` is the function (web) or the pointer
// the loader filled (native), `Signature` its function type.
template <unsigned Uses, auto& Raw,
          typename Signature = std::remove_pointer_t<std::remove_reference_t<decltype(Raw)>>>
struct GlCall;
template <unsigned Uses, auto& Raw, typename Result, typename... Parameters>
struct GlCall<Uses, Raw, Result(Parameters...)> {
  Result operator()(Parameters... parameters) const {
    bindings::make(Uses);
    return Raw(parameters...);
  }
};
}  // namespace obscura::gl

namespace obscura::gles {
#define OBSCURA_GL_FN(type, name) inline constexpr gl::GlCall<gl::bindingUse(#name), gl::raw::name> name{};
#define OBSCURA_GL_CACHED_FN(type, name)
#include "gl/GlFunctionList.inl"
#undef OBSCURA_GL_FN
#undef OBSCURA_GL_CACHED_FN
inline constexpr gl::GlCall<gl::kUsesAll, gl::raw::glDrawBuffersEXT> glDrawBuffersEXT{};
inline constexpr gl::GlCall<gl::kUsesNone, gl::raw::glGenVertexArraysOES> glGenVertexArraysOES{};
inline void glActiveTexture(GLenum unit) { gl::bindings::activeTexture(unit); }
inline void glBindTexture(GLenum target, GLuint texture) { gl::bindings::bindTexture(target, texture); }
inline void glUseProgram(GLuint program) { gl::bindings::useProgram(program); }
inline void glBindVertexArrayOES(GLuint vertexArray) { gl::bindings::bindVertexArray(vertexArray); }
inline void glViewport(GLint x, GLint y, GLsizei width, GLsizei height) { gl::bindings::viewport(x, y, width, height); }
inline void glDeleteTextures(GLsizei count, const GLuint* textures) { gl::bindings::deleteTextures(count, textures); }
inline void glDeleteVertexArraysOES(GLsizei count, const GLuint* vertexArrays) {
  gl::bindings::deleteVertexArrays(count, vertexArrays);
}
}  // namespace obscura::gles

namespace obscura {
using namespace gles;  // NOLINT: glFoo resolves to the wrappers above, natively and on the web.
}  // namespace obscura
