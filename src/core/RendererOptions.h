#pragma once
// How a Renderer is built (not what it draws: that is RenderSettings).
#include <optional>

#include "core/DepthHierarchyPass.h"
#include "core/EnvironmentLayout.h"
#include "core/VertexKind.h"

namespace obscura {

// Limits of the vertex stage to simulate: the renderer uses the smaller of these and the context's. gles2Minimum()
// is what every GLES 2 / WebGL 1 context guarantees: 128 uniform vectors, 8 attributes, no vertex texture units.
struct VertexLimits {
  int uniformVectors = 128, attributes = 8, textureUnits = 0;
  static VertexLimits gles2Minimum() { return {}; }
};

// Limits of the fragment stage (and the program's combined texture units) to simulate, as VertexLimits does for the
// vertex stage. gles2Minimum(): 16 uniform vectors, 8 texture units in the fragment stage, 8 in all. They set the
// punctual lights per draw (LightingEffect::punctualLightsPerDraw) and the texture units (core/TextureUnits.h).
struct FragmentLimits {
  int uniformVectors = 16, textureUnits = 8, combinedTextureUnits = 8;
  static FragmentLimits gles2Minimum() { return {}; }
};

struct RendererOptions {
  // glGetError after every pass (a GL error throws GlError naming the pass), and strict programs: a uniform a
  // program does not have is an error (gl/Program.h). The tests and the page's debug-gl turn it on.
  bool checkGlErrors = false;
  bool allowUint32Indices = true;  // false simulates a context without OES_element_index_uint
  // false simulates a context without EXT_draw_buffers / WEBGL_draw_buffers: the lighting draws the scene a second
  // time instead of reading the base colour the G-buffer pass writes beside it (tests compare both).
  bool allowDrawBuffers = true;
  // false: FXAA runs in one draw even where its target has a stencil buffer (FxaaEffect.h; tests compare both).
  bool allowFxaaStencil = true;
  // How the depth hierarchy is stored; unset: the extension mip chain where available, else the atlas
  // (DepthHierarchyPass.h). Tests and benchmarks force each storage to compare them.
  std::optional<DepthHierarchyPass::Storage> hierarchyStorage;
  // Where the prefiltered environment's roughness levels live; unset: the mip chain read with texture2DLodEXT where
  // EXT_shader_texture_lod exists, else the atlas (core/Environment.h). Tests force the atlas to compare both.
  std::optional<EnvironmentLayout> environmentLayout;
  // How skinned meshes are drawn; unset: the joint texture where the context has vertex textures and float
  // textures, else the uniform palette (core/GpuScene.h). A path the context cannot take falls back the same way.
  std::optional<SkinningPath> skinning;
  std::optional<VertexLimits> simulateVertexLimits;  // tests run the GLES 2 minimums on any context
  std::optional<FragmentLimits> simulateFragmentLimits;
  // The velocity pass draws every instance, not only those that moved (core/VelocityEffect.h): the alternative the
  // benchmark measures, and the tests' check that both give the same vectors.
  bool velocityDrawsEverything = false;
  // The G-buffer's normal is the shading normal (the normal texture applied, as the lighting shades) rather than the
  // interpolated vertex normal. Off: measured against the ray-traced AO, the AO is closer with the geometric normal
  // (docs/pbr.md; tests/test_baked_occlusion.cpp measures both).
  bool gbufferShadingNormals = false;
};

}  // namespace obscura
