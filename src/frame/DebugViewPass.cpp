#include "frame/DebugViewPass.h"

#include "frame/FramePlan.h"
#include "frame/PassContext.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

constexpr ViewDecoding kDecodings[] = {ViewDecoding::Grey,     ViewDecoding::Normals, ViewDecoding::Depth,
                                       ViewDecoding::Mask,     ViewDecoding::HdrColor, ViewDecoding::Color,
                                       ViewDecoding::Count,    ViewDecoding::Velocity};
constexpr const char* kDecodingNames[] = {"grey",  "normals", "depth", "mask",
                                          "hdr-color", "color", "count", "velocity"};

}  // namespace

ProgramSpec DebugViewPass::programSpec(ViewDecoding decoding) {
  const int index = static_cast<int>(decoding);
  return ProgramSpec{std::string("view[") + kDecodingNames[index] + "]",
                     "lib/fullscreen.vert",
                     "frame/debug_view.frag",
                     {{"VIEW_DECODING", std::to_string(index)}, {"FAR_RAY", "0"}},
                     {}};
}

std::vector<ProgramSpec> DebugViewPass::programSpecs() {
  std::vector<ProgramSpec> specs;
  for (ViewDecoding decoding : kDecodings) specs.push_back(programSpec(decoding));
  return specs;
}

const DebugViewPass::Variant& DebugViewPass::variant(ViewDecoding decoding) {
  auto it = variants_.find(decoding);
  if (it == variants_.end()) it = variants_.emplace(decoding, Variant(resources_.build(programSpec(decoding)))).first;
  return it->second;
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
    context.texture(target).bind(0);
    gl::Program::set(v.source, 0);
    resources_.triangle.draw();
    gl::restoreBaselineState();
  };
  return pass;
}

}  // namespace obscura
