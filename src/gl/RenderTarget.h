#pragma once
// RGBA8 textures and the framebuffers that render into them: the only render-target format Obscura uses, since
// core GLES 2 / WebGL 1 has no float, depth or multiple render targets.
#include <cstdint>
#include <string>
#include <vector>

#include "gl/GlObjects.h"

namespace obscura::gl {

// A 2D RGBA8 texture with clamp-to-edge wrapping (legal for any size under WebGL 1) and the given filter.
class Texture2D {
 public:
  Texture2D() = default;
  Texture2D(int width, int height, GLenum filter, const void* rgba = nullptr);

  GLuint id() const { return texture_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }
  void bind(int unit) const;
  void upload(const void* rgba);

 private:
  TextureHandle texture_;
  int width_ = 0, height_ = 0;
};

// A framebuffer with one RGBA8 colour texture and, optionally, a depth renderbuffer.
class RenderTarget {
 public:
  enum class Depth { None, Renderbuffer };
  RenderTarget() = default;
  // Throws GlError with a readable reason if the framebuffer is incomplete. `name` appears in messages.
  RenderTarget(const std::string& name, int width, int height, GLenum filter, Depth depth, bool depth24);

  int width() const { return color_.width(); }
  int height() const { return color_.height(); }
  const Texture2D& color() const { return color_; }
  GLuint framebuffer() const { return framebuffer_.id(); }
  explicit operator bool() const { return framebuffer_.id() != 0; }

  // Binds the framebuffer and sets the viewport to cover it.
  void bindForDrawing() const;
  // Reads the colour attachment back, rows top-to-bottom (image order, row 0 at the top).
  std::vector<std::uint8_t> readRgba() const;

 private:
  std::string name_;
  Texture2D color_;
  RenderbufferHandle depth_;
  FramebufferHandle framebuffer_;
};

// Throws GlError naming `what` when the bound framebuffer is not complete.
void checkFramebufferComplete(const std::string& what);

// Reads W x H RGBA8 pixels of the bound framebuffer, flipped to image order (row 0 at the top).
std::vector<std::uint8_t> readPixelsTopDown(int width, int height);

}  // namespace obscura::gl
