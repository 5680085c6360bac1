#pragma once
// Edges from the G-buffer (shaders_es2/edges/edges.frag), drawn as lines of a width in pixels over the display colour,
// and a stylised "toon" mode that also quantises the shading into bands (docs/edges.md).
//
// Schmalstieg's deck ("Edge Detection in Image Space", "Edge Detection on G-Buffer", "Non-Photorealistic
// Rendering"): run the filter on the depth buffer, profiles by a first-order differential, internal edges by a
// second-order one, and use the normal buffer as well. Obscura's one RGBA8 G-buffer holds both: an octahedral
// normal and the 16-bit linear depth. Three passes, all reading RGBA8 and writing RGBA8 (no multiple render targets):
//
// 1. edges-detect: each pixel against its four neighbours, from the G-buffer alone.
//    Depth (profiles). With w = 1/z the reciprocal of the view depth (0 for the background), the relative second
//      difference along x (and likewise y)
//        D_x = z_c (w_left + w_right) - 2                                                     (eq. 1)
//      is exactly 0 on every plane at every slant, since 1/z is affine in screen position on a plane (perspective
//      division), whereas the first-order difference of a slanted plane grows without bound as the plane turns
//      edge-on. D is scale-aware: it is unchanged when the whole scene and camera are scaled (z -> k z), as the
//      bilateral blur's depth weights are (blur.frag: sigma a fraction of the AO radius, not a depth-buffer unit).
//      At a profile whose near side is flat, D on the near pixel is z_near / z_far - 1: the relative first-order
//      jump, the deck's profile measure, and it is negative there (the pixel stands in front of its neighbours)
//      while it is positive on the far pixel. A pixel is a profile pixel where min(D_x, D_y) < -t_d, so the line
//      lies on the occluding side of the silhouette.
//      Under an orthographic camera z itself is affine in screen position on a plane, and the eye's distance means
//      nothing (the image is the same from anywhere along the axis): D_x = (2 z_c - z_left - z_right) / L, with L
//      the view's height (2 ymag: the depth at which a 53 degree lens sees as much). To first order in the jumps it
//      is the perspective D at z_c = L, so t_d keeps its meaning; a background neighbour is an infinite jump.
//    Normals (creases). A pixel is a crease pixel where a neighbour's normal is more than the crease angle away
//      (n_c . n_n < cos angle) and the neighbour is not nearer (depth code >= the pixel's; ties mark both): the
//      same rule, the nearer side of the boundary, so a crease too is one pixel wide.
//    Colour (optional, edges.color-threshold > 0). A pixel is a colour-edge pixel where a neighbour's display luma
//      (display-color's alpha, FXAA's luma) exceeds its own by more than t_c: the darker side.
//    Writes "edges-mask": R profile, G crease, B colour edge (each 0 or 1), A 1.
// 2. edges-h: for each pixel, the distance g in pixels to the nearest edge pixel of its row within R, R + 1 where
//    there is none (the first half of a separable exact Euclidean distance transform).
// 3. edges: d = min over |j| <= R of sqrt(g(y + j)^2 + j^2), the Euclidean distance to the nearest edge pixel's
//    centre; the line's coverage of the pixel is
//        a = strength clamp(width / 2 + 1/2 - d, 0, 1)                                        (eq. 2)
//    (a box filter's coverage of a band of `width` pixels: whole inside, a ramp one pixel wide at the line's sides,
//    which is the line's antialiasing; FXAA, after it in the frame, smooths the staircase of the pixels along it).
//    R = ceil(width / 2 - 1/2) is the farthest pixel a can reach. The display colour becomes mix(c, line colour, a).
//
// Where in the frame: after the tone mapping, on display colour. The line colour is then the colour on screen, the
// width is in output pixels, and the tone mapping (or the lighting that absorbs it) still writes display colour
// directly. Hatching (edges.style hatching) draws tonal strokes in world space first (Hatching.h). Toon (edges.style
// toon) quantises the display luma Y (BT.601, FXAA's) of each pixel into `bands` equal steps and rescales the colour
// to the band's centre, c' = min(c L / Y, 1) with L = (min(floor(Y bands), bands - 1) + 1/2) / bands: the shading
// becomes flat bands and the hue is kept. It quantises what the lighting made (the base colour times the light), which
// is what a frame without a separate albedo target has on every context.
//
// CPU mirror: EdgeDetector (pass 1), edgeDistances (passes 2 and 3's distance), lineCoverage (eq. 2) and toonShade;
// tests/test_edges.cpp holds the GPU to them and the lines to the analytic silhouette and creases of a cube.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "effects/edges/Hatching.h"
#include "frame/EffectEntry.h"

namespace obscura {

enum class EdgeStyle { Lines = 0, Toon = 1, Hatching = 2 };
const char* edgeStyleName(EdgeStyle style);  // "lines", "toon", "hatching"

struct EdgesSettings : ParameterAccess<EdgesSettings> {
  bool enabled = false;
  EdgeStyle style = EdgeStyle::Lines;
  float width = 1.5f;                 // pixels of the output
  glm::vec3 color{0.0f};              // linear; drawn as its sRGB display colour
  float strength = 1.0f;              // the line's opacity
  float depthThreshold = 0.05f;       // t_d: the least relative depth jump that is a profile (eq. 1)
  float normalThreshold = 35.0f;      // degrees between neighbouring normals that make a crease
  float colorThreshold = 0.0f;        // t_c, display luma; 0: no colour edges
  int bands = 4;                      // toon, hatching: shading levels
  float hatchSpacing = 6.0f;          // hatching: pixels between strokes (effects/edges/Hatching.h)

  static const std::vector<Parameter<EdgesSettings>>& parameters();
  void validate() const { validateParameters("edges"); }
};

// What pass 1 writes per pixel.
struct EdgeFlags {
  bool profile = false, crease = false, color = false;
  bool any() const { return profile || crease || color; }
};

// Pass 1's constants, derived once per frame, and its arithmetic on G-buffer texels as read back (RGBA8: RG the
// octahedral normal, BA the 16-bit depth code).
struct EdgeDetector {
  float depthThreshold = 0.05f;
  float normalCos = 0.0f;
  float colorThreshold = 0.0f;
  float near = 0.1f, depthRange = 99.9f;  // z = near + code / 65535 depthRange
  float orthographicDepth = 0.0f;         // L, for an orthographic camera; 0: perspective

  // `orthographicDepth`: L above (2 ymag), or 0 for a perspective camera.
  static EdgeDetector of(const EdgesSettings& settings, float near, float far, float orthographicDepth = 0.0f);
  // The view depth z of a texel, 0 for the background.
  float viewDepth(const std::uint8_t* texel) const;
  // Pass 1 over a whole image (4 bytes a pixel, rows in either order: the tests are symmetric); `luma` (one value
  // a pixel, display luma in [0, 1]) only where colour edges are on. Neighbours outside the image are the pixel
  // itself (CLAMP_TO_EDGE).
  std::vector<EdgeFlags> detect(const std::vector<std::uint8_t>& gbuffer, int width, int height,
                                const std::vector<float>& luma = {}) const;
  // Eq. 1 (or its orthographic form) along one axis for the pixel of depth zc between neighbours of depths za and
  // zb (0: background).
  float relativeSecondDifference(float zc, float za, float zb) const;
};

// R: how far (pixels) a line of `width` reaches from its edge pixel.
int lineRadius(float width);
// Per pixel, the Euclidean distance to the nearest edge pixel's centre where it is at most R, else something
// larger than R (what passes 2 and 3 compute).
std::vector<float> edgeDistances(const std::vector<EdgeFlags>& edges, int width, int height, int radius);
// Eq. 2.
float lineCoverage(float distance, float width, float strength);
// The toon quantisation of a display colour (sRGB-encoded, [0, 1]).
glm::vec3 toonShade(const glm::vec3& srgb, int bands);

class EdgesEffect : public Effect {
 public:
  using Settings = EdgesSettings;
  static constexpr bool kHasSwitch = true;
  static constexpr int kMaxRadius = 4;  // R at the widest line, 8 pixels
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit EdgesEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;
};

}  // namespace obscura
