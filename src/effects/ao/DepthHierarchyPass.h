#pragma once
// SAO's depth hierarchy under GLES 2 / WebGL 1 (McGuire, Mara, Luebke 2012, sec. 3.3; shader:
// shaders_es2/ao/depth_hierarchy.frag). Level 0 is the G-buffer itself; levels 1 .. SaoKernel::kMaxMipLevel (5) hold
// the packed depth key of one texel per 2^m x 2^m block, picked on a rotated grid (never averaged), and where in the
// block that texel lies.
//
// Core GLES 2 cannot render into mip levels above 0 and a fragment shader cannot choose a level, so the levels are
// stored in one of three ways (the same bytes each time, so the same AO; tested):
//   SeparateTextures  each level its own RGBA8 texture of halving size. The SAO shader picks the texture with a
//                     branch per level, and a rasteriser that runs every side of a divergent branch (llvmpipe,
//                     SwiftShader: CPU SIMD) then pays for all five fetches on every tap.
//   Atlas             levels 0 .. 5 as regions of one RGBA8 texture: level 0 (a copy of the G-buffer's depth key)
//                     at the origin, levels 1 .. 5 in a column to its right. One fetch per tap, no branch; the
//                     default without the extensions, when 1.5 x the width fits the texture size limit.
//   MipChain          OES_fbo_render_mipmap + EXT_shader_texture_lod: the levels are mip levels 0..4 of one
//                     power-of-two texture, rendered directly and read with texture2DLodEXT.
//
// Levels at 1920x1080: 960x540, 480x270, 240x135, 120x67, 60x33 -- a third of the G-buffer's pixels in all.
#include <optional>
#include <vector>

#include "frame/EffectEntry.h"
#include "frame/FullscreenPass.h"
#include "frame/FullscreenTriangle.h"
#include "frame/RendererOptions.h"
#include "gl/GlCaps.h"
#include "gl/RenderTarget.h"
#include "gl/ShaderLibrary.h"

namespace obscura {

class DepthHierarchyPass {
 public:
  // How the levels are stored (frame/RendererOptions.h, where a Renderer may be told which). SAO's program variants
  // are keyed by it too (sao.frag's DEPTH_HIERARCHY: the storage's value, or 0 for no hierarchy: SaoPass::programSpec
  // takes an optional Storage).
  using Storage = HierarchyStorage;

  // The level program for one depth layer (RG: the pick's offset) or two (RG: the second layer's depth code).
  static ProgramSpec programSpec(int layers);
  static std::vector<ProgramSpec> programSpecs();
  // MipChain where the context has both extensions, else Atlas; `forced` overrides (tests, benchmarks). An Atlas
  // falls back to SeparateTextures at sizes it would not fit (see storage()).
  static Storage storageFor(const gl::GlCaps& caps, std::optional<Storage> forced = std::nullopt);
  static const char* storageName(Storage storage);

  DepthHierarchyPass(const FullscreenTriangle& triangle, const gl::GlCaps& caps, Storage storage,
                     const EffectResources& resources);
  // The storage in use: the one asked for, or SeparateTextures when an atlas of this size would not fit.
  Storage storage() const { return active_; }
  void resize(int width, int height);
  // `secondLayer` (ao.layers 2: effects/ao/DepthPeelPass.h) given, every level's RG holds its depth code at the
  // picked pixel instead of the pick's offset (shaders_es2/ao/hierarchy_pick.glsl gives the offset then).
  void render(const gl::Texture2D& gbuffer, const gl::Texture2D* secondLayer = nullptr);
  // Binds the levels for sao.frag (DEPTH_HIERARCHY 1, 2 or 3) to the draw's next units, and sets their uniforms.
  void bindForSampling(FullscreenDraw& sao) const;
  // Level m (0 .. 5; 0 only with the atlas) read back, rows top to bottom, whatever the storage (tests, tools).
  std::vector<std::uint8_t> readLevel(int m) const;

 private:
  struct Region {
    int x = 0, y = 0, width = 0, height = 0;
  };
  Region atlasRegion(int level) const;

  const FullscreenTriangle& triangle_;
  gl::GlCaps caps_;
  Storage requested_, active_;
  ProgramCache& programs_;  // the level programs, one layer and two (programSpec), built on first use
  int width_ = 0, height_ = 0;
  std::vector<gl::RenderTarget> levels_;  // SeparateTextures: levels 1..5
  gl::RenderTarget atlas_;                // Atlas: levels 0..5
  gl::TextureHandle mipTexture_;          // MipChain: one texture, levels 0..4 used
  std::vector<gl::FramebufferHandle> mipFramebuffers_;
  int mipWidth_ = 0, mipHeight_ = 0;
};

}  // namespace obscura
