#include "frame/TileMaxPasses.h"

#include "frame/FramePlan.h"
#include "frame/PassContext.h"
#include "gl/PipelineState.h"

namespace obscura {

TileMaxPasses::RunProgram::RunProgram(gl::Program built)
    : program(std::move(built)),
      source(program.uniform("u_source")),
      sourceSize(program.uniform("u_sourceSize")),
      step(program.uniform("u_step")),
      tile(program.uniform("u_tile")),
      targetSize(program.uniform("u_targetSize")),
      frameSize(program.optionalUniform("u_frameSize")) {}

TileMaxPasses::NeighborProgram::NeighborProgram(gl::Program built)
    : program(std::move(built)),
      tiles(program.uniform("u_tiles")),
      tilesSize(program.uniform("u_tilesSize")),
      frameSize(program.optionalUniform("u_frameSize")) {}

TileMaxPasses::TileMaxPasses(const EffectResources& resources, const ProgramSpec& columns, const ProgramSpec& tiles,
                             const ProgramSpec& neighbors)
    : resources_(resources),
      columns_(resources.build(columns)),
      tiles_(resources.build(tiles)),
      neighbors_(resources.build(neighbors)) {}

void TileMaxPasses::plan(FramePlanner& planner, const std::string& prefix, const std::string& source, int k,
                         glm::vec2 frameSize, std::function<void()> setColumnsUniforms) const {
  using Write = PassDecl::Write;
  const std::string columnsTarget = prefix + "-tile-columns", tilesTarget = prefix + "-tiles",
                    neighborsTarget = prefix + "-neighbors";
  const float tile = static_cast<float>(k);
  auto runPass = [this, tile, frameSize](const RunProgram& p, const std::string& from, const std::string& to,
                                         glm::vec2 step, std::function<void()> setOwn) {
    return [this, &p, from, to, step, tile, frameSize, setOwn](PassContext& context) {
      context.bindForWriting(to);
      p.program.use();
      context.texture(from).bind(0);
      gl::Program::set(p.source, 0);
      gl::Program::set(p.sourceSize, glm::vec2(context.size(from)));
      gl::Program::set(p.step, step);
      gl::Program::set(p.tile, tile);
      gl::Program::set(p.targetSize, glm::vec2(context.size(to)));
      if (p.frameSize >= 0) gl::Program::set(p.frameSize, frameSize);
      if (setOwn) setOwn();
      resources_.triangle.draw();
      gl::restoreBaselineState();
    };
  };

  PassDecl columns;
  columns.name = prefix + "-tiles-h";
  columns.reads = {source};
  columns.writes = {{columnsTarget, TargetSize::tileColumns(k), Write::Depth::None, ""}};
  columns.run = runPass(columns_, source, columnsTarget, {1.0f, 0.0f}, std::move(setColumnsUniforms));
  planner.add(std::move(columns));

  PassDecl tiles;
  tiles.name = prefix + "-tiles";
  tiles.reads = {columnsTarget};
  tiles.writes = {{tilesTarget, TargetSize::tiles(k), Write::Depth::None, ""}};
  tiles.run = runPass(tiles_, columnsTarget, tilesTarget, {0.0f, 1.0f}, nullptr);
  planner.add(std::move(tiles));

  PassDecl neighbors;
  neighbors.name = prefix + "-neighbors";
  neighbors.reads = {tilesTarget};
  neighbors.writes = {{neighborsTarget, TargetSize::tiles(k), Write::Depth::None, ""}};
  neighbors.run = [this, tilesTarget, neighborsTarget, frameSize](PassContext& context) {
    context.bindForWriting(neighborsTarget);
    neighbors_.program.use();
    context.texture(tilesTarget).bind(0);
    gl::Program::set(neighbors_.tiles, 0);
    gl::Program::set(neighbors_.tilesSize, glm::vec2(context.size(tilesTarget)));
    if (neighbors_.frameSize >= 0) gl::Program::set(neighbors_.frameSize, frameSize);
    resources_.triangle.draw();
    gl::restoreBaselineState();
  };
  planner.add(std::move(neighbors));
}

}  // namespace obscura
