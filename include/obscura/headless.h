#pragma once
// Headless OpenGL ES 2 contexts (component Obscura::headless; pkg-config obscura-headless): Mesa's EGL on the
// surfaceless platform (a true GLES 2 context, no display; the first EGL device where the vendor has no surfaceless
// platform) or OSMesa (llvmpipe, a desktop GL context running GLSL ES 1.00). For command-line tools, servers and
// tests: render into an OffscreenFramebuffer (obscura/offscreen.h) and read the pixels back.
#include <memory>
#include <string>

#include "obscura/obscura.h"

namespace obscura::api {

class HeadlessContext {
 public:
  enum class Backend { Egl, OSMesa };
  // Creates the context and makes it current on this thread. Throws Error with the reason if the backend is
  // unavailable (no EGL display, libOSMesa missing).
  explicit HeadlessContext(Backend backend = Backend::Egl);
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  Backend backend() const { return backend_; }
  // Resolves the context's entry points: pass it to Renderer::Options::getProcAddress.
  ProcAddressLoader getProcAddress() const;
  // "egl" or "osmesa", and the reverse (throws Error for another name).
  static const char* backendName(Backend backend);
  static Backend parseBackend(const std::string& name);

 private:
  struct Impl;
  Backend backend_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace obscura::api
