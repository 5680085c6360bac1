#pragma once
// Motion blur: the reconstruction filter of McGuire, Hennessy, Bukowski and Osman, "A Reconstruction Filter for
// Plausible Motion Blur" (I3D 2012), as the SIGGRAPH 2012 talk "Scalable Motion Blur and Ambient Occlusion"
// presents it (../shared/papers/siggraph-2012-scalable-motion-blur-and-ao.txt), on the motion vectors of
// effects/velocity/VelocityEffect.h. Camera and object motion (node animation, skinning, morph targets) blur alike: the
// velocity target holds them all. Shader: shaders_es2/motion_blur/motion_blur.frag.
//
// The exposure is centred on the frame's time: [T - s/(2F), T + s/(2F)] for the shutter s (a fraction of the frame
// interval 1/F). The velocity target holds a pixel's motion over one frame interval (its previous frame 1/F earlier),
// so the blur's half-vector is V = s/2 times it, in pixels, clamped to the largest blur radius K. K is
// `max-radius` pixels at 720 rows, scaled with the frame's height, so the blur covers the same part of the picture at
// any resolution (the paper's K = 20 at 1280x720).
//
// Passes (all RGBA8, velocities in the velocity target's 16-bit packing, encoding/VelocityPacking.h):
//   motion-tiles-h    velocity -> motion-tile-columns   the largest V of each K pixels of a row
//   motion-tiles      motion-tile-columns -> motion-tiles   ... of each K x K tile (TileMax, separable)
//   motion-neighbors  motion-tiles -> motion-neighbors  the largest V of the 3 x 3 tiles around (NeighborMax)
//   motion-blur       display-color, velocity, gbuffer, motion-neighbors -> display-color: S samples along the
//                     neighbourhood's V, jittered per pixel, each classified by a soft depth comparison and the
//                     cylinder tests (in front and reaching X, or behind and uncovered by X's own blur) and weighted
//                     as the 1/S of the exposure it stands for; a pixel whose neighbourhood moves less than half a
//                     pixel is copied unchanged. The paper's cone weights and its 1/|V[X]| centre weight were
//                     measured first and left the inside of a moving edge too sharp (docs/temporal-effects.md).
//
// It blurs the display colour (after the tone curve, before FXAA): the space the brute-force reference
// (renderer/AccumulationReference.h) averages and a viewer sees, and cheap to read (no HDR decode per tap). A camera
// integrates light before its tone curve, so a bright highlight's streak is a little dimmer here than a film's
// (docs/temporal-effects.md).
#include <vector>

#include "frame/EffectEntry.h"
#include "frame/TileMaxPasses.h"

namespace obscura {

struct MotionBlurSettings : ParameterAccess<MotionBlurSettings> {
  bool enabled = false;
  float shutter = 0.5f;    // s: the fraction of the frame interval the shutter is open (180 degrees)
  int samples = 15;        // S: taps per pixel along the neighbourhood's motion (the paper's 15)
  float maxRadius = 20.0f; // K at 720 rows, pixels (the paper's 20 at 1280x720)

  static const std::vector<Parameter<MotionBlurSettings>>& parameters();
  void validate() const { validateParameters("motion blur"); }
  // K for a frame `height` pixels tall: maxRadius * height / 720, at least 1, at most kMaxTile.
  int tileSize(int height) const;
};

class MotionBlurEffect : public Effect {
 public:
  using Settings = MotionBlurSettings;
  static constexpr bool kHasSwitch = true;
  static constexpr int kMaxTile = 128;  // the tile passes' loop bound (MAX_TILE)
  static constexpr int kMinSamples = 2, kMaxSamples = 32;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit MotionBlurEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;
};

}  // namespace obscura
