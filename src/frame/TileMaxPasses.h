#pragma once
// The tile passes of McGuire, Hennessy, Bukowski and Osman 2012 (sec. 3: TileMax over K x K tiles, taken as two
// separable runs of K, then NeighborMax over the 3 x 3 tiles around), as motion blur (the largest velocity) and depth
// of field (the near field's largest circle of confusion) both run them. What "largest" means, and how the first pass
// reads its source, is each effect's shader (motion_blur.frag passes 1-3, dof.frag passes 3-5, their runs addressed
// by lib/tile_run.glsl); the three passes, their targets and their shared uniforms live here.
//
//   <prefix>-tiles-h    source -> <prefix>-tile-columns   each run of K pixels of a row
//   <prefix>-tiles      <prefix>-tile-columns -> <prefix>-tiles   each run of K tile columns: K x K
//   <prefix>-neighbors  <prefix>-tiles -> <prefix>-neighbors   the 3 x 3 tiles around each tile
#include <functional>
#include <string>

#include "frame/FullscreenPass.h"
#include "gl/ShaderLibrary.h"

namespace obscura {

class FramePlanner;

namespace TileMaxPasses {

// Adds the three passes for tiles of K pixels with the three programs (the row runs, the column runs, the 3 x 3
// neighbourhood). Programs that have u_frameSize get the frame's size; `columnsUniforms` sets the first pass's own
// uniforms each frame.
void plan(FramePlanner& planner, const std::string& prefix, const std::string& source, int k,
          const ProgramSpec& columns, const ProgramSpec& tiles, const ProgramSpec& neighbors,
          std::function<void(FullscreenDraw&, const PassContext&)> columnsUniforms);

}  // namespace TileMaxPasses
}  // namespace obscura
