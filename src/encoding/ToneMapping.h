#pragma once
// Tone-mapping curves and the sRGB transfer function. CPU mirror of shaders_es2/lib/tonemap.glsl; tests hold the two
// together (tests/test_tonemap.cpp on the CPU, tests/test_gpu_hdr.cpp through the GPU).
//
// The tone-mapping pass: decode the HDR texel (lib/hdr.glsl), multiply by the exposure 2^EV (uniform u_exposure, set
// to exposureScale(ev)), apply the curve (TONEMAP_OPERATOR), encode sRGB (linearToSrgb) for the RGBA8 display target.
// Every curve takes non-negative linear Rec. 709 (sRGB primaries) and returns linear display values in [0, 1].
//
//   linear    clamp(x, 0, 1).
//   reinhard  x / (1 + x) per channel (Reinhard et al., "Photographic Tone Reproduction for Digital Images", SIGGRAPH
//             2002, eq. 3, applied per channel as three.js's ReinhardToneMapping does).
//   aces      Stephen Hill's fit of the ACES RRT + sRGB ODT (TheRealMJP/BakingLab, BakingLab/ACES.hlsl: ACESInputMat,
//             RRTAndODTFit, ACESOutputMat, saturate), applied to x / 0.6. The 1/0.6 pre-gain is three.js's
//             (ACESFilmicToneMapping, mrdoob/three.js PR #19696, after PR #19621 replaced Narkowicz's pre-exposed fit
//             by Hill's and every scene came out darker; PlayCanvas did the same, playcanvas/engine PR #5216). We
//             follow it:
//             without it Hill's fit puts scene mid-grey 0.18 at 0.106 on the display (sRGB 91/255), with it at 0.213
//             (sRGB 128), next to AgX's 0.215 and Neutral's 0.14, so switching operators keeps the exposure meaningful,
//             and a scene lit for three.js's ACES looks the same here. acesFitted() is Hill's fit alone, without it.
//   neutral   Khronos PBR Neutral (KhronosGroup/ToneMapping, PBR_Neutral/pbrNeutral.glsl and its README's
//             specification): startCompression 0.8 - 0.04, desaturation 0.15. It is not the identity below the knee:
//             it subtracts F90 = 0.04 (less near black, x - 6.25 x^2 when the darkest channel x < 0.08), so a colour
//             with every channel in [0.08, 0.8] comes out exactly 0.04 lower (the spec's first note).
//   agx       Blender's AgX base look as ported by Filament (google/filament, filament/src/ToneMapper.cpp,
//             AgxToneMapper; PR #7236) and three.js r15x (AgXToneMapping): linear Rec. 709 -> Rec. 2020, the inset
//             matrix, log2 between AgxMinEv -12.47393 and AgxMaxEv 4.026069 (log2(0.18 * 2^-10) and
//             log2(0.18 * 2^6.5)), the 6th-order polynomial sigmoid of iolite-engine's "minimal AgX implementation"
//             (the one three.js uses; Filament now uses a 7th-order one), the outset matrix, pow 2.2, Rec. 2020 ->
//             Rec. 709, clamp. GLSL ES 1.00 has no inverse(): agxMatrices() derives every matrix here, in double, from
//             its definition (the primaries, Filament's AgXInsetMatrix and AgXOutsetMatrixInv), and the shader carries
//             the products as literals that a test holds bit-identical to these floats (GlslConstants.h).
//
// Scene mid-grey 0.18 at EV 0 lands at: linear 0.18, reinhard 0.153, aces 0.213, neutral 0.14, agx 0.215 (display
// linear; tested).
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "encoding/GlslConstants.h"

namespace obscura {

// The values are TONEMAP_OPERATOR's in lib/tonemap.glsl.
enum class ToneMapOperator : int { Linear = 0, Reinhard = 1, AcesFitted = 2, Neutral = 3, AgX = 4 };
constexpr int kToneMapOperatorCount = 5;
constexpr ToneMapOperator kToneMapOperators[kToneMapOperatorCount] = {
    ToneMapOperator::Linear, ToneMapOperator::Reinhard, ToneMapOperator::AcesFitted, ToneMapOperator::Neutral,
    ToneMapOperator::AgX};

const char* toneMapOperatorName(ToneMapOperator op);  // "linear", "reinhard", "aces", "neutral", "agx"
ToneMapOperator parseToneMapOperator(std::string_view name);  // throws InputError naming the valid names
// {"TONEMAP_OPERATOR", "<n>"}, for ProgramSpec::defines.
std::pair<std::string, std::string> toneMapShaderDefine(ToneMapOperator op);

// The shader's u_exposure: 2^ev, computed once on the CPU so both sides multiply by the same float.
float exposureScale(float ev);

// The curve alone (exposure already applied) and with exposure: toneMap(op, x * exposureScale(ev)).
glm::vec3 toneMap(ToneMapOperator op, const glm::vec3& linearHdr);
glm::vec3 toneMap(ToneMapOperator op, const glm::vec3& linearHdr, float exposureEv);

glm::vec3 reinhard(const glm::vec3& x);
glm::vec3 acesFitted(const glm::vec3& x);  // Hill's fit, without three.js's 1/0.6 (toneMap adds it)
glm::vec3 pbrNeutral(const glm::vec3& x);
glm::vec3 agx(const glm::vec3& x);
float agxContrast(float x);  // the 6th-order sigmoid on [0, 1]

constexpr float kAcesExposureGain = static_cast<float>(1.0 / 0.6);  // three.js's ACESFilmicToneMapping pre-gain
constexpr float kAgxMinEv = -12.47393f;  // Filament / three.js AgxMinEv: log2(2^-10 * 0.18)
constexpr float kAgxMaxEv = 4.026069f;   // Filament / three.js AgxMaxEv: log2(2^6.5 * 0.18)

struct AgxMatrices {
  glm::mat3 input;           // inset * Rec.709->Rec.2020
  glm::mat3 outset;          // inverse(AgXOutsetMatrixInv)
  glm::mat3 rec2020ToSrgb;   // inverse(Rec.709->Rec.2020)
};
const AgxMatrices& agxMatrices();
// Hill's ACES matrices (BakingLab ACES.hlsl, rows as printed there, here as glm's column-major matrices).
glm::mat3 acesInputMatrix();
glm::mat3 acesOutputMatrix();

// Every literal lib/tonemap.glsl shares with this file.
std::vector<GlslConstant> toneMapShaderConstants();

// IEC 61966-2-1:1999 sRGB transfer function, the real piecewise curve: 12.92 c for c <= 0.0031308, else
// 1.055 c^(1/2.4) - 0.055; and its inverse (c / 12.92 for c <= 0.04045, else ((c + 0.055) / 1.055)^2.4). Inputs are
// clamped to [0, 1].
float linearToSrgb(float linear);
float srgbToLinear(float srgb);
glm::vec3 linearToSrgb(const glm::vec3& linear);
glm::vec3 srgbToLinear(const glm::vec3& srgb);

// Luma for FXAA: Lottes' FXAA 3.11 (NVIDIA, 2011) expects the luma of the display-encoded (sRGB) colour in alpha,
// computed as dot(rgb, (0.299, 0.587, 0.114)) (ITU-R BT.601 weights), the same in lib/tonemap.glsl's fxaaLuma.
float fxaaLuma(const glm::vec3& srgb);

}  // namespace obscura
