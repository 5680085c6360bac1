#pragma once
// The one door to OpenGL ES 2.0 for all of Obscura.
//
// The core includes <GLES2/gl2.h> (and gl2ext.h for guarded extensions) and nothing else, so it cannot call a
// desktop-GL entry point: the same code links for WebGL 1.
//
// On the web, Emscripten provides the GLES 2 functions directly. Natively, one process may hold an OSMesa context
// or an EGL (GLES 2) context, each with its own dispatch, so the prototypes are switched off and the entry points are
// function pointers in namespace obscura::gles, filled from the current context's GetProcAddress (loadGles2). Code
// in namespace obscura calls glFoo(...) unqualified either way.
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
namespace obscura::gles {}
#else
#define OBSCURA_GL_DIRECT 0
#define GL_GLES_PROTOTYPES 0
#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>
namespace obscura::gles {
#define OBSCURA_GL_FN(type, name) extern type name;
#include "gl/GlFunctionList.inl"
#undef OBSCURA_GL_FN
// Extension entry points: loaded when the context has them, null otherwise (GlCaps says which are usable).
extern PFNGLDRAWBUFFERSEXTPROC glDrawBuffersEXT;
// OES_vertex_array_object on a GLES 2 context; on a desktop context (OSMesa) the same names point at the core
// (GL 3.0, ARB_vertex_array_object) functions, which GlCaps::query chooses (selectVertexArrayEntryPoints).
extern PFNGLGENVERTEXARRAYSOESPROC glGenVertexArraysOES;
extern PFNGLDELETEVERTEXARRAYSOESPROC glDeleteVertexArraysOES;
extern PFNGLBINDVERTEXARRAYOESPROC glBindVertexArrayOES;
}  // namespace obscura::gles
#endif

#include "gl/GlLoader.h"

namespace obscura {
using namespace gles;  // NOLINT: makes glFoo resolve to the dispatch table natively, to the prototypes on the web.
}  // namespace obscura
