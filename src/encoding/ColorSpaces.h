#pragma once
// RGB <-> CIE XYZ matrices derived from a colour space's primaries and white point, in double precision, so that every
// colour matrix the shaders use (lib/hdr.glsl's LogLuv, lib/tonemap.glsl's AgX) is computed once from its definition
// instead of being copied, rounded, from somewhere else. GLSL ES 1.00 has no inverse(): the CPU derives, the shader
// gets the numbers (see GlslConstants.h).
//
// Derivation (SMPTE RP 177-1993, sec. 3.3): with the primaries' chromaticities (x, y) lifted to XYZ at Y = 1,
// P = [X_r X_g X_b; 1 1 1; Z_r Z_g Z_b], and the white point W (Y = 1), the scales S = P^-1 W make
// RGB (1, 1, 1) map to W: M_RGB->XYZ = P diag(S).
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace obscura::ColorSpaces {

struct Primaries {
  glm::dvec2 red, green, blue, white;  // CIE 1931 xy chromaticities
};

// ITU-R BT.709-6, table "Derivation of luminance signal" / item 1.3-1.4: the sRGB primaries (IEC 61966-2-1 uses the
// same primaries and D65 white, x = 0.3127, y = 0.3290).
constexpr Primaries kBt709{{0.640, 0.330}, {0.300, 0.600}, {0.150, 0.060}, {0.3127, 0.3290}};
// ITU-R BT.2020-2, table 3, items 3.3-3.4: the Rec. 2020 primaries, D65 white.
constexpr Primaries kBt2020{{0.708, 0.292}, {0.170, 0.797}, {0.131, 0.046}, {0.3127, 0.3290}};

// Column-major (glm): XYZ = M * rgb. Row 1 of the result (M[0][1], M[1][1], M[2][1]) is the luminance weights.
glm::dmat3 rgbToXyz(const Primaries& primaries);

// Linear BT.709 (sRGB) to linear BT.2020 RGB: rgbToXyz(BT.2020)^-1 * rgbToXyz(BT.709). ITU-R BT.2087-0 eq. (4)
// prints it to four decimals (0.6274 0.3293 0.0433 / 0.0691 0.9195 0.0114 / 0.0164 0.0880 0.8956); tested against it.
glm::dmat3 srgbToRec2020();

// The fully bright colour of a hue (HSV with V = 1; hue in [0, 1), saturation 0 white .. 1 pure): the test and study
// colours of the HDR encodings sweep hues and saturations with it.
glm::vec3 hsvColor(float hue, float saturation);

}  // namespace obscura::ColorSpaces
