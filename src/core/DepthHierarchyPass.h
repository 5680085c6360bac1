#pragma once
// SAO's depth hierarchy under GLES 2 / WebGL 1 (McGuire, Mara, Luebke 2012, sec. 3.3; shader:
// shaders_es2/depth_hierarchy.frag). Level 0 is the G-buffer itself; levels 1 .. SaoKernel::kMaxMipLevel (5) hold
// the packed depth key of one texel per 2^m x 2^m block, picked on a rotated grid (never averaged).
//
// Core GLES 2 cannot render into mip levels above 0 and a fragment shader cannot choose a level, so there are two
// storage paths, chosen by what the context offers:
//   SeparateTextures  each level its own RGBA8 texture of halving size; the SAO shader branches on the level.
//   MipChain          OES_fbo_render_mipmap + EXT_shader_texture_lod: the levels are mip levels 0..4 of one
//                     power-of-two texture, rendered directly and read with texture2DLodEXT.
// Both hold the same bytes, so the AO is the same (tested where both exist).
//
// Levels at 1920x1080: 960x540, 480x270, 240x135, 120x67, 60x33 -- a third of the G-buffer's pixels in all.
#include <array>
#include <vector>

#include "core/FrameContext.h"
#include "core/ShaderLibrary.h"
#include "gl/GlCaps.h"
#include "gl/RenderTarget.h"

namespace obscura {

class DepthHierarchyPass {
 public:
  enum class Storage { SeparateTextures, MipChain };

  static std::vector<ProgramSpec> programSpecs();
  // The mip-chain path needs both extensions; `allowExtensions` = false forces the core path (tests, benchmarks).
  static Storage storageFor(const gl::GlCaps& caps, bool allowExtensions);

  DepthHierarchyPass(const FullscreenTriangle& triangle, Storage storage);
  Storage storage() const { return storage_; }
  void resize(int width, int height);
  void render(const gl::Texture2D& gbuffer);
  // Binds the levels for sao.frag (DEPTH_HIERARCHY 1 or 2) to texture units firstUnit, firstUnit + 1, ...
  void bindForSampling(const gl::Program& sao, int firstUnit) const;
  // Level m (1 .. 5) of the SeparateTextures storage, for tests and tools.
  const gl::RenderTarget& level(int m) const { return levels_.at(static_cast<size_t>(m - 1)); }

 private:
  const FullscreenTriangle& triangle_;
  Storage storage_;
  gl::Program program_;
  int width_ = 0, height_ = 0;
  std::vector<gl::RenderTarget> levels_;        // SeparateTextures: levels 1..5
  gl::TextureHandle mipTexture_;                // MipChain: one texture, levels 0..4 used
  std::vector<gl::FramebufferHandle> mipFramebuffers_;
  int mipWidth_ = 0, mipHeight_ = 0;
};

}  // namespace obscura
