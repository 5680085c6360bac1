#pragma once
// Temporal antialiasing (shaders_es2/taa/taa.frag, taa/taa.glsl): the projection is jittered by a Halton(2, 3)
// sub-pixel offset every frame (EffectInfo::jitters; Renderer::beginFrame, 16 phases), and each frame's HDR colour
// ("scene-color") is blended into a history that follows the scene through the motion vectors ("velocity"):
//   - reprojection through the velocity of the nearest depth in the 3x3 neighbourhood (Karis 2014, "High quality
//     temporal supersampling", SIGGRAPH course);
//   - disocclusion: the previous frame's G-buffer depth, kept in a second history target ("taa-depth"), must be the
//     depth the surface had then, or the history there is dropped;
//   - rectification: the history is clipped in YCoCg towards the neighbourhood's mean onto the box mean +- gamma
//     sigma (Salvi 2016's variance clipping, clipped along the line to the mean as in Pedersen 2016, INSIDE);
//   - the history resampled with Catmull-Rom from 4x4 texels, decoded one by one (one texel on a still view);
//   - averaging in Karis' reversible tone-mapped space c / (1 + luma);
//   - optional sharpening of what leaves the pass (never of the history).
// It runs after the lighting, on HDR colour, so FXAA (on display colour, after tone mapping) may run after it.
//
// Which effects see the jitter: the G-buffer, the AO (which reads the jittered G-buffer; its per-pixel noise is
// already there, a sub-pixel shift of its taps is within it) and the lighting are jittered; the velocity is
// unjittered (both projections without it); every effect after TAA reads the resolved image, whose jitter the
// history has averaged out.
//
// History encoding (measured, tests/test_taa.cpp "HistoryEncodingIsChosenByMeasurement"): RGB9E5 of lib/hdr.glsl,
// the lighting's own encoding. A grey-to-white ramp of 1024 pixels, fed through 16 frames of feedback 0.9 with
// inputs alternating +-10 % (as jittered edge samples do), read in 8-bit sRGB against the same feedback in floats:
//   rgb9e5 (chosen)                    0.73 LSB largest, 0.26 mean, no inversions (bit-exact CPU/GPU encoder)
//   Karis x / (1 + luma), 8-bit        6.4 LSB largest: linear 8 bits band near black
//   Karis, sqrt, 10 bits (A: 2 x 3)    0.69 LSB largest, 0.30 mean: no better, and inexact on the GPU (sqrt, division)
// Precision: 9 mantissa bits relative from 2^-15 up, so a history the 10 % update can no longer move (the stall of
// every quantised feedback) is under a display level at any brightness.
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"

namespace obscura {

struct TaaSettings : ParameterAccess<TaaSettings> {
  bool enabled = false;
  // The history's weight: 0.9 averages about the last 10 frames (1 / (1 - f)), Karis 2014's and most engines'
  // figure; the first 16 frames after a drop average evenly (weight n / (n + 1) for the n-th), so a still image is
  // the exact mean of the 16 jitter phases (taaFeedback).
  float feedback = 0.9f;
  float sharpen = 0.0f;  // unsharp mask of the output, 0 off .. 1 (the centre against its four neighbours' mean)

  static const std::vector<Parameter<TaaSettings>>& parameters();
  void validate() const { validateParameters("TAA"); }
};

// CPU mirror of taa/taa.glsl.
glm::vec3 taaToYCoCg(const glm::vec3& rgb);
glm::vec3 taaFromYCoCg(const glm::vec3& ycocg);
glm::vec3 taaToneWeight(const glm::vec3& ycocg);
glm::vec3 taaToneUnweight(const glm::vec3& weighted);
glm::vec3 taaClipTowardsMean(const glm::vec3& history, const glm::vec3& mean, const glm::vec3& extent);

// Variance clipping's gamma, the box's half-size in standard deviations. Salvi 2016 suggests 1 (tight: little
// ghosting, more flicker) .. 1.25. Measured by tests/test_taa.cpp (egl; edge MAE in levels, still room / camera
// pan; pendulum's uncovered band): 0.75: 5.04 / 8.23, 5.79; 1: 3.88 / 7.56, 5.70; 1.25: 3.49 / 7.27, 5.82; 1.5: 3.09 /
// 7.13, 5.81; 2: 2.95 / 6.98, 5.77. The band does not move (the depth test rejects the history there, not the
// clipping); the gain flattens beyond 1.5, and a looser box keeps more of a history whose colour changed at the same
// depth (shading, a texture), which these tests do not measure: 1.5.
constexpr float kTaaClipGamma = 1.5f;

// The jitter's phases (Renderer::beginFrame: Halton(2, 3) indices 1 .. 16).
constexpr int kTaaJitterPhases = 16;
// The history weight of the frame with `historyFrames` earlier frames in the history (0: none): a running mean
// over the first kTaaJitterPhases frames, `feedback` after.
float taaFeedback(float feedback, int historyFrames);

class TaaEffect : public Effect {
 public:
  using Settings = TaaSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit TaaEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;

 private:
  // Frames in this effect's own history (its targets are made on first use, so it may start after the Renderer's).
  int historyFrames_ = 0;
  std::uint64_t lastFrameIndex_ = ~std::uint64_t(0);
};

}  // namespace obscura
