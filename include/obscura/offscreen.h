#pragma once
// An RGBA8 framebuffer of Obscura's to render into when the caller has none (headless tools, tests), read back, and
// written as PNG. Part of the core library (Obscura::obscura); needs a current GLES 2 context like the Renderer.
#include <cstdint>
#include <string>
#include <vector>

#include "obscura/obscura.h"

namespace obscura::api {

class OffscreenFramebuffer {
 public:
  // An RGBA8 colour texture of width x height (NEAREST) with a framebuffer around it. Throws Error if the context
  // cannot make one. Create it after a Renderer (which loads the GL entry points).
  OffscreenFramebuffer(int width, int height);
  ~OffscreenFramebuffer();
  OffscreenFramebuffer(OffscreenFramebuffer&&) noexcept;
  OffscreenFramebuffer& operator=(OffscreenFramebuffer&&) noexcept;
  OffscreenFramebuffer(const OffscreenFramebuffer&) = delete;
  OffscreenFramebuffer& operator=(const OffscreenFramebuffer&) = delete;

  Framebuffer framebuffer() const;  // for Renderer::render and friends
  unsigned int texture() const;     // its colour texture (a GLuint)
  int width() const;
  int height() const;
  // The pixels, RGBA8, rows top to bottom (image order).
  std::vector<std::uint8_t> readRgba() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes RGBA8 rows top to bottom as a PNG. Throws Error naming the path if it cannot be written.
void writePng(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgba);

}  // namespace obscura::api
