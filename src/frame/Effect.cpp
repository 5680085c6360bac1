#include "frame/Effect.h"

#include <algorithm>

#include <glm/common.hpp>

namespace obscura {

glm::ivec2 TargetSize::of(glm::ivec2 frame) const {
  switch (kind) {
    case Kind::Full: return frame;
    case Kind::Half: return glm::max(frame / 2, glm::ivec2(1));
    case Kind::Quarter: return glm::max(frame / 4, glm::ivec2(1));
    case Kind::Tiles: return (frame + glm::ivec2(tile - 1)) / std::max(tile, 1);
    case Kind::TileColumns: return {(frame.x + tile - 1) / std::max(tile, 1), frame.y};
    case Kind::Scaled:
      return glm::max(glm::ivec2((frame.x >> shiftX) * timesX + plusX, (frame.y >> shiftY) + plusY), glm::ivec2(1));
    case Kind::Fixed: return {tile, height};
  }
  return frame;
}

std::string TargetSize::name() const {
  switch (kind) {
    case Kind::Full: return "full";
    case Kind::Half: return "half";
    case Kind::Quarter: return "quarter";
    case Kind::Tiles: return "tiles of " + std::to_string(tile);
    case Kind::TileColumns: return "tile columns of " + std::to_string(tile);
    case Kind::Scaled: {
      const std::string across = (timesX == 1 ? "" : std::to_string(timesX) + " x ") + "1/" +
                                 std::to_string(1 << shiftX) + (plusX ? " + " + std::to_string(plusX) : "");
      const std::string down = "1/" + std::to_string(1 << shiftY) + (plusY ? " + " + std::to_string(plusY) : "");
      return (timesX == 1 && !plusX ? across : "(" + across + ")") + " x " + (plusY ? "(" + down + ")" : down);
    }
    case Kind::Fixed: return std::to_string(tile) + "x" + std::to_string(height);
  }
  return "?";
}

}  // namespace obscura
