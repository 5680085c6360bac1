#pragma once
// A 3D colour lookup table (colour grading's LUT): read from an Adobe / Resolve `.cube` file, stored for the GPU as a
// 2D strip of RGBA8 texels, and applied with trilinear interpolation. CPU mirror of the grading stage's lookup
// (shaders_es2/grading/grading.glsl); tests hold the two together.
//
// The .cube format (Adobe, "Cube LUT Specification", version 1.0, 2013; what DaVinci Resolve, Photoshop and most
// grading tools write): text lines, '#' starts a comment;
//   TITLE "text"                       optional
//   LUT_3D_SIZE N                      2 .. 256 lattice points per axis
//   DOMAIN_MIN r g b / DOMAIN_MAX r g b  the input range (default 0 0 0 and 1 1 1); each min below its max
//   LUT_3D_INPUT_RANGE min max         Resolve's form of the same, one range for all three
// then N^3 lines of three numbers, red changing fastest, then green, then blue. A 1D LUT (LUT_1D_SIZE) is refused:
// its curves are what grading's slope, offset and power already do. Anything else (an unknown keyword, a number that
// is not one, too few or too many rows, a keyword after the rows) is refused with the file's name and the line.
//
// The strip: slice b (blue lattice index) holds the N x N texels of (r, g) at (r, g) + b (N, 0), left to right, as
// wide as the context allows: slices that do not fit in one row wrap onto the next row of slices (cols = max size /
// N slices a row). Texel bytes are round(255 v) of each channel, clamped to [0, 1]; alpha 255. Hardware bilinear
// filtering of the strip interpolates r and g inside a slice (plain colour filters correctly); the blue axis, which
// crosses slices, is interpolated by hand between two fetches: trilinear, as the hardware cannot do it on a 2D texture.
//
// Where it applies: to display colour (sRGB-encoded, after the tone curve), as .cube files made for video and the web
// expect: the input is mapped from the domain to [0, 1] and clamped.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace obscura {

struct ColorLut {
  int size = 0;                        // lattice points per axis
  std::vector<glm::vec3> values;       // size^3, red fastest
  glm::vec3 domainMin{0.0f}, domainMax{1.0f};
  std::string title;

  const glm::vec3& at(int r, int g, int b) const {
    return values[(static_cast<size_t>(b) * size + static_cast<size_t>(g)) * size + static_cast<size_t>(r)];
  }
  // Trilinear interpolation of the lattice (as stored: each value quantised to 8 bits, as the strip holds it, when
  // `asStored`), at a colour mapped from the domain to [0, 1] and clamped.
  glm::vec3 apply(const glm::vec3& color, bool asStored = true) const;

  // The identity (each point its own coordinates), and a LUT sampling `f` on [0, 1]^3.
  static ColorLut identity(int size);
  static ColorLut of(int size, const std::function<glm::vec3(const glm::vec3&)>& f);
};

constexpr int kMinLutSize = 2, kMaxLutSize = 256;

// Parses .cube text; `name` (the file's) starts every message: "grade.cube line 12: expected three numbers, got
// 'a b c'". Throws InputError.
ColorLut parseCubeLut(const std::string& text, const std::string& name);
// Reads and parses a .cube file (InputError when it cannot be read).
ColorLut readCubeLut(const std::string& path);
// The .cube text of a LUT (every value in its shortest exact form).
std::string writeCubeLut(const ColorLut& lut);

// The strip as the GPU stores it.
struct LutStrip {
  int width = 0, height = 0;
  int slicesPerRow = 0;
  std::vector<std::uint8_t> rgba;  // rows bottom to top (uv y = 0 first), as a texture is uploaded
};
// Throws InputError when the strip cannot fit in a square of `maxTextureSize`.
LutStrip lutStrip(const ColorLut& lut, int maxTextureSize);

}  // namespace obscura
