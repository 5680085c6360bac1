#pragma once
// Hatching, the illustration deck's tonal strokes (edges.style hatching; shaders_es2/edges/hatching.glsl), drawn by
// the edges' last pass before its lines.
//
// Where the strokes live: in world space, projected triplanarly (each of the three planes facing a world axis,
// weighted by the normal's component along that axis to the 4th power). The frame's one G-buffer holds no texture
// coordinates, and a glTF's UVs, where a file has them, are laid out for its textures (atlases, mirrored islands,
// seams, arbitrary scales), not for strokes; world space needs nothing from the file, keeps the strokes on the
// surface as the camera moves (no "shower door" effect: they do not swim over the image), and gives every object the
// same stroke density. The depth-reconstructed position and the normal come from the G-buffer.
//
// Strokes stay about `hatch-spacing` pixels apart at any distance: the stroke period is the power-of-two octave of
// that spacing in world units at the pixel's depth, cross-faded into the next octave, whose strokes are every other
// one of the finer octave's (a tonal art map's mipmaps, Praun et al. 2001, "Real-Time Hatching", made procedurally).
// Each stroke is a line one pixel wide with its coverage ramping over one pixel (the edges' box-filter coverage).
//
// Tone: the display luma Y (FXAA's) in `bands` equal steps; the darkest band has bands - 1 layers of strokes, the
// lightest none. Layer k runs at 45, 135, 0, 90 degrees in its plane (then those turned by 22.5 degrees), offset by
// 0.37 k world units. The pixel becomes the paper (white) where no stroke covers it, the stroke (line) colour where
// one does; the background is left as it is. The edges' lines are drawn over it.
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "frame/FrameContext.h"
#include "gl/Program.h"

namespace obscura {

constexpr int kMaxHatchLayers = 15;  // MAX_HATCH_LAYERS: bands up to 16

// CPU mirror. Layer k's stroke direction in its plane.
glm::vec2 hatchDirection(int layer);
// The strokes' coverage of layer k at world position p for a pixel of `pixel` world units.
float hatchLayerCoverage(const glm::vec3& p, const glm::vec3& weights, int layer, float pixel, float spacing);
// The display colour of a geometry pixel: `display` hatched by its luma.
glm::vec3 hatchedColor(const glm::vec3& display, const glm::vec3& worldPosition, const glm::vec3& worldNormal,
                       float pixel, float spacing, int bands, const glm::vec3& strokeColor);
// A pixel's size in the world at view depth z (negative), x z + y, from the projection: 2 w / (P11 H) with
// w = -z for a perspective projection, 1 for an orthographic one.
glm::vec2 pixelWorldSize(const glm::mat4& projection, int height);

// Sets the hatching uniforms on the program in use (by name: gl/Program.h); the G-buffer bound to `gbufferUnit`.
void setHatching(const gl::Program& program, const FrameCamera& camera, float spacing, int bands, int gbufferUnit);

}  // namespace obscura
