#pragma once
// Dynamic resolution (resolution.dynamic, frame/Resolution.h): the render scale a viewer draws its next frame at,
// chosen from the frame times it measured, so that frames take about resolution.target-ms.
//
// The scale moves on a ladder: s_k = max-scale x 2^(-k / 8), down to min-scale (each step about 9 % of a side, 16 %
// of the pixels). Measurements name the scale they were taken at, and only those of the current step count: GPU
// timer results come back a few frames late, and a frame measured before a change says nothing about the scale after
// it. The first kSettleFrames of a step are not used either (a change reallocates the frame's targets, which costs
// once). Then, with c the running mean of the step's frame times (weight kSmoothing per new frame) and the cost
// taken as proportional to the pixels, c (s' / s)^2 at another scale s':
//   - down, once kMeanFrames frames are in the mean (at once where one frame is kOverload times the target) and c is
//     above the target: to the largest scale predicted within kDownHeadroom of it. The step left is marked too dear;
//   - up, after kUpFrames frames at the step: to the largest scale predicted within kUpHeadroom of the target, but
//     not to a step marked too dear within the last kRetryFrames frames.
// It starts at the smallest scale: the first frame is the cheapest one (a page is shown sooner), and the scale climbs
// from there as soon as frames show room; refining() tells a front end that draws only on change to draw on while it
// climbs, so a still view on a fast GPU reaches the largest scale within a few dozen frames.
// The two headrooms are the hysteresis: a step up costs 1.19 times as much, so a cost anywhere in
// (kUpHeadroom / 1.19, 1] x target holds its step, and noise cannot push the scale both ways. A step marked too dear is
// tried again only after kRetryFrames, so where the best scale sits right at the target the scale changes by one
// step at most once in that many frames (tests/test_dynamic_resolution.cpp: simulated cost functions with noise and
// lag settle within 40 frames and then stay within one step). Cost that grows more slowly than the pixels (a fixed
// part) makes going up look dearer than it is, which errs towards staying.
#include <cstdint>

namespace obscura {

class DynamicResolution {
 public:
  DynamicResolution() { step_ = lastStep_ = ladderEnd(); }
  static constexpr int kStepsPerHalving = 8;
  static constexpr int kSettleFrames = 2;
  static constexpr int kMeanFrames = 4;
  static constexpr int kUpFrames = 12;
  static constexpr int kRetryFrames = 600;
  static constexpr double kSmoothing = 0.25;
  static constexpr double kOverload = 1.5;
  static constexpr double kDownHeadroom = 0.9;
  static constexpr double kUpHeadroom = 0.85;

  // The limits: the frame time to hold, and the smallest and largest scales (0 < min <= max <= 1). The first call
  // starts at the smallest; a change keeps the current scale where it is still within them (the nearest step of the
  // new ladder).
  void configure(double targetMs, float minScale, float maxScale);
  // One frame's time in ms, drawn at `scale` (any other scale than the current one is ignored).
  void measured(double frameMs, float scale);
  // The scale to draw the next frame at.
  float scale() const { return scaleOf(step_); }
  // Its step on the ladder (0: the largest scale), and the ladder's last.
  int step() const { return step_; }
  int lastStep() const { return lastStep_; }
  // The running mean of the current step's frame times (0 before its first counted frame), and the frames counted.
  double meanMs() const { return frames_ > kSettleFrames ? mean_ : 0.0; }
  int framesMeasured() const { return frames_; }
  // How many times the scale changed.
  std::uint64_t changes() const { return changes_; }
  // Whether more frames would let it climb: a step up is open (not the largest, not marked too dear) and the frames
  // measured at this step so far leave room for it, or are too few to tell. A front end that draws only on change
  // draws on while this holds.
  bool refining() const;
  // Forgets the measurements, keeping the scale: what a frame costs has changed (a new output size, a new scene), so
  // the next frames decide afresh (and refining() holds until they have).
  void forget();
  // Back to the smallest scale, forgetting the measurements.
  void reset();

 private:
  float scaleOf(int step) const;
  double predicted(int step) const;  // the current step's mean cost, carried to `step`
  int ladderEnd() const;  // the first step at or below the smallest scale
  void moveTo(int step);

  double targetMs_ = 33.3;
  float minScale_ = 0.5f, maxScale_ = 1.0f;
  int step_ = 0, lastStep_ = 0;
  bool configured_ = false;
  int frames_ = 0;     // frames measured at the current step, the settling ones included
  double mean_ = 0.0;  // their running mean, settling frames excluded
  int tooDear_ = -1;   // the last step left for costing more than the target (-1: none)
  int sinceTooDear_ = 0;  // frames measured since
  std::uint64_t changes_ = 0;
};

}  // namespace obscura
