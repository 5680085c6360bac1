#pragma once
// Screen-space velocity in an RGBA8 texel, by arithmetic only. CPU mirror of shaders_es2/lib/packing.glsl
// (packVelocity / unpackVelocity); tests hold the two together.
//
//   velocity  v     = uv_now - uv_previous, per component       uv in [0, 1] across the screen: v in [-1, 1]
//   code      c     = floor(clamp(v, -1, 1) * 32767 + 0.5) + 32768     in [1, 65535]; v = 0 is code 32768 exactly
//   texel           = (x high, x low, y high, y low) bytes, each written as (b + 0.25) / 255 (LinearDepthPacking)
//
// 16 bits per component: a step of 1/32767 of the screen, 0.06 pixel at 1920 pixels, fine enough for reprojection
// (temporal antialiasing) and for blur lengths; a motion across more than the whole screen in one frame clamps.
// y is up, as in normalised device coordinates.
#include <array>
#include <cstdint>

#include <glm/vec2.hpp>

namespace obscura::VelocityPacking {

constexpr float kStepsPerUnit = 32767.0f;

std::uint16_t codeFromComponent(float v);  // clamps to [-1, 1]
float componentFromCode(std::uint16_t code);
std::array<std::uint8_t, 4> bytesFromVelocity(glm::vec2 velocity);
glm::vec2 velocityFromBytes(const std::uint8_t* bytes);  // four bytes

}  // namespace obscura::VelocityPacking
