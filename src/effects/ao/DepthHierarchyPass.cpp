#include "effects/ao/DepthHierarchyPass.h"

#include <algorithm>
#include <string>

#include "base/Error.h"
#include "effects/ao/SaoKernel.h"
#include "frame/FullscreenPass.h"

namespace obscura {
namespace {

// SeparateTextures: the samplers of levels 1 .. 5 in sao.frag.
constexpr const char* kLevelSamplers[] = {"u_level1", "u_level2", "u_level3", "u_level4", "u_level5"};

int nextPowerOfTwo(int v) {
  int p = 1;
  while (p < v) p *= 2;
  return p;
}

glm::ivec2 levelSize(int width, int height, int level) {
  return SaoKernel::hierarchyLevelSize(glm::ivec2(width, height), level);
}

// Reads a rectangle of the bound framebuffer, rows top to bottom.
std::vector<std::uint8_t> readRegion(GLuint framebuffer, int x, int y, int width, int height) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  const size_t row = static_cast<size_t>(width) * 4;
  std::vector<std::uint8_t> bottomUp(row * static_cast<size_t>(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x, y, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  std::vector<std::uint8_t> topDown(bottomUp.size());
  for (int r = 0; r < height; ++r)
    std::copy_n(&bottomUp[static_cast<size_t>(height - 1 - r) * row], row, &topDown[static_cast<size_t>(r) * row]);
  return topDown;
}

}  // namespace

ProgramSpec DepthHierarchyPass::programSpec(int layers) {
  return ProgramSpec{layers == 2 ? "depth-hierarchy[layers=2]" : "depth-hierarchy",
                     "lib/fullscreen.vert",
                     "ao/depth_hierarchy.frag",
                     {{"MAX_MIP_LEVEL", std::to_string(SaoKernel::kMaxMipLevel)},
                      {"AO_LAYERS", std::to_string(layers)}},
                     {}};
}

std::vector<ProgramSpec> DepthHierarchyPass::programSpecs() { return {programSpec(1), programSpec(2)}; }

DepthHierarchyPass::Storage DepthHierarchyPass::storageFor(const gl::GlCaps& caps, std::optional<Storage> forced) {
  if (forced) return *forced == Storage::MipChain && !(caps.shaderTextureLod && caps.fboRenderMipmap)
                        ? Storage::Atlas  // asked for an extension path the context lacks
                        : *forced;
  return caps.shaderTextureLod && caps.fboRenderMipmap ? Storage::MipChain : Storage::Atlas;
}

const char* DepthHierarchyPass::storageName(Storage storage) {
  switch (storage) {
    case Storage::SeparateTextures: return "separate";
    case Storage::Atlas: return "atlas";
    case Storage::MipChain: return "mipchain";
  }
  return "?";
}

DepthHierarchyPass::DepthHierarchyPass(const FullscreenTriangle& triangle, const gl::GlCaps& caps, Storage storage,
                                       const EffectResources& resources)
    : triangle_(triangle),
      caps_(caps),
      requested_(storage),
      active_(storage),
      programs_(resources.programs) {}

DepthHierarchyPass::Region DepthHierarchyPass::atlasRegion(int level) const {
  const glm::ivec2 size = levelSize(width_, height_, level);
  if (level == 0) return {0, 0, size.x, size.y};
  // Levels 1 .. 5 one above the other in a column right of level 0.
  int y = 0;
  for (int j = 1; j < level; ++j) y += levelSize(width_, height_, j).y;
  return {width_, y, size.x, size.y};
}

void DepthHierarchyPass::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  width_ = width;
  height_ = height;
  levels_.clear();
  atlas_ = gl::RenderTarget();
  mipFramebuffers_.clear();
  mipTexture_.reset();

  active_ = requested_;
  if (active_ == Storage::Atlas) {
    const Region last = atlasRegion(SaoKernel::kMaxMipLevel);
    const int atlasWidth = width + levelSize(width, height, 1).x;
    const int atlasHeight = std::max(height, last.y + last.height);
    if (std::max(atlasWidth, atlasHeight) <= caps_.maxRenderSize()) {
      atlas_ = gl::RenderTarget("depth hierarchy atlas", atlasWidth, atlasHeight, GL_NEAREST,
                                gl::RenderTarget::Depth::None, false);
      return;
    }
    active_ = Storage::SeparateTextures;  // too wide for this context: one texture per level instead
  }
  if (active_ == Storage::SeparateTextures) {
    for (int level = 1; level <= SaoKernel::kMaxMipLevel; ++level) {
      const glm::ivec2 size = levelSize(width, height, level);
      levels_.emplace_back("depth hierarchy level " + std::to_string(level), size.x, size.y, GL_NEAREST,
                           gl::RenderTarget::Depth::None, false);
    }
    return;
  }
  // MipChain: a power-of-two texture (WebGL 1 allows mipmaps on those only) whose mip level j is at least as large
  // as hierarchy level j + 1. Every level down to 1x1 is allocated, as mipmap completeness requires.
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

void DepthHierarchyPass::render(const gl::Texture2D& gbuffer, const gl::Texture2D* secondLayer) {
  FullscreenDraw draw(programs_.get(programSpec(secondLayer ? 2 : 1)), triangle_);
  draw.texture("u_gbuffer", gbuffer);
  if (secondLayer) draw.texture("u_secondLayer", *secondLayer);
  draw.set("u_gbufferSize", glm::vec2(gbuffer.width(), gbuffer.height()));
  // The atlas also holds level 0 (a copy of the G-buffer's depth key), so every tap reads the one texture.
  const int firstLevel = active_ == Storage::Atlas ? 0 : 1;
  if (active_ == Storage::Atlas) glBindFramebuffer(GL_FRAMEBUFFER, atlas_.framebuffer());
  for (int level = firstLevel; level <= SaoKernel::kMaxMipLevel; ++level) {
    switch (active_) {
      case Storage::SeparateTextures: levels_[static_cast<size_t>(level - 1)].bindForDrawing(); break;
      case Storage::Atlas: {
        const Region region = atlasRegion(level);
        glViewport(region.x, region.y, region.width, region.height);
        break;
      }
      case Storage::MipChain: {
        const glm::ivec2 size = levelSize(width_, height_, level);
        glBindFramebuffer(GL_FRAMEBUFFER, mipFramebuffers_[static_cast<size_t>(level - 1)].id());
        glViewport(0, 0, size.x, size.y);  // the level's data fills the corner of its mip level
        break;
      }
    }
    draw.set("u_level", static_cast<float>(level));
    draw.draw();
  }
}

void DepthHierarchyPass::bindForSampling(FullscreenDraw& sao) const {
  switch (active_) {
    case Storage::SeparateTextures:
      for (int level = 1; level <= SaoKernel::kMaxMipLevel; ++level)
        sao.texture(kLevelSamplers[level - 1], levels_[static_cast<size_t>(level - 1)].color());
      break;
    case Storage::Atlas: {
      sao.texture("u_depthAtlas", atlas_.color());
      sao.set("u_depthAtlasSize", glm::vec2(atlas_.width(), atlas_.height()));
      // Levels 2 .. 5 start at these rows (level 1 at row 0).
      sao.set("u_atlasLevelRows", glm::vec4(atlasRegion(2).y, atlasRegion(3).y, atlasRegion(4).y, atlasRegion(5).y));
      break;
    }
    case Storage::MipChain:
      sao.texture("u_depthMips", mipTexture_.id());
      sao.set("u_depthMipsSize", glm::vec2(mipWidth_, mipHeight_));
      break;
  }
}

std::vector<std::uint8_t> DepthHierarchyPass::readLevel(int m) const {
  switch (active_) {
    case Storage::SeparateTextures:
      if (m < 1) throw GlError("depth hierarchy: separate textures start at level 1");
      return levels_.at(static_cast<size_t>(m - 1)).readRgba();
    case Storage::Atlas: {
      const Region region = atlasRegion(m);
      return readRegion(atlas_.framebuffer(), region.x, region.y, region.width, region.height);
    }
    case Storage::MipChain: {
      if (m < 1) throw GlError("depth hierarchy: the mip chain starts at level 1");
      const glm::ivec2 size = levelSize(width_, height_, m);
      return readRegion(mipFramebuffers_.at(static_cast<size_t>(m - 1)).id(), 0, 0, size.x, size.y);
    }
  }
  return {};
}

}  // namespace obscura
