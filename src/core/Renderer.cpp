#include "core/Renderer.h"

#include <cstdio>

#include "core/Error.h"
#include "core/SaoKernel.h"

namespace obscura {
namespace {

const gl::GlCaps& requireUsable(const gl::GlCaps& caps) {
  if (!caps.fragmentHighp)
    throw GlError("this GL context has no highp float in fragment shaders (GL_HIGH_FLOAT precision is 0); "
                  "Obscura's 16-bit depth packing needs it");
  return caps;
}

struct ScopedPass {
  ScopedPass(PassTimer* timer, Pass pass) : timer_(timer), pass_(pass) {
    if (timer_) timer_->begin(pass_);
  }
  ~ScopedPass() {
    if (timer_) timer_->end(pass_);
  }
  PassTimer* timer_;
  Pass pass_;
};

}  // namespace

View parseView(const std::string& name) {
  for (View v : {View::Final, View::Ao, View::AoRaw, View::Normals, View::Depth, View::Mask})
    if (name == viewName(v)) return v;
  throw InputError("view: expected final, ao, ao-raw, normals, depth or mask, got '" + name + "'");
}

const char* viewName(View view) {
  switch (view) {
    case View::Final: return "final";
    case View::Ao: return "ao";
    case View::AoRaw: return "ao-raw";
    case View::Normals: return "normals";
    case View::Depth: return "depth";
    case View::Mask: return "mask";
  }
  return "?";
}

const char* passName(Pass pass) {
  switch (pass) {
    case Pass::GBuffer: return "gbuffer";
    case Pass::Hierarchy: return "hierarchy";
    case Pass::Sao: return "sao";
    case Pass::BlurHorizontal: return "blur-h";
    case Pass::BlurVertical: return "blur-v";
    case Pass::Upsample: return "upsample";
    case Pass::Composite: return "composite";
    case Pass::Count: break;
  }
  return "?";
}

Renderer::Renderer(const gl::GlCaps& caps, const RendererOptions& options)
    : caps_(requireUsable(caps)),
      options_(options),
      gbuffer_(caps.depth24),
      hierarchy_(triangle_, caps, DepthHierarchyPass::storageFor(caps, options.hierarchyStorage)),
      sao_(triangle_),
      blur_(triangle_),
      upsample_(triangle_),
      debugView_(triangle_),
      white_(1, 1, GL_NEAREST, std::vector<std::uint8_t>{255, 255, 255, 255}.data()) {}

std::vector<ProgramSpec> Renderer::allProgramSpecs() {
  std::vector<ProgramSpec> specs;
  for (auto list : {GBufferPass::programSpecs(), DepthHierarchyPass::programSpecs(), SaoPass::programSpecs(),
                    BilateralBlurPass::programSpecs(), AoUpsamplePass::programSpecs(), LightingPass::programSpecs(),
                    DebugViewPass::programSpecs()})
    specs.insert(specs.end(), list.begin(), list.end());
  return specs;
}

void Renderer::setScene(const Scene& scene) {
  GpuScene::Options options;
  options.allowUint32Indices = options_.allowUint32Indices;
  scene_ = GpuScene(scene, caps_, options);
  checkErrors(Pass::Count);
}

void Renderer::checkErrors(Pass after) const {
  if (!options_.checkGlErrors) return;
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", error);
  throw GlError(std::string("GL error ") + code + " " +
                (after == Pass::Count ? std::string("outside the passes (pending before the frame or from the scene "
                                                    "upload)")
                                      : std::string("after pass ") + passName(after)));
}

void Renderer::render(const Camera& camera, const AoSettings& settings, View view, const OutputTarget& output,
                      PassTimer* timer) {
  checkErrors(Pass::Count);  // an error the application left pending is reported as such, not blamed on a pass
  settings.validate();
  const int limit = caps_.maxRenderSize();
  if (output.width < 1 || output.height < 1 || output.width > limit || output.height > limit)
    throw InputError("output size " + std::to_string(output.width) + "x" + std::to_string(output.height) +
                     " is outside what this context can render (1 .. " + std::to_string(limit) + " per side)");
  const FrameCamera frame = FrameCamera::from(camera, output.width, output.height);
  const bool needAo = settings.enabled || view == View::Ao || view == View::AoRaw;

  gbuffer_.resize(output.width, output.height);
  {
    ScopedPass scoped(timer, Pass::GBuffer);
    gbuffer_.render(scene_, frame);
  }
  checkErrors(Pass::GBuffer);

  finalAo_ = &white_;
  if (needAo) {
    // Half resolution: AO at floor(size / 2), AO pixel p standing for G-buffer pixel 2p.
    const int aoScale = settings.halfResolution ? 2 : 1;
    const glm::ivec2 aoSize =
        SaoKernel::hierarchyLevelSize(glm::ivec2(output.width, output.height), settings.halfResolution ? 1 : 0);
    const gl::Texture2D& gbuffer = gbuffer_.target().color();
    if (settings.depthHierarchy) {
      hierarchy_.resize(output.width, output.height);
      {
        ScopedPass scoped(timer, Pass::Hierarchy);
        hierarchy_.render(gbuffer);
      }
      checkErrors(Pass::Hierarchy);
    }
    sao_.resize(aoSize.x, aoSize.y);
    {
      ScopedPass scoped(timer, Pass::Sao);
      sao_.render(gbuffer, settings.depthHierarchy ? &hierarchy_ : nullptr, frame, settings, aoScale);
    }
    checkErrors(Pass::Sao);
    finalAo_ = &sao_.target().color();
    if (settings.blur && settings.blurRadius > 0) {
      blur_.resize(aoSize.x, aoSize.y);
      for (Pass pass : {Pass::BlurHorizontal, Pass::BlurVertical}) {
        {
          ScopedPass scoped(timer, pass);
          blur_.render(pass == Pass::BlurHorizontal ? BilateralBlurPass::Direction::Horizontal
                                                    : BilateralBlurPass::Direction::Vertical,
                       sao_.target().color(), gbuffer, frame, settings, aoScale);
        }
        checkErrors(pass);
      }
      finalAo_ = &blur_.output().color();
    }
    if (aoScale == 2) {
      upsample_.resize(output.width, output.height);
      {
        ScopedPass scoped(timer, Pass::Upsample);
        upsample_.render(*finalAo_, gbuffer, frame, settings);
      }
      checkErrors(Pass::Upsample);
      finalAo_ = &upsample_.target().color();
    }
  }

  {
    ScopedPass scoped(timer, Pass::Composite);
    glBindFramebuffer(GL_FRAMEBUFFER, output.framebuffer);
    glViewport(0, 0, output.width, output.height);
    switch (view) {
      case View::Final:
        lighting_.render(scene_, frame, light_, settings.enabled ? *finalAo_ : white_, output.aoSplitX);
        break;
      case View::Ao: debugView_.render(DebugViewPass::Mode::Ao, *finalAo_, frame); break;
      case View::AoRaw: debugView_.render(DebugViewPass::Mode::Ao, sao_.target().color(), frame); break;
      case View::Normals: debugView_.render(DebugViewPass::Mode::Normals, gbuffer_.target().color(), frame); break;
      case View::Depth: debugView_.render(DebugViewPass::Mode::Depth, gbuffer_.target().color(), frame); break;
      case View::Mask: debugView_.render(DebugViewPass::Mode::Mask, gbuffer_.target().color(), frame); break;
    }
  }
  checkErrors(Pass::Composite);
}

}  // namespace obscura
