// Auto exposure's 16-bit log2 values and weights (CPU mirror: src/encoding/ExposureMetering.h, which says why each
// constant is what it is). Needs lib/precision.glsl and lib/packing.glsl first.
//
//   log2 value x in [-16, 16] -> code floor((x + 16) / 32 * 65535 + 0.5), two bytes high first
//   weight     w in [0, 1]    -> code floor(w * 65535 + 0.5)
// Both are packLinearDepth's 16-bit fixed point of [0, 1] (lib/packing.glsl), which is exact in highp.
const float EXPOSURE_MIN_LOG2 = -16.0;
const float EXPOSURE_RANGE = 32.0;
const float EXPOSURE_BLACK = 1.52587890625e-5;  // 2^-16: a luminance below it is black, and not metered

vec2 packLog2(float x) { return packLinearDepth((x - EXPOSURE_MIN_LOG2) * (1.0 / EXPOSURE_RANGE)); }
float unpackLog2(vec2 channels) { return EXPOSURE_MIN_LOG2 + unpackLinearDepth(channels) * EXPOSURE_RANGE; }
vec2 packWeight(float w) { return packLinearDepth(w); }
float unpackWeight(vec2 channels) { return unpackLinearDepth(channels); }

// The exposure target (auto exposure's result: RG the adapted log-average, BA the EV to apply) as a multiplier.
float exposureFromTarget(vec4 texel) { return exp2(unpackLog2(texel.ba)); }
