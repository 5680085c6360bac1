#include "gl/RenderTarget.h"

#include <cstdio>
#include <cstring>

#include "base/Error.h"

namespace obscura::gl {

Texture2D::Texture2D(int width, int height, GLenum filter, const void* rgba)
    : texture_(TextureHandle::create()), width_(width), height_(height) {
  glBindTexture(GL_TEXTURE_2D, texture_.id());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(filter));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(filter));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  glBindTexture(GL_TEXTURE_2D, 0);
}

void Texture2D::bind(int unit) const {
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  glBindTexture(GL_TEXTURE_2D, texture_.id());
}

void checkFramebufferComplete(const std::string& what) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return;
  const char* reason = "unknown status";
  switch (status) {
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: reason = "an attachment is incomplete"; break;
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: reason = "no image is attached"; break;
    case GL_FRAMEBUFFER_INCOMPLETE_DIMENSIONS: reason = "attachments differ in size"; break;
    case GL_FRAMEBUFFER_UNSUPPORTED: reason = "this combination of formats is unsupported"; break;
    default: break;
  }
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", status);
  throw GlError("framebuffer '" + what + "' is incomplete: " + reason + " (status " + code + ")");
}

namespace {
// Checks the bound framebuffer, then unbinds it whether or not it is complete (the throw leaves no binding behind).
void checkCompleteAndUnbind(const std::string& what) {
  try {
    checkFramebufferComplete(what);
  } catch (...) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    throw;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}
}  // namespace

RenderTarget::RenderTarget(const std::string& name, int width, int height, GLenum filter, Depth depth, bool depth24,
                           bool stencil)
    : name_(name), color_(width, height, filter), framebuffer_(FramebufferHandle::create()) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_.id(), 0);
  if (depth == Depth::Renderbuffer) {
    depth_ = RenderbufferHandle::create();
    glBindRenderbuffer(GL_RENDERBUFFER, depth_.id());
    // Core GLES 2 guarantees only 16-bit depth renderbuffers; OES_depth24 gives 24. WebGL 1 has no OES_depth24 but
    // has a core DEPTH_STENCIL renderbuffer (24-bit depth in practice): with 16 bits, a face seen edge-on at a
    // crease wins the odd pixel and SAO finds it fully occluded (dark dots in the browser, see README's parity).
#if defined(__EMSCRIPTEN__)
    constexpr GLenum kWebGlDepthStencil = 0x84F9;  // WebGL 1 constant
    stencil_ = stencil || !depth24;
    if (stencil_) glRenderbufferStorage(GL_RENDERBUFFER, kWebGlDepthStencil, width, height);
    else
#else
    stencil_ = stencil;
    if (stencil_) glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8_OES, width, height);
    else
#endif
      glRenderbufferStorage(GL_RENDERBUFFER, depth24 ? GL_DEPTH_COMPONENT24_OES : GL_DEPTH_COMPONENT16, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    attachDepth();
  }
  checkCompleteAndUnbind(name);
}

void RenderTarget::attachDepth() const {
#if defined(__EMSCRIPTEN__)
  constexpr GLenum kWebGlDepthStencilAttachment = 0x821A;  // WebGL 1 constant
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, stencil_ ? kWebGlDepthStencilAttachment : GL_DEPTH_ATTACHMENT,
                            GL_RENDERBUFFER, depth_.id());
#else
  // OES_packed_depth_stencil: one renderbuffer at both attachment points.
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.id());
  if (stencil_) glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_.id());
#endif
}

FramebufferHandle RenderTarget::sharingDepth(const RenderTarget& color, const RenderTarget& depthOwner,
                                             const std::string& name) {
  FramebufferHandle framebuffer = FramebufferHandle::create();
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color.color().id(), 0);
  depthOwner.attachDepth();
  checkCompleteAndUnbind(name);
  return framebuffer;
}

FramebufferHandle RenderTarget::multipleTargets(const std::vector<const RenderTarget*>& targets,
                                                const std::string& name) {
  FramebufferHandle framebuffer = FramebufferHandle::create();
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
  std::vector<GLenum> buffers;
  bool depth = false;
  for (const RenderTarget* target : targets) {
    const GLenum attachment = GL_COLOR_ATTACHMENT0_EXT + static_cast<GLenum>(buffers.size());
    glFramebufferTexture2D(GL_FRAMEBUFFER, attachment, GL_TEXTURE_2D, target->color().id(), 0);
    buffers.push_back(attachment);
    if (!depth && target->depth_) {
      target->attachDepth();
      depth = true;
    }
  }
  // Draw-buffer state belongs to the framebuffer: set once here, it holds whenever this one is bound.
  glDrawBuffersEXT(static_cast<GLsizei>(buffers.size()), buffers.data());
  checkCompleteAndUnbind(name);
  return framebuffer;
}

void RenderTarget::bindForDrawing() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, width(), height());
}

std::vector<std::uint8_t> RenderTarget::readRgba() const {
  GLint previous = 0;
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &previous);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  std::vector<std::uint8_t> pixels = readPixelsTopDown(width(), height());
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous));
  return pixels;
}

std::vector<std::uint8_t> readPixelsTopDown(int width, int height) {
  const size_t row = static_cast<size_t>(width) * 4;
  std::vector<std::uint8_t> bottomUp(row * static_cast<size_t>(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
  std::vector<std::uint8_t> topDown(bottomUp.size());
  for (int y = 0; y < height; ++y)
    std::memcpy(&topDown[static_cast<size_t>(y) * row], &bottomUp[static_cast<size_t>(height - 1 - y) * row], row);
  return topDown;
}

}  // namespace obscura::gl
