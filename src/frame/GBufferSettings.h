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
  // Level of detail (scene/MeshDetail.h): the largest error, in pixels of the frame, of the simplified meshes every
  // geometry pass draws; 0 draws each mesh in full. The presets (docs/benchmarks.md, "Levels of detail"): medium, the
  // default, a third of a pixel (kMediumPresetLod), where the AO against the ray-traced reference is still the full
  // meshes' (MAE +0.0001 over the 72 tuning cases; at half a pixel +0.0008, the thin features' edges moving) and
  // 2CylinderEngine draws 55 % of its triangles at 640x360; low half a pixel (kLowPresetLod); high and ultra full
  // detail.
  float lod = kMediumPresetLod;
  QualityPreset preset = QualityPreset::Medium;  // the frame preset `lod` came from (applyPreset)

  static const std::vector<Parameter<GBufferSettings>>& parameters();
  static constexpr float kLowPresetLod = 0.5f;
  static constexpr float kMediumPresetLod = 0.35f;
  void applyPreset(QualityPreset which);
  bool matchesPreset(QualityPreset which) const;
  void validate() const { validateParameters("G-buffer"); }
};

}  // namespace obscura
