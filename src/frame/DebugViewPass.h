#pragma once
// The frame's own last pass when it shows a debug view: one named target (frame/Effect.h, TargetInfo::views)
// decoded into the output (shaders_es2/frame/debug_view.frag). Also the present pass, which copies the frame's result
// into the output when its writer could not write there itself.
#include <vector>

#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"

namespace obscura {

class DebugViewPass {
 public:
  static ProgramSpec programSpec(ViewDecoding decoding);
  static std::vector<ProgramSpec> programSpecs();

  // A pass named `name` reading `target`, writing the output.
  static PassDecl pass(const std::string& name, const std::string& target, ViewDecoding decoding);
};

}  // namespace obscura
