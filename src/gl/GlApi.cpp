#include "gl/GlApi.h"

#if !OBSCURA_GL_DIRECT
namespace obscura::gles {
#define OBSCURA_GL_FN(type, name) type name = nullptr;
#include "gl/GlFunctionList.inl"
#undef OBSCURA_GL_FN
PFNGLDRAWBUFFERSEXTPROC glDrawBuffersEXT = nullptr;
}  // namespace obscura::gles
#endif

namespace obscura::gl {

bool loadGles2([[maybe_unused]] ProcLoader loader, [[maybe_unused]] std::string* missing) {
#if OBSCURA_GL_DIRECT
  return true;
#else
#define OBSCURA_GL_FN(type, name)                                 \
  gles::name = reinterpret_cast<type>(loader(#name));             \
  if (!gles::name) {                                              \
    if (missing) *missing = #name;                                \
    return false;                                                 \
  }
#include "gl/GlFunctionList.inl"
#undef OBSCURA_GL_FN
  gles::glDrawBuffersEXT = reinterpret_cast<PFNGLDRAWBUFFERSEXTPROC>(loader("glDrawBuffersEXT"));
  return true;
#endif
}

}  // namespace obscura::gl
