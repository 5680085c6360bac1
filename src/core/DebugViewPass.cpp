#include "core/DebugViewPass.h"

#include "gl/PipelineState.h"

namespace obscura {
namespace {
ProgramSpec spec(DebugViewPass::Mode mode) {
  static const char* names[] = {"view[ao]", "view[normals]", "view[depth]", "view[mask]"};
  const int index = static_cast<int>(mode);
  return ProgramSpec{names[index], "fullscreen.vert", "debug_view.frag", {{"VIEW_MODE", std::to_string(index)}}, {}};
}
}  // namespace

std::vector<ProgramSpec> DebugViewPass::programSpecs() {
  return {spec(Mode::Ao), spec(Mode::Normals), spec(Mode::Depth), spec(Mode::Mask)};
}

void DebugViewPass::render(Mode mode, const gl::Texture2D& source, const FrameCamera& camera) {
  auto it = programs_.find(mode);
  if (it == programs_.end()) it = programs_.emplace(mode, spec(mode).build()).first;
  const gl::Program& program = it->second;
  program.use();
  setReconstructionUniforms(program, camera.reconstruction);
  source.bind(0);
  program.set("u_source", 0);
  triangle_.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
