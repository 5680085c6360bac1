#pragma once
// Linear HDR radiance in RGBA8 texels that the hardware's bilinear filter may read: the prefiltered environment's
// levels (environment/Environment.h). CPU mirror of lib/environment.glsl's environmentDecode().
//
// scene-color's RGB9E5 (HdrEncoding.h) must be fetched NEAREST and filtered by hand: blending the bytes of texels with
// different exponents is not blending their colours. The environment is read by every lit pixel and by the whole
// background, so the hand filter's four fetches and four decodes per level were the lighting's largest cost on the
// CPU rasterisers. The candidates here decode with a multiply (and a square) from bytes the hardware blends: each is
// exact under filtering (linear) or close to it where neighbouring texels are alike. Each level has its own scale (a
// uniform), the level's brightest channel, so the bytes cover exactly its range.
// `build/obscura-environment-study` measures them against the filter over the linear texels (docs/lighting.md).
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace obscura {

// The values are ENVIRONMENT_ENCODING's in lib/environment.glsl.
enum class EnvironmentEncodingKind : int {
  // c / scale in RGB, rounded; A 1. Linear, so the filter is exact; the step is scale / 255 everywhere: coarse in the
  // level's darks when it holds a bright sun.
  Linear = 1,
  // sqrt(c / scale) in RGB, rounded; decoded squared. The step grows with the value (relative step 2 / (255 sqrt x)),
  // twice the linear's precision in the darks; the filter blends square roots, which is exact where the neighbours
  // are alike and under-reads between unlike ones (by (sqrt a - sqrt b)^2 / 4 at the midpoint).
  Sqrt = 2,
  // RGBM (Karis 2009) with the level's scale as its range: M = ceil(255 max / scale) / 255 in A, c / (M scale) in RGB.
  // Relative precision (8 bits of the brightest channel) down to scale / 255; the filter blends M and RGB apart, so it
  // is off where M changes between neighbours, by (dRGB dM) / 4 at the midpoint.
  Rgbm = 3,
};
const std::vector<EnvironmentEncodingKind>& allEnvironmentEncodings();
const char* environmentEncodingName(EnvironmentEncodingKind kind);  // "linear", "sqrt", "rgbm"

using EnvironmentTexel = std::array<std::uint8_t, 4>;

// The level's scale: its brightest channel (1 for a black level, so decoding stays finite).
float environmentLevelScale(EnvironmentEncodingKind kind, const std::vector<glm::vec3>& texels);
EnvironmentTexel encodeEnvironment(EnvironmentEncodingKind kind, const glm::vec3& linear, float scale);
std::vector<EnvironmentTexel> encodeEnvironmentLevel(EnvironmentEncodingKind kind,
                                                     const std::vector<glm::vec3>& texels, float scale);
// The decode of normalised channels (bytes / 255, or what the hardware's filter made of them).
glm::vec3 decodeEnvironmentChannels(EnvironmentEncodingKind kind, const glm::vec4& channels, float scale);
glm::vec3 decodeEnvironment(EnvironmentEncodingKind kind, const EnvironmentTexel& texel, float scale);

}  // namespace obscura
