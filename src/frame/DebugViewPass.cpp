#include "frame/DebugViewPass.h"

#include "frame/FramePlan.h"
#include "frame/PassContext.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

constexpr ViewDecoding kDecodings[] = {ViewDecoding::Grey,     ViewDecoding::Normals, ViewDecoding::Depth,
                                       ViewDecoding::Mask,     ViewDecoding::HdrColor, ViewDecoding::Color,
                                       ViewDecoding::Count,    ViewDecoding::Velocity, ViewDecoding::NormalsFromDepth};
constexpr const char* kDecodingNames[] = {"grey",  "normals", "depth",    "mask",
                                          "hdr-color", "color", "count", "velocity", "normals-from-depth"};

}  // namespace

ProgramSpec DebugViewPass::programSpec(ViewDecoding decoding) {
  const int index = static_cast<int>(decoding);
  // Only the normals from depth reconstruct view positions.
  const bool farRay = decoding == ViewDecoding::NormalsFromDepth;
  return ProgramSpec{std::string("view[") + kDecodingNames[index] + "]",
                     "lib/fullscreen.vert",
                     "frame/debug_view.frag",
                     {{"VIEW_DECODING", std::to_string(index)}, {"FAR_RAY", farRay ? "1" : "0"}},
                     {}};
}

std::vector<ProgramSpec> DebugViewPass::programSpecs() {
  std::vector<ProgramSpec> specs;
  for (ViewDecoding decoding : kDecodings) specs.push_back(programSpec(decoding));
  return specs;
}

const DebugViewPass::Variant& DebugViewPass::variant(ViewDecoding decoding) {
  auto it = variants_.find(decoding);
  if (it == variants_.end())
    it = variants_.emplace(decoding, Variant(resources_.build(programSpec(decoding)), decoding)).first;
  return it->second;
}

DebugViewPass::Variant::Variant(gl::Program built, ViewDecoding decoding)
    : program(std::move(built)), source(program.uniform("u_source")) {
  if (decoding != ViewDecoding::NormalsFromDepth) return;
  reconstruction = ReconstructionUniforms(program);
  sourceSize = program.uniform("u_sourceSize");
}

PassDecl DebugViewPass::pass(const std::string& name, const std::string& target, ViewDecoding decoding) {
  PassDecl pass;
  pass.name = name;
  pass.reads = {target};
  pass.writes = {{kOutputTarget, TargetSize::full(), PassDecl::Write::Depth::None, ""}};
  pass.run = [this, target, decoding](PassContext& context) {
    const Variant& v = variant(decoding);
    context.bindForWriting(kOutputTarget);
    v.program.use();
    const gl::Texture2D& source = context.texture(target);
    source.bind(0);
    gl::Program::set(v.source, 0);
    if (v.sourceSize >= 0) {
      v.reconstruction.set(context.camera().reconstruction);
      gl::Program::set(v.sourceSize, glm::vec2(source.width(), source.height()));
    }
    resources_.triangle.draw();
    gl::restoreBaselineState();
  };
  return pass;
}

}  // namespace obscura
