#pragma once
// 16-bit linear depth in two 8-bit channels, by arithmetic only (GLSL ES 1.00 has no bitwise operators).
// CPU mirror of shaders_es2/lib/packing.glsl (packLinearDepth / unpackLinearDepth); tests hold the two together.
//
//   linear depth  d    = (-z_view - near) / (far - near)            in [0, 1]       (Gravås 2013, sec. 3.1.3.2)
//   code          c    = floor(d * 65535 + 0.5)                     in [0, 65535]
//   bytes         hi   = floor(c / 256),  lo = c - 256 * hi         (exact in fp32: c < 2^24, 256 is a power of two)
//
// Each byte b is written as (b + 0.25) / 255, so a render target that rounds f * 255 to nearest and one that
// truncates it both store b. Reading applies floor(t * 255 + 0.5), so the texel decodes to b on either.
//
// Code 65535 (d = 1, the far plane) is the background: the G-buffer is cleared to it. Geometry within half a code of
// the far plane rounds to it and is treated as background too.
#include <array>
#include <cstdint>

namespace obscura::LinearDepthPacking {

constexpr std::uint32_t kCodeCount = 65536;
constexpr std::uint16_t kBackgroundCode = 65535;

std::uint16_t codeFromDepth(float linearDepth);  // clamps to [0, 1]
float depthFromCode(std::uint16_t code);          // exact: code / 65535
std::array<std::uint8_t, 2> bytesFromCode(std::uint16_t code);
std::uint16_t codeFromBytes(std::uint8_t high, std::uint8_t low);

// The float each byte is written as by the shader, and the byte a stored texel value decodes to.
float channelFromByte(std::uint8_t byte);
std::uint8_t byteFromChannel(float channel);

}  // namespace obscura::LinearDepthPacking
