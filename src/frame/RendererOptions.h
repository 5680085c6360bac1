#pragma once
// How a Renderer is built (not what it draws: that is RenderSettings).
#include <optional>

#include "environment/EnvironmentLayout.h"
#include "gl/GlCaps.h"
#include "gpu/VertexKind.h"

namespace obscura {

// How the AO's depth hierarchy stores its levels (effects/ao/DepthHierarchyPass.h): separate textures, one mip chain
// (OES_fbo_render_mipmap and EXT_shader_texture_lod), or one atlas texture.
enum class HierarchyStorage { SeparateTextures = 1, MipChain = 2, Atlas = 3 };

struct RendererOptions {
  // glGetError after every pass (a GL error throws GlError naming the pass), and strict programs: a uniform a
  // program does not have is an error (gl/Program.h). The tests and the page's debug-gl turn it on.
  bool checkGlErrors = false;
  bool allowUint32Indices = true;  // false simulates a context without OES_element_index_uint
  // false simulates a context without OES_vertex_array_object: the scene's draws set their vertex streams per draw
  // (gpu/GpuScene.h; tests compare both images, the page's `vertex-arrays=0` and the benchmarks measure both).
  bool allowVertexArrays = true;
  // false: every instance is drawn by itself, none in a static batch (gpu/GpuScene.h, staticBatchCount; tests compare
  // both, the page's setStaticBatches(false) and the benchmarks measure both).
  bool batchStaticInstances = true;
  // false simulates a context without EXT_draw_buffers / WEBGL_draw_buffers: the lighting draws the scene a second
  // time instead of reading the base colour the G-buffer pass writes beside it (tests compare both).
  bool allowDrawBuffers = true;
  // false: FXAA runs in one draw even where its target has a stencil buffer (FxaaEffect.h; tests compare both).
  bool allowFxaaStencil = true;
  // false: the passes that limit their work to the scene's bounds on screen (PassContext::sceneRect: the AO's, the
  // deferred lighting's shading, FXAA) run over the whole frame (tests compare both; the benchmark measures both).
  bool limitToScene = true;
  // false: every instance is drawn whatever the view, none left out by frustum culling (GpuScene::cullToView; tests
  // compare both, the benchmark measures both).
  bool cullToView = true;
  // false: per-pixel stages run as passes of their own instead of fusing into the pass before them (frame/Stage.h;
  // tests compare both, the benchmark measures what fusing saves).
  bool fuseStages = true;
  // false: the frame's plan is made every frame instead of being found among the cached ones (renderer/Renderer.h;
  // tests compare both, the benchmark measures what caching saves).
  bool cachePlans = true;
  // How the depth hierarchy is stored; unset: the extension mip chain where available, else the atlas
  // (DepthHierarchyPass.h). Tests and benchmarks force each storage to compare them.
  std::optional<HierarchyStorage> hierarchyStorage;
  // Where the prefiltered environment's roughness levels live; unset: half floats the hardware filters where the
  // context has OES_texture_half_float_linear, else the mip chain read with texture2DLodEXT where
  // EXT_shader_texture_lod exists, else the atlas (environment/Environment.h). Tests force each to compare them.
  std::optional<EnvironmentLayout> environmentLayout;
  // Which of the environment's levels the hardware's filter reads; unset (EnvironmentFiltering::Measured): levels
  // 2 .. 5 where they keep kEnvironmentFilterBound, else none (environment/Environment.h). Benchmarks and tests
  // force either to compare them.
  EnvironmentFiltering environmentFiltering = EnvironmentFiltering::Measured;
  // How skinned meshes are drawn; unset: the joint texture where the context has vertex textures and float
  // textures, else the uniform palette (gpu/GpuScene.h). A path the context cannot take falls back the same way.
  std::optional<SkinningPath> skinning;
  std::optional<VertexLimits> simulateVertexLimits;  // tests run the GLES 2 minimums on any context
  std::optional<FragmentLimits> simulateFragmentLimits;
  // The velocity pass draws every instance, not only those that moved (effects/velocity/VelocityEffect.h): the
  // alternative the benchmark measures, and the tests' check that both give the same vectors.
  bool velocityDrawsEverything = false;
  // The G-buffer's normal is the shading normal (the normal texture applied, as the lighting shades) rather than the
  // interpolated vertex normal. Off: measured against the ray-traced AO, the AO is closer with the geometric normal
  // (docs/pbr.md; tests/test_baked_occlusion.cpp measures both).
  bool gbufferShadingNormals = false;
};

}  // namespace obscura
