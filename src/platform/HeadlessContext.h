#pragma once
// Headless GL contexts for the command-line tools and the tests (native only):
//   OSMesa        Mesa's off-screen renderer (llvmpipe, desktop GL compatibility profile running #version 100
//                 shaders). Deprecated upstream, still the most widely installed.
//   EGL           Mesa's EGL on the surfaceless platform: a true OpenGL ES 2 context, no display needed.
// Either way the GLES 2 dispatch table is loaded from the context, and rendering goes to framebuffer objects.
#include <memory>
#include <string>

#include "gl/GlCaps.h"

namespace obscura {

enum class HeadlessBackend { OSMesa, Egl };
HeadlessBackend parseBackend(const std::string& name);  // "osmesa" | "egl"; throws InputError
const char* backendName(HeadlessBackend backend);

class HeadlessContext {
 public:
  // Creates and makes current a context. Throws GlError with the reason if the backend is unavailable.
  explicit HeadlessContext(HeadlessBackend backend);
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  HeadlessBackend backend() const { return backend_; }
  const gl::GlCaps& caps() const { return caps_; }

 private:
  struct Impl;
  HeadlessBackend backend_;
  std::unique_ptr<Impl> impl_;
  gl::GlCaps caps_;
};

}  // namespace obscura
