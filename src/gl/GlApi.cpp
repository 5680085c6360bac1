#include "gl/GlApi.h"

#if !OBSCURA_GL_DIRECT
namespace obscura::gl::raw {
#define OBSCURA_GL_FN(type, name) type name = nullptr;
#define OBSCURA_GL_CACHED_FN(type, name) type name = nullptr;
#include "gl/GlFunctionList.inl"
#undef OBSCURA_GL_FN
#undef OBSCURA_GL_CACHED_FN
PFNGLDRAWBUFFERSEXTPROC glDrawBuffersEXT = nullptr;
PFNGLGENVERTEXARRAYSOESPROC glGenVertexArraysOES = nullptr;
PFNGLDELETEVERTEXARRAYSOESPROC glDeleteVertexArraysOES = nullptr;
PFNGLBINDVERTEXARRAYOESPROC glBindVertexArrayOES = nullptr;
}  // namespace obscura::gl::raw

namespace {
// Both spellings of the vertex array entry points, as loaded; selectVertexArrayEntryPoints picks one set.
struct VertexArrayEntryPoints {
  PFNGLGENVERTEXARRAYSOESPROC gen = nullptr;
  PFNGLDELETEVERTEXARRAYSOESPROC del = nullptr;
  PFNGLBINDVERTEXARRAYOESPROC bind = nullptr;
  bool complete() const { return gen && del && bind; }
};
VertexArrayEntryPoints g_oesVertexArrays, g_coreVertexArrays;
}  // namespace
#endif

namespace obscura::gl {

bool loadGles2([[maybe_unused]] ProcLoader loader, [[maybe_unused]] std::string* missing) {
#if OBSCURA_GL_DIRECT
  return true;
#else
#define OBSCURA_GL_FN(type, name)                                 \
  raw::name = reinterpret_cast<type>(loader(#name));              \
  if (!raw::name) {                                               \
    if (missing) *missing = #name;                                \
    return false;                                                 \
  }
#define OBSCURA_GL_CACHED_FN OBSCURA_GL_FN
#include "gl/GlFunctionList.inl"
#undef OBSCURA_GL_FN
#undef OBSCURA_GL_CACHED_FN
  raw::glDrawBuffersEXT = reinterpret_cast<PFNGLDRAWBUFFERSEXTPROC>(loader("glDrawBuffersEXT"));
  g_oesVertexArrays = {reinterpret_cast<PFNGLGENVERTEXARRAYSOESPROC>(loader("glGenVertexArraysOES")),
                       reinterpret_cast<PFNGLDELETEVERTEXARRAYSOESPROC>(loader("glDeleteVertexArraysOES")),
                       reinterpret_cast<PFNGLBINDVERTEXARRAYOESPROC>(loader("glBindVertexArrayOES"))};
  g_coreVertexArrays = {reinterpret_cast<PFNGLGENVERTEXARRAYSOESPROC>(loader("glGenVertexArrays")),
                        reinterpret_cast<PFNGLDELETEVERTEXARRAYSOESPROC>(loader("glDeleteVertexArrays")),
                        reinterpret_cast<PFNGLBINDVERTEXARRAYOESPROC>(loader("glBindVertexArray"))};
  selectVertexArrayEntryPoints(false);
  return true;
#endif
}

bool selectVertexArrayEntryPoints([[maybe_unused]] bool desktopGl) {
#if OBSCURA_GL_DIRECT
  return true;
#else
  const VertexArrayEntryPoints& chosen = desktopGl ? g_coreVertexArrays : g_oesVertexArrays;
  raw::glGenVertexArraysOES = chosen.gen;
  raw::glDeleteVertexArraysOES = chosen.del;
  raw::glBindVertexArrayOES = chosen.bind;
  return chosen.complete();
#endif
}

}  // namespace obscura::gl
