#pragma once
// Loading the GLES 2 dispatch table (gl/GlApi.h) from the current context. Kept free of GL headers so platform code
// can include it beside its own (OSMesa's header pulls in desktop <GL/gl.h>, which the core must never see).
#include <string>

namespace obscura::gl {

using ProcLoader = void* (*)(const char* name);

// Fills the dispatch table from the current context. Returns false and names the first missing entry point if the
// context lacks one. On the web (direct linking) this is a no-op.
bool loadGles2(ProcLoader loader, std::string* missing);

// Points the OES_vertex_array_object names of the dispatch table (gl::raw::glBindVertexArrayOES, ...) at the entry
// points the current context's kind has: the OES ones on GLES 2, the core ones (glBindVertexArray) on a desktop
// context, whose dispatch may hand out a stub for an OES name it does not implement. True where all three loaded
// (always on the web, where Emscripten links them). GlCaps::query calls it once it knows the context's kind.
bool selectVertexArrayEntryPoints(bool desktopGl);

}  // namespace obscura::gl
