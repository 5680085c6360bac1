#include "frame/DebugViewPass.h"

#include "frame/FramePlan.h"
#include "frame/FullscreenPass.h"
#include "frame/PassContext.h"

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

PassDecl DebugViewPass::pass(const std::string& name, const std::string& target, ViewDecoding decoding) {
  std::function<void(FullscreenDraw&, const PassContext&)> uniforms;
  if (decoding == ViewDecoding::NormalsFromDepth)
    uniforms = [target](FullscreenDraw& draw, const PassContext& context) {
      setReconstruction(draw.program(), context.camera().reconstruction);
      const gl::Texture2D& source = context.texture(target);
      draw.set("u_sourceSize", glm::vec2(source.width(), source.height()));
    };
  return fullscreenPass(name, programSpec(decoding), {{"u_source", target}}, {kOutputTarget}, std::move(uniforms));
}

}  // namespace obscura
