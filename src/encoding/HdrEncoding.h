#pragma once
// Linear HDR colour in one RGBA8 texel. CPU mirror of encodeHdr / decodeHdr in shaders_es2/lib/hdr.glsl; the encoding
// is picked there by `#define HDR_ENCODING <n>` (the HdrEncodingKind values; hdrShaderDefines() writes them).
//
// Core GLES 2 / WebGL 1 renders only into RGBA8, so the lighting pass's colour above 1 (emissive surfaces, a sun
// highlight, later bloom's input) must be packed into four bytes and unpacked by the tone-mapping pass. As elsewhere
// (lib/packing.glsl) the shader computes exact byte values with floor/ceil arithmetic and writes byte b as
// (b + 0.25) / 255, which rounding and truncating targets both store as b; this file computes the same bytes.
//
// FILTERING AN ENCODED TEXTURE IS NOT FILTERING THE COLOUR. None of these encodings survives bilinear filtering,
// mipmapping, MSAA resolve or blending: the hardware would average bytes whose meaning depends on the other bytes of
// the texel (a shared exponent, a multiplier, the two halves of a 16-bit code). Readers must fetch texels with NEAREST
// sampling, decode each, and only then filter (for bloom's downsampling: four fetches, four decodes, then average).
// Nothing may blend into an encoded target: draw the HDR colour in one pass per pixel.
//
// Candidates, measured by `build/obscura-hdr-study` (tools/hdr_encoding_study.cpp defines every column): error is
// |decoded - c| over c's brightest channel, for 64 hues x 5 saturations and luminances 1e-4 .. the range; banding is
// the largest deviation the encoding adds to the display after exposure (-4 .. +4 EV), each of the five tone curves
// and 8-bit sRGB, in display LSBs, along smooth ramps (the display's own rounding is 0.5: more means coarser steps than
// the display's), for grey and pastel ramps (saturation <= 0.5) and saturated ones (0.9, 1); cost is encode + decode in
// a 1280x720 full-screen pass on llvmpipe beyond the same pass writing the colour plainly (2.06 ms), median of 60:
//
//   encoding  largest  smallest  error %      banding, LSB (EV 0 / -4..+4)              bilinear midpoint  cost
//                      (1 %)     max / mean   pastel        saturated     gradient / edge
//   rgbm8     8        0.0057    53 / 2.9     0.44 / 5.99   2.04 / 4.78   50 / 78 %          +0.67 ms
//   rgbm16    16       0.011     100 / 5.9    0.75 / 11.8   2.19 / 8.48   100 / 100 %        +0.62 ms
//   rgbm64    64       0.046     100 / 15     3.01 / 29.0   3.09 / 23.8   100 / 100 %        +0.62 ms
//   rgbd16    16       0.011     100 / 5.9    0.75 / 11.8   3.85 / 8.48   100 / 100 %        +0.77 ms
//   rgbd256   256      0.18      100 / 23     11.8 / 54.8   8.57 / 54.7   100 / 100 %        +0.86 ms
//   rgbe      4.3e9    2.3e-10   0.39 / 0.23  0.65 / 0.65   255 / 255     50 / 100 %         +1.86 ms
//   rgb9e5    65408    2.7e-6    0.20 / 0.10  0.34 / 0.34   1.96 / 1.97   126 / 184 %        +2.45 ms  <- chosen
//   logluv    65514    1.5e-5    1.3 / 0.58   2.84 / 2.84   255 / 255     4.4 / 103 %        +3.49 ms
//
// Chosen: RGB9E5 (kHdrColorEncoding). 16 stops over display white and the same relative precision from 2^-15 up, so
// dark gradients stay smooth at any exposure (0.34 LSB at most on grey and pastel ramps, every curve, -4 .. +4 EV),
// where RGBM and RGBD, linear, band near black once exposed up or at useful ranges; half RGBE's error, and zero
// channels stay zero where RGBE's centred decoding and LogLuv's chroma steps turn an over-exposed pure hue white under
// linear or Reinhard; cheaper than LogLuv; and an encoder of exact binary32 operations only (no log2: the exponent by a
// binary search with products by powers of two), so a GPU with binary32 highp writes the CPU's bytes (bit-exact on
// OSMesa and EGL).
// Its weakness is any shared exponent's: dimmer channels are quantised in the brightest channel's steps, so ramps of
// saturated colours (dimmer channels at 10 %) gain up to 0.7 (AgX) .. 1.45 (ACES) LSB, 2 under linear clamp, and
// near-pure hues (1 %) up to 6 LSB with ACES, 16 with linear clamp once the brightest channel clips.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "encoding/GlslConstants.h"

namespace obscura {

// The values are HDR_ENCODING's in lib/hdr.glsl.
enum class HdrEncodingKind : int {
  // Karis, "RGBM color encoding", 2009 (graphicrants.blogspot.com), as three.js's LinearToRGBM: M = ceil(max / R *
  // 255) / 255 (quantised up, so rgb / (M R) <= 1), rgb / (M R) in RGB. Linear; precision relative to R, not to the
  // colour: the darkest step is R / 255^2.
  Rgbm = 1,
  // three.js's LinearToRGBD ("divide"): D = clamp(floor(R / max), 1, 255) in A, rgb * D / R in RGB, decoded
  // rgb * R / D. Finer than RGBM near R, the same darkest step R / 255^2.
  Rgbd = 2,
  // Ward, "Real Pixels", Graphics Gems II (1991): shared exponent, 8-bit mantissas. max = m 2^e with m in [0.5, 1)
  // (frexp), bytes floor(c 2^(8-e)), E = e + 128; decoded (byte + 0.5) 2^(E-136), E = 0 is black. e is limited to
  // [-31, 32] here, which keeps every 2^k a normal float inside GLSL ES 1.00's minimum highp range (2^62).
  Rgbe = 3,
  // OpenGL's GL_RGB9_E5 (EXT_texture_shared_exponent, "Encoding of special internal formats"; OpenGL 3.0 spec
  // sec. 3.8.1): three 9-bit mantissas, one 5-bit exponent, bias 15, largest value 65408, rounding to nearest, with
  // denormals down to 2^-24. The 32 bits are split by arithmetic: RGB hold each mantissa's low 8 bits, A holds
  // exponent * 8 + the three mantissas' ninth bits (red 4, green 2, blue 1).
  Rgb9e5 = 4,
  // LogLuv after Ward, "The LogLuv Encoding for Full Gamut, High Dynamic Range Images", JGT 3(1), 1998: CIE
  // luminance Y as a 16-bit log code (B high byte, A low byte), 2048 codes per octave over [2^-16, 2^16), and the
  // CIE 1976 UCS chromaticity (u', v') in R and G. Unlike Ward's 410 steps over the whole visible gamut, u' and v'
  // take 620 steps per unit over the sRGB gamut (u' 0.125 .. 0.451, v' 0.158 .. 0.563: its primaries), offset so
  // that D65 white lands on a code (grey decodes grey). Matrices derived from the BT.709 primaries (ColorSpaces.h),
  // not the Ericson / Heavenly Sword matrix three.js used ("Converting RGB to LogLuv in a fragment shader",
  // realtimecollisiondetection.net, 2007), whose luminance weights for r, g, b (0.339, 0.678, 0.113) are not CIE Y's.
  LogLuv = 5,
};

struct HdrEncoding {
  HdrEncodingKind kind = HdrEncodingKind::Rgb9e5;
  float range = 0.0f;  // RGBM and RGBD only: the largest channel value, HDR_RANGE in the shader

  std::string name() const;  // "rgbm16", "rgbd256", "rgbe", "rgb9e5", "logluv"
};

// The encoding the lighting pass writes and the tone-mapping pass reads (lib/hdr.glsl's default).
constexpr HdrEncoding kHdrColorEncoding{HdrEncodingKind::Rgb9e5, 0.0f};

// Every candidate the study measures and the tests cover.
std::vector<HdrEncoding> hdrEncodingCandidates();

using HdrTexel = std::array<std::uint8_t, 4>;  // R, G, B, A bytes as stored in the RGBA8 target

// Negative channels encode as 0 (NaN too on the CPU; the GPU's clamp of NaN is undefined). Values above the largest
// encodable clamp: per channel for RGBM, RGBD, RGBE and RGB9E5 (so an over-range colour shifts hue), in luminance for
// LogLuv (chroma kept).
//
// `roundingMargin`, when given, receives the smallest distance, in units of the code being rounded, between an
// inexactly computed value (a division, a log2, a dot product) and the boundary where its byte changes. The GPU
// rounds those operations its own way, so only values closer than a hair to a boundary may legitimately land in the
// neighbouring code (tests/test_gpu_hdr.cpp). Operations exact in binary32 (a product by a power of two) count as
// infinitely far.
HdrTexel encodeHdr(const glm::vec3& linear, const HdrEncoding& encoding = kHdrColorEncoding,
                   float* roundingMargin = nullptr);
glm::vec3 decodeHdr(const HdrTexel& texel, const HdrEncoding& encoding = kHdrColorEncoding);

// The largest value a channel (RGBM, RGBD, RGBE, RGB9E5) or the luminance (LogLuv) can hold.
float hdrLargestValue(const HdrEncoding& encoding);

// {"HDR_ENCODING", "<n>"} and, for RGBM and RGBD, {"HDR_RANGE", "<R>"}: for ProgramSpec::defines.
std::vector<std::pair<std::string, std::string>> hdrShaderDefines(const HdrEncoding& encoding);

// LogLuv's matrices and chroma code offsets, derived from the BT.709 primaries; every literal lib/hdr.glsl shares with
// this file.
struct LogLuvConstants {
  glm::mat3 encode;    // linear sRGB -> (4X, Y, X + 15Y + 3Z)
  glm::mat3 decode;    // (u' d, Y, d) with d = X + 15Y + 3Z -> linear sRGB
  float uOffset = 0, vOffset = 0;  // u' = uOffset + code * kLogLuvChromaStep
};
constexpr float kLogLuvChromaScale = 620.0f;  // codes per unit of u' and v'
constexpr float kLogLuvChromaStep = 1.0f / 620.0f;
constexpr int kLogLuvWhiteU = 46, kLogLuvWhiteV = 193;  // D65's codes
const LogLuvConstants& logLuvConstants();
std::vector<GlslConstant> hdrShaderConstants();

}  // namespace obscura
