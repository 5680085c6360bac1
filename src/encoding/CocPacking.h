#pragma once
// The signed circle of confusion (effects/dof/DepthOfFieldEffect.h) in RGBA8, by arithmetic only. CPU mirror of
// shaders_es2/dof/coc.glsl (packCoc / unpackCoc, packHalfCoc / unpackHalfCoc); tests/test_dof.cpp holds the two
// together on the CPU and through the GPU.
//
//   CoC        C     the blur circle's signed diameter in pixels of the full frame, negative in front of the focus
//   range      R     the largest |C| the effect draws (2 x its largest radius in pixels): C is stored as C / R
//   dof-coc    code  = floor(clamp(C / R, -1, 1) * 32767 + 0.5) + 32768 in RG (high byte, low byte), as the velocity
//                    target's components are (encoding/VelocityPacking.h): C = 0 is exact, the step is R / 32767 (0.001
//                    pixel at the default R of 32 pixels); B, A zero
//   dof-half   code  = floor(clamp(C / R, -1, 1) * 127 + 0.5) + 128 in A beside the half-size colour, for the gather
//                    passes' weights only (a step of R / 127, a quarter pixel at R = 32: the composite, where an
//                    8-bit CoC draws halos, reads the 16-bit one)
// Each byte b is written as (b + 0.25) / 255 (encoding/LinearDepthPacking.h): rounding and truncating targets agree.
#include <array>
#include <cstdint>

namespace obscura::CocPacking {

constexpr float kSteps16 = 32767.0f, kSteps8 = 127.0f;

std::uint16_t codeFromCoc(float coc, float range);  // clamps to [-range, range]; a NaN is 0
float cocFromCode(std::uint16_t code, float range);
std::array<std::uint8_t, 4> bytesFromCoc(float coc, float range);  // the dof-coc texel
float cocFromBytes(const std::uint8_t* bytes, float range);         // two bytes, RG

std::uint8_t halfCodeFromCoc(float coc, float range);  // the dof-half alpha byte
float cocFromHalfCode(std::uint8_t code, float range);

}  // namespace obscura::CocPacking
