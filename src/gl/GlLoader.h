#pragma once
// Loading the GLES 2 dispatch table (gl/GlApi.h) from the current context. Kept free of GL headers so platform code
// can include it beside its own (OSMesa's header pulls in desktop <GL/gl.h>, which the core must never see).
#include <string>

namespace obscura::gl {

using ProcLoader = void* (*)(const char* name);

// Fills the dispatch table from the current context. Returns false and names the first missing entry point if the
// context lacks one. On the web (direct linking) this is a no-op.
bool loadGles2(ProcLoader loader, std::string* missing);

}  // namespace obscura::gl
