#include "frame/DebugViewPass.h"

#include "frame/FramePlan.h"
#include "frame/FullscreenPass.h"

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

PassDecl DebugViewPass::pass(const std::string& name, const std::string& target, ViewDecoding decoding) {
  return fullscreenPass(name, programSpec(decoding), {{"u_source", target}}, {kOutputTarget});
}

}  // namespace obscura
