#pragma once
// The tile passes of McGuire, Hennessy, Bukowski and Osman 2012 (sec. 3: TileMax over K x K tiles, taken as two
// separable runs of K, then NeighborMax over the 3 x 3 tiles around), as motion blur (the largest velocity) and depth
// of field (the near field's largest circle of confusion) both run them. What "largest" means, and how the first pass
// reads its source, is each effect's shader (motion_blur.frag passes 1-3, dof.frag passes 3-5, their runs addressed
// by lib/tile_run.glsl); the three passes, their targets and their uniforms are the same, and live here.
//
//   <prefix>-tiles-h    source -> <prefix>-tile-columns   each run of K pixels of a row
//   <prefix>-tiles      <prefix>-tile-columns -> <prefix>-tiles   each run of K tile columns: K x K
//   <prefix>-neighbors  <prefix>-tiles -> <prefix>-neighbors   the 3 x 3 tiles around each tile
#include <functional>
#include <string>

#include <glm/vec2.hpp>

#include "frame/EffectEntry.h"
#include "gl/ShaderLibrary.h"

namespace obscura {

class FramePlanner;

class TileMaxPasses {
 public:
  // The three programs: the row runs, the column runs, the 3 x 3 neighbourhood.
  TileMaxPasses(const EffectResources& resources, const ProgramSpec& columns, const ProgramSpec& tiles,
                const ProgramSpec& neighbors);

  // The first pass's program, for the uniforms only it has (the effect resolves them once).
  const gl::Program& columnsProgram() const { return columns_.program; }

  // Adds the three passes for tiles of K pixels. `frameSize` goes to the programs that have u_frameSize;
  // `setColumnsUniforms` sets the first pass's own uniforms while its program is in use.
  void plan(FramePlanner& planner, const std::string& prefix, const std::string& source, int k, glm::vec2 frameSize,
            std::function<void()> setColumnsUniforms) const;

 private:
  struct RunProgram {
    explicit RunProgram(gl::Program built);
    gl::Program program;
    GLint source, sourceSize, step, tile, targetSize, frameSize;
  };
  struct NeighborProgram {
    explicit NeighborProgram(gl::Program built);
    gl::Program program;
    GLint tiles, tilesSize, frameSize;
  };

  const EffectResources& resources_;
  RunProgram columns_, tiles_;
  NeighborProgram neighbors_;
};

}  // namespace obscura
