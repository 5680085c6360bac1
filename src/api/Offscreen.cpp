// obscura/offscreen.h over gl::RenderTarget and scene/ImageIo.
#include "obscura/offscreen.h"

#include "gl/RenderTarget.h"
#include "scene/ImageIo.h"

namespace obscura::api {

struct OffscreenFramebuffer::Impl {
  gl::RenderTarget target;
};

OffscreenFramebuffer::OffscreenFramebuffer(int width, int height) : impl_(std::make_unique<Impl>()) {
  if (width < 1 || height < 1)
    throw Error("OffscreenFramebuffer: " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  try {
    impl_->target = gl::RenderTarget("obscura-offscreen", width, height, GL_NEAREST, gl::RenderTarget::Depth::None,
                                     false);
  } catch (const std::exception& e) {
    throw Error(e.what());
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}
OffscreenFramebuffer::~OffscreenFramebuffer() = default;
OffscreenFramebuffer::OffscreenFramebuffer(OffscreenFramebuffer&&) noexcept = default;
OffscreenFramebuffer& OffscreenFramebuffer::operator=(OffscreenFramebuffer&&) noexcept = default;

Framebuffer OffscreenFramebuffer::framebuffer() const {
  return {impl_->target.framebuffer(), impl_->target.width(), impl_->target.height()};
}
unsigned int OffscreenFramebuffer::texture() const { return impl_->target.color().id(); }
int OffscreenFramebuffer::width() const { return impl_->target.width(); }
int OffscreenFramebuffer::height() const { return impl_->target.height(); }
std::vector<std::uint8_t> OffscreenFramebuffer::readRgba() const {
  std::vector<std::uint8_t> pixels = impl_->target.readRgba();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return pixels;
}

void writePng(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgba) {
  if (width < 1 || height < 1 || rgba.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4)
    throw Error("writePng: " + std::to_string(rgba.size()) + " bytes are not " + std::to_string(width) + "x" +
                std::to_string(height) + " RGBA8 pixels");
  try {
    obscura::writePng(path, Image{width, height, rgba});
  } catch (const std::exception& e) {
    throw Error(e.what());
  }
}

}  // namespace obscura::api
