#pragma once
// Auto exposure's arithmetic: the luminance it meters, the RGBA8 encodings of its reduction and histogram targets,
// the metering weights, the trimmed histogram mean, and the adaptation over time. CPU mirror of
// shaders_es2/lib/exposure.glsl and shaders_es2/auto_exposure/*; tests hold the two together
// (tests/test_exposure_metering.cpp on the CPU, tests/test_auto_exposure.cpp through the GPU).
//
// The scene is metered as the log-average of its luminance (Reinhard et al. 2002, "Photographic Tone Reproduction for
// Digital Images", eq. 1: exp of the mean of log(delta + L)), here in base 2 over the pixels that are not black.
// Reinhard's delta keeps black from sending the mean to -infinity; it still drags the mean down by as many EV as the
// delta is small, and a black background or an unlit shadow says nothing about how the lit scene should be exposed.
// So a pixel darker than 2^-16 weighs nothing, and a frame with nothing lit keeps the exposure it had.
//
//   luminance       Y = 0.2126 R + 0.7152 G + 0.0722 B          (Rec. 709, linear)
//   metered value   l = clamp(log2(Y), -16, 16)                 (EV relative to luminance 1), for Y >= 2^-16
//   16-bit code     c = floor((x + 16) / 32 * 65535 + 0.5)     for every log2 value (step 0.00049 EV), in two bytes,
//                                                               high first, written as (b + 0.25) / 255 like every
//                                                               packed byte (encoding/LinearDepthPacking.h)
//
// Reduction texel (RG: the weighted mean of l over its block, as a 16-bit code; BA: the block's weight, the sum of its
// pixels' weights divided by the block's pixel count, as round(w * 65535)). Averaging texels by their weights is then
// exact whatever the block holds: partial blocks at the frame's right and top edges, and the centre weighting.
//
// Histogram (percentile metering): 128 bins of 0.25 EV over [-16, 16]. Each sample is one point drawn with additive
// blending into a 128 x 64 RGBA8 target; sample i adds one count (1/255) to one channel of one row, (i mod 256)
// picking row and channel, so a texel's channel holds at most ceil(samples / 256) counts. A channel saturates at 255:
// up to kHistogramMaxSamples = 256 x 255 = 65280 samples never saturate, and the histogram draws at most that many
// (a larger meter grid is sampled evenly). The 64 rows and 4 channels are then summed per bin into 16-bit counts.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace obscura::ExposureMetering {

constexpr float kMinLog2 = -16.0f, kMaxLog2 = 16.0f;
// The scene's log-average is exposed to the tone curves' mid grey 0.18 (Reinhard's key, the "18 % grey" a light
// meter assumes): EV = log2(0.18) - l_adapted.
constexpr float kKeyLog2 = -2.4739311f;  // log2(0.18)

constexpr int kMeterBlock = 8;    // the meter pass: 8 x 8 pixels per texel
constexpr int kReduceBlock = 16;  // each reduction: 16 x 16 texels per texel, until one level fits in 16 x 16
constexpr int kHistogramBins = 128;
constexpr int kHistogramRows = 64;
constexpr int kHistogramMaxSamples = kHistogramRows * 4 * 255;

constexpr float kBlack = 1.52587890625e-5f;  // 2^-16

float luminance(const glm::vec3& linear);
bool metered(const glm::vec3& linear);       // not black: Y >= kBlack
float meteredLog2(const glm::vec3& linear);  // l above (-16 for black)

std::uint16_t codeFromLog2(float x);  // clamps to [kMinLog2, kMaxLog2]
float log2FromCode(std::uint16_t code);
std::uint16_t codeFromWeight(float w);  // clamps to [0, 1]
float weightFromCode(std::uint16_t code);

// A reduction texel: the weighted mean log2 value and the weight, as the bytes the shader writes, and back.
struct MeteredBlock {
  float meanLog2 = 0.0f;
  float weight = 0.0f;
};
std::array<std::uint8_t, 4> bytesFromBlock(const MeteredBlock& block);
MeteredBlock blockFromBytes(const std::uint8_t* bytes);

// A lit pixel's metering weight at uv (0..1 across the frame): 1 for the plain average; centre-weighted,
// exp(-2 d^2) with d the distance from the frame's centre in half the frame's height (1 at the middle of the top
// edge, 0.14 there; the corners of a 16:9 frame weigh 0.0002).
enum class Metering { Average = 0, Centre = 1, Percentile = 2 };
float meteringWeight(Metering metering, glm::vec2 uv, float aspect);

// The number of reductions after the meter pass for a frame (each divides by 16, until the level fits in 16 x 16),
// and the meter grid's size: ceil(frame / 8).
glm::ivec2 meterGridSize(glm::ivec2 frame);
int reductionCount(glm::ivec2 frame);

// The histogram's bin for a log2 value, and the value a bin stands for (its centre).
int histogramBin(float log2Value);
float histogramBinCentre(int bin);
// The mean of the samples between the `low` and `high` fractions of their count (0 <= low < high <= 1), each bin's
// samples at its centre, a bin cut by a bound counted in part. 0 without samples. (A grid texel with nothing lit in
// it is not a sample.)
float percentileMean(const std::vector<std::uint32_t>& counts, float low, float high);

// One frame of adaptation: the adapted value moves towards the metered one by 1 - e^(-speed dt), with speed `up`
// when the scene got brighter (target above the adapted value) and `down` when it got darker.
float adapt(float adaptedLog2, float targetLog2, float seconds, float up, float down);
// A frame whose total weight is 0 (nothing lit) meters the adapted value itself (kKeyLog2, EV 0, without history).
// The exposure the tone mapping applies, in EV: the key over the adapted log-average, clamped to [minEv, maxEv],
// plus the compensation; within [kMinLog2, kMaxLog2] (the encoding's range).
float exposureEv(float adaptedLog2, float compensation, float minEv, float maxEv);

}  // namespace obscura::ExposureMetering
