#pragma once
// How a Renderer is built (not what it draws: that is RenderSettings).
#include <optional>

#include "core/DepthHierarchyPass.h"

namespace obscura {

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
};

}  // namespace obscura
