#include "core/DepthHierarchyPass.h"

#include <algorithm>
#include <string>

#include "core/SaoKernel.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

int nextPowerOfTwo(int v) {
  int p = 1;
  while (p < v) p *= 2;
  return p;
}

glm::ivec2 levelSize(int width, int height, int level) {
  return SaoKernel::hierarchyLevelSize(glm::ivec2(width, height), level);
}

}  // namespace

std::vector<ProgramSpec> DepthHierarchyPass::programSpecs() {
  return {ProgramSpec{"depth-hierarchy",
                      "fullscreen.vert",
                      "depth_hierarchy.frag",
                      {{"MAX_MIP_LEVEL", std::to_string(SaoKernel::kMaxMipLevel)}},
                      {}}};
}

DepthHierarchyPass::Storage DepthHierarchyPass::storageFor(const gl::GlCaps& caps, bool allowExtensions) {
  return allowExtensions && caps.shaderTextureLod && caps.fboRenderMipmap ? Storage::MipChain
                                                                          : Storage::SeparateTextures;
}

DepthHierarchyPass::DepthHierarchyPass(const FullscreenTriangle& triangle, Storage storage)
    : triangle_(triangle), storage_(storage), program_(programSpecs().front().build()) {}

void DepthHierarchyPass::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  width_ = width;
  height_ = height;
  levels_.clear();
  mipFramebuffers_.clear();
  mipTexture_.reset();
  if (storage_ == Storage::SeparateTextures) {
    for (int level = 1; level <= SaoKernel::kMaxMipLevel; ++level) {
      const glm::ivec2 size = levelSize(width, height, level);
      levels_.emplace_back("depth hierarchy level " + std::to_string(level), size.x, size.y, GL_NEAREST,
                           gl::RenderTarget::Depth::None, false);
    }
    return;
  }
  // A power-of-two texture (WebGL 1 allows mipmaps on those only) whose mip level j is at least as large as
  // hierarchy level j + 1. Every level down to 1x1 is allocated, as mipmap completeness requires.
  const glm::ivec2 first = levelSize(width, height, 1);
  mipWidth_ = nextPowerOfTwo(first.x);
  mipHeight_ = nextPowerOfTwo(first.y);
  mipTexture_ = gl::TextureHandle::create();
  glBindTexture(GL_TEXTURE_2D, mipTexture_.id());
  for (int j = 0, w = mipWidth_, h = mipHeight_;; ++j, w = std::max(1, w / 2), h = std::max(1, h / 2)) {
    glTexImage2D(GL_TEXTURE_2D, j, GL_RGBA, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    if (w == 1 && h == 1) break;
  }
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  for (int level = 1; level <= SaoKernel::kMaxMipLevel; ++level) {
    mipFramebuffers_.push_back(gl::FramebufferHandle::create());
    glBindFramebuffer(GL_FRAMEBUFFER, mipFramebuffers_.back().id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, mipTexture_.id(), level - 1);
    gl::checkFramebufferComplete("depth hierarchy mip level " + std::to_string(level - 1));
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void DepthHierarchyPass::render(const gl::Texture2D& gbuffer) {
  program_.use();
  gbuffer.bind(0);
  program_.set("u_gbuffer", 0);
  program_.set("u_gbufferSize", glm::vec2(gbuffer.width(), gbuffer.height()));
  for (int level = 1; level <= SaoKernel::kMaxMipLevel; ++level) {
    const glm::ivec2 size = levelSize(width_, height_, level);
    if (storage_ == Storage::SeparateTextures) {
      levels_[static_cast<size_t>(level - 1)].bindForDrawing();
    } else {
      glBindFramebuffer(GL_FRAMEBUFFER, mipFramebuffers_[static_cast<size_t>(level - 1)].id());
      glViewport(0, 0, size.x, size.y);  // the level's data fills the corner of its mip level
    }
    program_.set("u_level", static_cast<float>(level));
    triangle_.draw();
  }
  gl::restoreBaselineState();
}

void DepthHierarchyPass::bindForSampling(const gl::Program& sao, int firstUnit) const {
  if (storage_ == Storage::SeparateTextures) {
    for (int level = 1; level <= SaoKernel::kMaxMipLevel; ++level) {
      const int unit = firstUnit + level - 1;
      levels_[static_cast<size_t>(level - 1)].color().bind(unit);
      const std::string name = "u_level" + std::to_string(level);
      sao.set(name.c_str(), unit);
    }
  } else {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + firstUnit));
    glBindTexture(GL_TEXTURE_2D, mipTexture_.id());
    sao.set("u_depthMips", firstUnit);
    sao.set("u_depthMipsSize", glm::vec2(mipWidth_, mipHeight_));
  }
}

}  // namespace obscura
