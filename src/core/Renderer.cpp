#include "core/Renderer.h"

#include <cstdio>

#include "core/Error.h"

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
    case Pass::Sao: return "sao";
    case Pass::BlurHorizontal: return "blur-h";
    case Pass::BlurVertical: return "blur-v";
    case Pass::Composite: return "composite";
    case Pass::Count: break;
  }
  return "?";
}

Renderer::Renderer(const gl::GlCaps& caps, const RendererOptions& options)
    : caps_(requireUsable(caps)),
      options_(options),
      gbuffer_(caps.depth24),
      sao_(triangle_),
      blur_(triangle_),
      debugView_(triangle_),
      white_(1, 1, GL_NEAREST, std::vector<std::uint8_t>{255, 255, 255, 255}.data()) {}

std::vector<ProgramSpec> Renderer::allProgramSpecs() {
  std::vector<ProgramSpec> specs;
  for (auto list : {GBufferPass::programSpecs(), SaoPass::programSpecs(), BilateralBlurPass::programSpecs(),
                    LightingPass::programSpecs(), DebugViewPass::programSpecs()})
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
  throw GlError(std::string("GL error ") + code + " after " +
                (after == Pass::Count ? std::string("scene upload") : std::string("pass ") + passName(after)));
}

void Renderer::render(const Camera& camera, const AoSettings& settings, View view, const OutputTarget& output,
                      PassTimer* timer) {
  settings.validate();
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
    sao_.resize(output.width, output.height);
    {
      ScopedPass scoped(timer, Pass::Sao);
      sao_.render(gbuffer_.target().color(), frame, settings);
    }
    checkErrors(Pass::Sao);
    finalAo_ = &sao_.target().color();
    if (settings.blur && settings.blurRadius > 0) {
      blur_.resize(output.width, output.height);
      for (Pass pass : {Pass::BlurHorizontal, Pass::BlurVertical}) {
        {
          ScopedPass scoped(timer, pass);
          blur_.render(pass == Pass::BlurHorizontal ? BilateralBlurPass::Direction::Horizontal
                                                    : BilateralBlurPass::Direction::Vertical,
                       sao_.target().color(), gbuffer_.target().color(), frame, settings);
        }
        checkErrors(pass);
      }
      finalAo_ = &blur_.output().color();
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
