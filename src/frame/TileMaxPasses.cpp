#include "frame/TileMaxPasses.h"

#include "frame/FramePlan.h"
#include "frame/PassContext.h"

namespace obscura::TileMaxPasses {

void plan(FramePlanner& planner, const std::string& prefix, const std::string& source, int k,
          const ProgramSpec& columns, const ProgramSpec& tiles, const ProgramSpec& neighbors,
          std::function<void(FullscreenDraw&, const PassContext&)> columnsUniforms) {
  using Write = PassDecl::Write;
  const std::string columnsTarget = prefix + "-tile-columns", tilesTarget = prefix + "-tiles",
                    neighborsTarget = prefix + "-neighbors";
  const float tile = static_cast<float>(k);
  auto frameSize = [](FullscreenDraw& draw, const PassContext& context) {
    if (draw.program().has("u_frameSize"))
      draw.set("u_frameSize", glm::vec2(context.camera().width, context.camera().height));
  };
  auto run = [tile, frameSize](const std::string& from, const std::string& to, glm::vec2 step,
                               std::function<void(FullscreenDraw&, const PassContext&)> own) {
    return [tile, frameSize, from, to, step, own](FullscreenDraw& draw, const PassContext& context) {
      draw.set("u_sourceSize", glm::vec2(context.size(from)));
      draw.set("u_step", step);
      draw.set("u_tile", tile);
      draw.set("u_targetSize", glm::vec2(context.size(to)));
      frameSize(draw, context);
      if (own) own(draw, context);
    };
  };
  planner.add(fullscreenPass(prefix + "-tiles-h", columns, {{"u_source", source}},
                             {columnsTarget, TargetSize::tileColumns(k), Write::Depth::None, ""},
                             run(source, columnsTarget, {1.0f, 0.0f}, std::move(columnsUniforms))));
  planner.add(fullscreenPass(prefix + "-tiles", tiles, {{"u_source", columnsTarget}},
                             {tilesTarget, TargetSize::tiles(k), Write::Depth::None, ""},
                             run(columnsTarget, tilesTarget, {0.0f, 1.0f}, nullptr)));
  planner.add(fullscreenPass(prefix + "-neighbors", neighbors, {{"u_tiles", tilesTarget}},
                             {neighborsTarget, TargetSize::tiles(k), Write::Depth::None, ""},
                             [tilesTarget, frameSize](FullscreenDraw& draw, const PassContext& context) {
                               draw.set("u_tilesSize", glm::vec2(context.size(tilesTarget)));
                               frameSize(draw, context);
                             }));
}

}  // namespace obscura::TileMaxPasses
