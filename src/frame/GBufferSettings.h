#pragma once
// The G-buffer's settings (gbuffer.NAME): the row of the G-buffer effect (effects/gbuffer/GBufferEffect.h), declared
// here with the frame because its readers, effects that may not include another effect, read them too.
#include <vector>

#include "frame/Parameters.h"

namespace obscura {

// Where the G-buffer's readers take the surface normal from for geometry (the AO estimator's hemisphere):
enum class GBufferNormals {
  Stored,         // the normal the G-buffer pass wrote (interpolated vertex normals)
  Reconstructed,  // from the depths of the pixel's neighbours (lib/normal_from_depth.glsl), the stored one where a
                  // feature one pixel wide leaves no side to follow; shading keeps the stored (or geometry's) normals
};

struct GBufferSettings : ParameterAccess<GBufferSettings> {
  GBufferNormals normals = GBufferNormals::Stored;

  static const std::vector<Parameter<GBufferSettings>>& parameters();
  void validate() const { validateParameters("G-buffer"); }
};

}  // namespace obscura
