#pragma once
// The AO pipeline of one frame, the same on every platform:
//   G-buffer -> depth hierarchy -> SAO -> bilateral blur (H, V) -> [upsample, at half resolution]
//            -> forward lighting with AO on the ambient term (or a diagnostic view).
// The platform layer owns the context and the output framebuffer; the Renderer owns every GL object it creates.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/AoSettings.h"
#include "core/AoUpsamplePass.h"
#include "core/BilateralBlurPass.h"
#include "core/DebugViewPass.h"
#include "core/DepthHierarchyPass.h"
#include "core/FrameContext.h"
#include "core/GBufferPass.h"
#include "core/GpuScene.h"
#include "core/LightingPass.h"
#include "core/SaoPass.h"
#include "gl/GlCaps.h"
#include "scene/Camera.h"
#include "scene/Scene.h"

namespace obscura {

enum class View { Final, Ao, AoRaw, Normals, Depth, Mask };
View parseView(const std::string& name);  // final | ao | ao-raw | normals | depth | mask; throws InputError
const char* viewName(View view);

enum class Pass { GBuffer, Hierarchy, Sao, BlurHorizontal, BlurVertical, Upsample, Composite, Count };
const char* passName(Pass pass);

// Receives the start and end of each pass (per-pass timings: glFinish-bounded natively, timer queries on the web).
class PassTimer {
 public:
  virtual ~PassTimer() = default;
  virtual void begin(Pass pass) = 0;
  virtual void end(Pass pass) = 0;
};

struct OutputTarget {
  GLuint framebuffer = 0;  // 0: the default framebuffer
  int width = 1, height = 1;
  float aoSplitX = 0.0f;   // Final view: AO applies right of this pixel column (split-screen comparison)
};

struct RendererOptions {
  bool checkGlErrors = false;        // glGetError after every pass; a GL error throws GlError naming the pass
  bool allowUint32Indices = true;    // false simulates a context without OES_element_index_uint
  // How the depth hierarchy is stored; unset: the extension mip chain where available, else the atlas
  // (DepthHierarchyPass.h). Tests and benchmarks force each storage to compare them.
  std::optional<DepthHierarchyPass::Storage> hierarchyStorage;
};

class Renderer {
 public:
  // Throws GlError if the context cannot run Obscura (no fragment highp) or a shader fails to build.
  explicit Renderer(const gl::GlCaps& caps, const RendererOptions& options = {});
  // The passes hold references to the renderer's shared full-screen triangle: a Renderer stays where it is built.
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  void setScene(const Scene& scene);
  void render(const Camera& camera, const AoSettings& settings, View view, const OutputTarget& output,
              PassTimer* timer = nullptr);

  // Every program the renderer may build, for the shader validation tools and tests.
  static std::vector<ProgramSpec> allProgramSpecs();

  const gl::GlCaps& caps() const { return caps_; }
  const GpuScene& gpuScene() const { return scene_; }
  // The textures of the last frame, for tests and tools.
  const gl::RenderTarget& gbuffer() const { return gbuffer_.target(); }
  const gl::RenderTarget& rawAo() const { return sao_.target(); }  // half size at half resolution
  DepthHierarchyPass::Storage hierarchyStorage() const { return hierarchy_.storage(); }
  // The AO the lighting pass used: blurred, or raw when the blur is off.
  const gl::Texture2D& finalAo() const { return *finalAo_; }

 private:
  void checkErrors(Pass after) const;

  gl::GlCaps caps_;
  RendererOptions options_;
  FullscreenTriangle triangle_;
  GpuScene scene_;
  GBufferPass gbuffer_;
  DepthHierarchyPass hierarchy_;
  SaoPass sao_;
  BilateralBlurPass blur_;
  AoUpsamplePass upsample_;
  LightingPass lighting_;
  DebugViewPass debugView_;
  gl::Texture2D white_;  // AO = 1 when AO is off
  const gl::Texture2D* finalAo_ = nullptr;
  Lighting light_;
};

}  // namespace obscura
