#pragma once
// FXAA 3.11, quality path (Lottes 2011; shaders_es2/fxaa/fxaa.frag): the frame's antialiasing, last in the chain. It
// reads "display-color" (sRGB, luma in alpha; NEAREST, filtered by hand where FXAA reads between texels) and writes
// it again, straight into the output framebuffer when it is the frame's result.
//
// Why FXAA and not multisampling: WebGL 1 cannot resolve a multisampled buffer into a texture, and every frame reads
// the lit image again (the tone-mapping pass decodes its HDR encoding), so Obscura draws no geometry into the back
// buffer, where multisampling would act. Canvas and window are made without it (measured: docs/benchmarks.md).
//
// Where the target it writes has a stencil buffer (the desktop window and obscura-render's output have one),
// the pass runs in two draws, as SMAA does with its edge mask (Jimenez et al. 2012): a classifying draw writes the
// pixels below FXAA's contrast threshold as they are and leaves stencil 1 on the edge pixels, then the full FXAA
// draws only where the stencil is 1. The image is the same as one full draw's (tests/test_pipeline.cpp). What it
// saves is the part of FXAA after its early exit, which a GPU skips where a whole wavefront exits, but which CPU
// rasterisers pay for far more often (SwiftShader runs both sides of every branch, masked): llvmpipe's FXAA pass went
// from about 40 to 13 ms at 1280x720. On SwiftShader the page's frame was no faster (WebCanvas.cpp), so the canvas
// has no stencil and the pass there is one draw.
#include <functional>
#include <string>
#include <vector>

#include "frame/EffectEntry.h"
#include "frame/Resolution.h"

namespace obscura {

struct FxaaSettings : ParameterAccess<FxaaSettings> {
  bool enabled = true;
  QualityPreset preset = QualityPreset::Medium;
  int quality = 12;              // Lottes' FXAA_QUALITY__PRESET: 10 .. 15, 20 .. 29 or 39 (the search's steps)
  float subpix = 0.75f;          // Lottes' default: amount of subpixel aliasing removal
  float edgeThreshold = 0.166f;  // Lottes' default: minimum local contrast to process, relative to the max luma
  float edgeThresholdMin = 0.0833f;  // Lottes' default: skip darks below this absolute contrast

  static const std::vector<Parameter<FxaaSettings>>& parameters();
  // The frame's preset (RenderSettings::applyPreset): the settings of `fxaa.preset`, and FXAA off at low.
  void applyPreset(QualityPreset which);
  bool matchesPreset(QualityPreset which) const;
  // `fxaa.preset`: Lottes' steps and thresholds only.
  void applySettingsOf(QualityPreset which);
  bool settingsMatch(QualityPreset which) const;
  void validate() const { validateParameters("FXAA"); }
};

// The search's step lengths of one of Lottes' quality presets (FXAA_QUALITY__P0 ..), in pixels.
const std::vector<float>& fxaaSearchSteps(int quality);

// Below render scale 1 (frame/Resolution.h) FXAA's pass also upscales the frame into the output, in place of the
// resolution effect's `upscale` pass (PassDecl::Alternative::absorbing): each output pixel runs FXAA on the source
// texel under it and reads the upscale (lib/upscale.glsl) at its own point moved by FXAA's resample offset, so
// where FXAA leaves a texel alone the pixel is exactly the upscale's, and where it antialiases an edge the upscale
// reads from across the edge as FXAA's resample would (shaders_es2/fxaa/fxaa.frag, UPSCALE).
class FxaaEffect : public Effect {
 public:
  using Settings = FxaaSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit FxaaEffect(const EffectResources& resources) : resources_(resources) {}
  void plan(FramePlanner& planner) override;

 private:
  // The pass's draws into `output`: `passThrough` around the scene's bounds on screen, then within them the
  // classifying one first where the target written has a stencil buffer, and `full`; `upscales`: the variants that
  // also upscale into the output (frame/Resolution.h).
  std::function<void(PassContext&)> run(ProgramSpec full, ProgramSpec classify, ProgramSpec passThrough,
                                        std::string output, bool upscales) const;

  const EffectResources& resources_;
};

}  // namespace obscura
