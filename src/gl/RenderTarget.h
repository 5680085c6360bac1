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

 private:
  TextureHandle texture_;
  int width_ = 0, height_ = 0;
};

// A framebuffer with one RGBA8 colour texture and, optionally, a depth renderbuffer.
class RenderTarget {
 public:
  enum class Depth { None, Renderbuffer };
  RenderTarget() = default;
  // Throws GlError with a readable reason if the framebuffer is incomplete. `name` appears in messages. With
  // `stencil` (where GlCaps::packedDepthStencil), the depth renderbuffer also holds 8 stencil bits.
  RenderTarget(const std::string& name, int width, int height, GLenum filter, Depth depth, bool depth24,
               bool stencil = false);

  int width() const { return color_.width(); }
  int height() const { return color_.height(); }
  const Texture2D& color() const { return color_; }
  GLuint framebuffer() const { return framebuffer_.id(); }
  explicit operator bool() const { return framebuffer_.id() != 0; }

  // A framebuffer drawing into `color`'s texture with `depthOwner`'s depth renderbuffer attached (same size), so a
  // pass can depth-test against what another pass drew (the lighting pass against the G-buffer's depth). Throws
  // GlError if it is incomplete.
  static FramebufferHandle sharingDepth(const RenderTarget& color, const RenderTarget& depthOwner,
                                        const std::string& name);
  // A framebuffer drawing into every target's texture at once (EXT_draw_buffers: colour attachment i is
  // targets[i], and its draw buffers are set to all of them), with the first depth renderbuffer among them. All the
  // same size. Throws GlError if it is incomplete.
  static FramebufferHandle multipleTargets(const std::vector<const RenderTarget*>& targets, const std::string& name);

  // Binds the framebuffer and sets the viewport to cover it.
  void bindForDrawing() const;
  // Reads the colour attachment back, rows top-to-bottom (image order, row 0 at the top).
  std::vector<std::uint8_t> readRgba() const;

 private:
  // Attaches depth_ to the bound framebuffer at the attachment point its format needs.
  void attachDepth() const;

  std::string name_;
  Texture2D color_;
  RenderbufferHandle depth_;
  bool stencil_ = false;  // a packed depth + stencil renderbuffer (WebGL 1's DEPTH_STENCIL, DEPTH24_STENCIL8_OES)
  FramebufferHandle framebuffer_;
};

// Throws GlError naming `what` when the bound framebuffer is not complete.
void checkFramebufferComplete(const std::string& what);

// Reads W x H RGBA8 pixels of the bound framebuffer, flipped to image order (row 0 at the top).
std::vector<std::uint8_t> readPixelsTopDown(int width, int height);

}  // namespace obscura::gl
