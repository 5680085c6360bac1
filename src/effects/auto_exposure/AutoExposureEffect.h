#pragma once
// Auto exposure (eye adaptation), after the HDR deck's "tone mapping by the frame's average luminance, downscale to
// 1x1" and Reinhard et al. 2002's log-average: the scene colour's log2 luminance is metered, reduced to one value,
// adapted over time, and the tone mapping applies the exposure that puts it at mid grey (shaders_es2/auto_exposure/,
// CPU mirror encoding/ExposureMetering.h). Everything stays on the GPU, in RGBA8: no readback, no float texture.
//
//   exposure-meter      scene-color (full) -> exposure-meter (tiles of 8): per 8 x 8 pixels, the weighted mean of
//                       l = log2 luminance as a 16-bit code and the block's weight (metering: average 1, centre
//                       exp(-2 d^2))
//   exposure-reduce(-2) -> exposure-level-1, -2 (tiles of 128, 2048): 16 x 16 texels each, averaged by weight, until
//                       the grid fits in 16 x 16 (one reduction at 1280x720: 160x90 -> 10x6)
//   exposure-histogram  (percentile metering) one point per grid texel, scattered into its 0.25 EV bin of a 128 x 64
//                       target with additive blending (the saturation limit: ExposureMetering.h)
//   exposure-bins       -> 128 x 1 bins of 16-bit counts
//   exposure-adapt      the last grid (or the bins: the mean between two percentiles) and the history (1 x 1) ->
//                       exposure (1 x 1: RG the adapted log-average, BA the EV), also written to the history
// The adapted value moves towards the metered one by 1 - e^(-speed dt) a frame, dt the real frame interval
// (FrameOptions::frameInterval), faster towards light (speed-up) than towards dark (speed-down), as eyes and cameras
// adapt. The history is dropped with the frame's (scene change, resize, a lost context's new Renderer): the first
// frame after takes the metered value as it is.
//
// The tone mapping reads `exposure` when this effect is on and applies 2^EV in place of tonemap.exposure: EV =
// clamp(log2(0.18) - adapted, min-ev, max-ev) + compensation.
#include <vector>

#include "encoding/ExposureMetering.h"
#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"

namespace obscura {

struct AutoExposureSettings : ParameterAccess<AutoExposureSettings> {
  using Metering = ExposureMetering::Metering;
  bool enabled = false;
  float compensation = 0.0f;  // EV added to the metered exposure
  float minEv = -10.0f, maxEv = 10.0f;  // the range of the metered exposure (before the compensation)
  float speedUp = 3.0f;    // per second, towards a brighter scene: 95 % of the way in 1 s
  float speedDown = 1.0f;  // per second, towards a darker one: 95 % in 3 s
  Metering metering = Metering::Average;
  float percentileLow = 10.0f, percentileHigh = 90.0f;  // percentile metering: the samples averaged, in per cent

  static const std::vector<Parameter<AutoExposureSettings>>& parameters();
  void validate() const { validateParameters("auto exposure"); }
};

class AutoExposureEffect : public Effect {
 public:
  using Settings = AutoExposureSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit AutoExposureEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;

  // Whether percentile metering can run here (a vertex texture unit); without one the effect meters the average.
  static bool histogramAvailable(const gl::GlCaps& caps);

 private:
  // The percentile metering's scatter of the meter's texels into the histogram's bins (additive points).
  void histogram(const PassContext& context);
  // The adapted exposure, into the history and into the frame's `exposure` target.
  void adapt(const PassContext& context, const AutoExposureSettings& settings, bool percentile,
             const std::string& from);

  const EffectResources& resources_;
  gl::BufferHandle sampleIndices_;  // 0 .. kHistogramMaxSamples - 1: the histogram's points, made on first use
};

}  // namespace obscura
