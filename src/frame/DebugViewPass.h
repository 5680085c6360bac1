#pragma once
// The frame's own last pass when it shows a debug view: one named target (frame/Effect.h, TargetInfo::views)
// decoded into the output (shaders_es2/frame/debug_view.frag). Also the present pass, which copies the frame's result
// into the output when its writer could not write there itself.
#include <map>
#include <vector>

#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"

namespace obscura {

class DebugViewPass {
 public:
  static ProgramSpec programSpec(ViewDecoding decoding);
  static std::vector<ProgramSpec> programSpecs();

  explicit DebugViewPass(const EffectResources& resources) : resources_(resources) {}
  // A pass named `name` reading `target`, writing the output.
  PassDecl pass(const std::string& name, const std::string& target, ViewDecoding decoding);

 private:
  struct Variant {
    Variant(gl::Program built, ViewDecoding decoding);
    gl::Program program;
    GLint source;
    ReconstructionUniforms reconstruction;  // the normals from depth only
    GLint sourceSize = -1;
  };
  const Variant& variant(ViewDecoding decoding);

  const EffectResources& resources_;
  std::map<ViewDecoding, Variant> variants_;
};

}  // namespace obscura
