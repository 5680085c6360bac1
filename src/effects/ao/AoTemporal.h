#pragma once
// Temporal AO (ao.temporal; shaders_es2/ao/ao_temporal.frag, run by AoEffect's "ao-temporal" pass): the arithmetic of
// the pass in plain C++, which tests hold the shader to, and the per-frame offsets of the estimators' taps.
//
//   frame offsets   frame f turns every estimator's taps by (halton(k, 2)) of a turn (GTAO: of its 1/16 Bayer step)
//                   and shifts their distance jitter by halton(k, 3), k = f mod 8 + 1: 8 frames sample 8 rotations
//                   and 8 distances, each set stratified (the radical inverses fill the gaps evenly).
//   rejection       the history is kept where the point Q it saw, moved into this frame's view space, lies within
//                   `tolerance` of this pixel's tangent plane: |n . (Q - C)| <= tolerance.
//   accumulation    A = H' + (a - H') / m, m = min(n + 1, N') (n the history's frames, 0 where rejected), stored as
//                   the A byte; where something nearby moves (rectifies), H' = clamp(H, low, high) (the 3x3 range
//                   of this frame's AO) and N' = maxFramesAt(motion, N); elsewhere H' = H and N' = N.
//   quantisation    floor(255 A + u), u = fract(ign(pixel) + d_f) in [0, 1): stochastic rounding, unbiased.
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace obscura::AoTemporal {

// The period of the per-frame offsets (and the default of ao.temporal-frames).
constexpr int kSequenceLength = 8;

// The taps' rotation (x, a fraction of a turn) and distance jitter (y) of frame `frameIndex`.
glm::vec2 frameOffset(std::uint64_t frameIndex);
// The dither offset of frame `frameIndex` (halton(k, 5)): the stochastic rounding moves every frame.
float ditherOffset(std::uint64_t frameIndex);

// Whether the history's point Q (this frame's view space) belongs to the surface at C with normal n.
bool keepsHistory(const glm::vec3& normal, const glm::vec3& centre, const glm::vec3& historyPoint, float tolerance);

// Rectification (where something within the AO radius moves relative to the pixel by more than
// kRelativeMotionPixels a frame): the mean's memory, held to a lag of about kLagPixels.
constexpr float kRelativeMotionPixels = 0.5f;
constexpr float kLagPixels = 2.0f;
bool rectifies(float relativeMotionPixels);
// N where nothing nearby moves; else clamp(floor(2 kLagPixels / motion), 1, N).
int maxFramesAt(float relativeMotionPixels, int maxFrames);

struct Accumulated {
  float ao;    // before quantisation
  int frames;  // m: frames in the mean, 1 .. maxFrames
};
// One step of the running mean. `historyFrames` 0: no history (rejected, or the first frame).
Accumulated accumulate(float history, int historyFrames, float current, float low, float high, int maxFrames);

// The stored byte of `ao` with the dither value u in [0, 1).
std::uint8_t quantise(float ao, float dither);

}  // namespace obscura::AoTemporal
