#pragma once
// Depth of field: a thin-lens camera's blur, gathered at half size in a near and a far field: the scatter-as-gather
// of Doerries 2018, sec. 3.2.6 (../shared/papers/doerries-2018-post-processing-survey.txt), after Sousa (CryEngine 3,
// SIGGRAPH 2013) and Jimenez ("Next generation post processing in Call of Duty: Advanced Warfare", SIGGRAPH 2014).
// Shader: shaders_es2/dof/dof.frag.
//
// The circle of confusion (Samuelcik's deck, "Depth of field"): a point at depth D seen through a lens of focal
// length F and aperture diameter A = F / N (N the f-number), focused at distance P, images as a disc of diameter
//   C = |A F (P - D) / (D (P - F))|
// on the sensor; on a sensor `h` tall imaged onto H pixel rows that is C H / h pixels. Here C keeps its sign,
// negative in front of the focus (D < P): C = s (D - P) / (D (P - F)) with s = A F H / h (ThinLens). D and P are
// depths along the view axis (the G-buffer's linear depth), as the thin-lens equation has them.
//
// An orthographic camera has no lens: every ray is parallel, and nothing depends on the eye's distance but its
// depths. It gets a focal plane at P and a CoC that grows linearly with the distance from it,
//   C = s (D - P) / (P (P - F)),
// the thin lens's own CoC to first order around its focus (dC/dD at D = P), so the settings keep their meaning there
// and the plane P is sharp; unlike the lens's, the blur keeps growing with D behind the focus. Its reference
// (renderer/AccumulationReference.h: accumulateAperture) tilts parallel rays about the focal plane over a disc of
// slopes instead of moving a pinhole over a lens (ThinLens::parallelAperture).
//
// Passes (RGBA8; the CoC in encoding/CocPacking.h's codes, range R = 2 x the largest radius in pixels):
//   dof-coc        gbuffer -> dof-coc               the signed CoC per pixel, 16 bits; P from dof.focus, or, for
//                                                   `auto`, the G-buffer's depth at the focus point (no read-back)
//   dof-downsample scene-color, dof-coc -> dof-half the 2 x 2 mean HDR colour (as a field: dofFieldEncode), the nearest
//                                                   (smallest) CoC, 8 bits
//   dof-tiles-h    dof-coc -> dof-tile-columns      the near field's largest |C| of K pixels of a row (K: the
//   dof-tiles      dof-tile-columns -> dof-tiles    ... of each K x K tile            largest radius, so that
//   dof-neighbors  dof-tiles -> dof-neighbors       ... of the 3 x 3 tiles around     a tile's neighbours hold
//                                                                                     every near pixel reaching it)
//   dof-near       dof-half, dof-neighbors -> dof-near  the near field: a golden-angle disc of T taps as wide as the
//                  neighbourhood's largest near CoC, each near sample beyond kDofSmallCoc weighted by whether its own
//                  CoC reaches the centre (scatter as gather) and by the share of its disc one tap stands for;
//                  premultiplied by the coverage, so an out-of-focus foreground spreads over the in-focus background
//                  behind it
//   dof-far        dof-half -> dof-far              the far field: T taps within the pixel's own CoC, far samples
//                  only, each reaching with the smaller of its CoC and the centre's (a blurred background does not
//                  spill over a sharper surface in front); premultiplied by 1 where the pixel is far, else 0
//   dof-composite  scene-color, dof-coc, dof-near, dof-far, dof-neighbors -> scene-color: a small blur (|C| up to
//                  kDofSmallCoc) gathered here at full size over the 3 x 3 block, the far field blended in by the
//                  pixel's own 16-bit CoC, the near field over it by its coverage. A pixel whose |C| is under half a
//                  pixel and that no near blur reaches is copied unchanged.
//
// Where it runs: before the tone mapping, on the HDR colour (after bloom, the lens flare and the glare's sources;
// before auto exposure meters it), as a lens gathers light: a small highlight far above display white makes a bokeh
// disc as bright as the lens's (docs/depth-of-field.md measures it against the aperture reference, which averages
// linear light). The half-size fields are plain bytes filtered LINEAR in the composite, so they hold the HDR colour
// as f = sqrt(c / (1 + c)) (dofFieldEncode), decoded at every tap.
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "frame/EffectEntry.h"
#include "frame/Stage.h"
#include "frame/TileMaxPasses.h"

namespace obscura {

struct DofSettings : ParameterAccess<DofSettings> {
  bool enabled = false;
  std::optional<float> focus;  // P, metres; unset: autofocus on the G-buffer's depth at (focusX, focusY)
  float focusX = 0.5f, focusY = 0.5f;  // the autofocus point: fractions of the width from the left, height from the top
  float fstop = 2.0f;          // N
  float focalLength = 50.0f;   // F, millimetres
  float sensorHeight = 24.0f;  // h, millimetres (a full-frame sensor's 36 x 24)
  float maxRadius = 16.0f;     // the largest blur radius, pixels at 720 rows (scaled with the height)
  QualityPreset preset = QualityPreset::Medium;  // dof.preset: the gather passes' taps

  static const std::vector<Parameter<DofSettings>>& parameters();
  void validate() const { validateParameters("depth of field"); }
  void applyPreset(QualityPreset which) { preset = which; }
  bool matchesPreset(QualityPreset which) const { return preset == which; }
  int taps() const;  // of the preset: 12, 24, 40, 64
  // The autofocus pixel of a width x height frame: (column, row from the top), inside the frame.
  glm::ivec2 focusPixel(int width, int height) const;
  // The largest blur radius in pixels for a frame `height` tall: maxRadius * height / 720, in [0.5, kMaxTile].
  float maxRadiusPixels(int height) const;
};

// The thin lens of the settings, for a frame `height` pixels tall: the CoC of a depth, and the lens a pinhole
// reference samples. CPU mirror of the CoC in shaders_es2/dof/dof.frag (pass 1).
struct ThinLens {
  float scale = 0.0f;        // s = A F H / h, pixel metres
  float focalLength = 0.05f; // F, metres
  bool orthographic = false; // the orthographic camera's focal plane (above)

  static ThinLens of(const DofSettings& settings, int height, bool orthographic = false);
  // P as the shader takes it: at least 1.001 F (a lens cannot focus nearer than its focal length).
  float usableFocus(float focus) const;
  // C in pixels at depth D for the focus P: s (D - P) / (D (P - F)), negative in front of the focus; orthographic:
  // s (D - P) / (P (P - F)).
  float coc(float depth, float focus) const;
  // The diameter of the lens a pinhole camera samples (metres in the scene) so that its renders, each sheared to
  // keep the plane at P fixed, blur a point at D over projScale A' |1/D - 1/P| pixels: C's own magnitude, since
  // C = s P / (P - F) (1/D - 1/P). `projScale`: pixels per metre at 1 m (FrameCamera::projScale().x).
  float pinholeAperture(float focus, float projScale) const;
  // The orthographic camera's: the diameter of the disc of slopes (metres sideways per metre of depth) over which its
  // parallel rays tilt about the plane at P, so that a point at D moves over pixelsPerMetre T |D - P| pixels: the
  // orthographic C's magnitude. `pixelsPerMetre`: FrameCamera::pixelsPerMetre.
  float parallelAperture(float focus, float pixelsPerMetre) const;
};

// The half-size fields' colour: linear HDR as f = sqrt(c / (1 + c)) per channel in a byte, and back (CPU mirror of
// toField / fromField in dof.frag): invertible, near sRGB's precision (a byte step is 1.3/255 of display colour at
// 0.01 and at 0.18 linear, 1.7/255 at 0.5; the tone curve compresses what lies above), up to 255 times display white.
glm::vec3 dofFieldEncode(const glm::vec3& linear);
glm::vec3 dofFieldDecode(const glm::vec3& field);
// Small blurs gathered at full size in the composite: CoCs up to kDofSmallCoc pixels (handing over to the half-size
// fields over the next pixel), over the 3 x 3 block (a disc of 2.5 pixels would reach the next ring of pixels by a
// sliver at the sides: measured, the 5 x 5 block is 10 % more accurate on the room's small blurs, and its gather
// costs about twice as much).
constexpr float kDofSmallCoc = 2.5f;

class DepthOfFieldEffect : public Effect {
 public:
  using Settings = DofSettings;
  static constexpr bool kHasSwitch = true;
  static constexpr int kMaxTile = 128;  // the tile passes' loop bound (MAX_TILE); the largest radius clamps to it
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();
  // The composite offers the stages after it (frame/Stage.h: fullscreenStageHead): the tone curve and the display
  // colour's stages run in its program instead of a pass of their own. Its program without stages and the fragment
  // uniform vectors it keeps for itself (u_range, u_fullSize).
  static std::vector<StageHeadSpec> stageHeads();
  static constexpr int kCompositeUniformVectors = 2;

  explicit DepthOfFieldEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;

 private:
  const EffectResources& resources_;
};

}  // namespace obscura
