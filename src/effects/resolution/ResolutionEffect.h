#pragma once
// The frame's resolution (frame/Resolution.h: resolution.scale, .upscale, .sharpness, dynamic resolution and the
// page's pixel ratio), as a row of the effect table: where the frame renders below the output's size, its one pass,
// `upscale`, draws the finished image (`display-color`, at the scaled size) into the output at the output's size
// (shaders_es2/resolution/upscale.frag over lib/upscale.glsl: bilinear, or the EASU-like edge upscale with its
// optional RCAS-like sharpening). Where FXAA runs, FXAA's pass does the upscale too (FxaaEffect.cpp: it absorbs this
// pass, PassDecl::Alternative), so the frame passes over the output once either way. At scale 1 it plans nothing.
//
// The rest of the frame needs no change for a scale: the Renderer sizes the frame context and the pooled targets to
// the render size (renderer/Renderer.cpp), and every effect sizes its work by them. What is measured against
// rendering at full size: tests/test_upscale.cpp and docs/resolution.md.
#include <vector>

#include "frame/EffectEntry.h"
#include "frame/Resolution.h"

namespace obscura {

class ResolutionEffect : public Effect {
 public:
  using Settings = ResolutionSettings;
  static constexpr bool kHasSwitch = false;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit ResolutionEffect(const EffectResources&) {}
  void plan(FramePlanner& planner) override;
};

}  // namespace obscura
