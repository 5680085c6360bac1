#pragma once
// References made by brute force for the effects that integrate over time or over the pixel (issue 14):
//   - the shutter reference for motion blur: the mean of many renders with the temporal effects off, at times spread
//     over the exposure interval [T - s/(2F), T + s/(2F)] (shutter s, frame rate F), the interval centred on the
//     frame's time as a camera's shutter is (McGuire et al. 2012 blur the same interval);
//   - the supersampling reference for antialiasing: the frame rendered at k times its size with the antialiasing off,
//     box-downsampled (k x k pixels per output pixel). With a zero shutter the two combine: one instant,
//     supersampled, the reference of temporal antialiasing on a moving scene.
//   - the aperture reference for depth of field: the mean of many pinhole renders from points on the lens
//     (accumulateAperture below).
// The shutter and supersampling references average the final image's display values (sRGB-encoded, after the tone
// curve), which is what the effects they judge (motion blur, antialiasing, on display colour) are compared on and what
// a viewer sees; averaging linear light before the tone curve would brighten blurred edges between bright and dark by
// at most the curve's non-linearity over the two (docs/temporal-effects.md). The aperture reference averages linear
// light, as a lens does and as depth of field (on the HDR colour) gathers it: a small highlight far above display white
// makes a bokeh disc as bright as a lens would (docs/depth-of-field.md).
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec2.hpp>

#include "renderer/Renderer.h"
#include "renderer/RenderSettings.h"
#include "scene/Animation.h"
#include "scene/Camera.h"
#include "scene/Scene.h"

namespace obscura {

// `settings` with every effect whose EffectInfo::temporal is set switched off, and the AO's accumulation over frames
// (ao.temporal): what each sub-frame of a reference is rendered with.
RenderSettings withoutTemporalEffects(const RenderSettings& settings);

// The times of `samples` sub-frames spread evenly over [T - s/(2F), T + s/(2F)]: the midpoints of `samples` equal
// strata (stratified, so 64 samples leave no gaps a 64-tap blur would fill). A zero shutter gives `samples` copies
// of T. Throws InputError for samples < 1, fps <= 0 or a shutter outside [0, 1].
std::vector<double> shutterSampleTimes(double time, double fps, double shutter, int samples);

// An image of display values in [0, 1] with more precision than 8 bits: a mean of renders.
struct LinearImage {
  int width = 0, height = 0;
  std::vector<float> rgba;  // width * height * 4, rows top to bottom (like Image)

  float at(int x, int y, int c) const { return rgba[(static_cast<size_t>(y) * width + x) * 4 + c]; }
  // Rounded to 8 bits per channel (for PNGs).
  Image toImage() const;
  static LinearImage from(const std::vector<std::uint8_t>& rgba, int width, int height);
};

// The mean of `factor` x `factor` blocks of an RGBA8 image whose sides are multiples of `factor`. Throws InputError
// otherwise.
LinearImage downsampleBox(const std::vector<std::uint8_t>& rgba, int width, int height, int factor);

struct AccumulationOptions {
  double time = 0.0;     // T, seconds on the scene's timeline
  double fps = 60.0;     // F
  double shutter = 0.5;  // s: the fraction of the frame interval the shutter stays open (0: one instant)
  int samples = 64;      // sub-frames
  int supersample = 1;   // each sub-frame rendered at this many times the camera's size and box-downsampled
  AnimationChoice animation;
  bool loop = true;
};

// The mean of `options.samples` final images rendered with withoutTemporalEffects(settings) at shutterSampleTimes(),
// each through `cameraAt(t)` (a camera pan: the camera of each sub-frame; its size is the image's) at `supersample`
// times that size and box-downsampled. Renders into targets of its own through `renderer`, whose scene it draws;
// afterwards the renderer's history is that of the last sub-frame, so a caller rendering an effect after this
// renders that effect's frames anew (its previous frame first). Throws InputError when the supersampled size
// exceeds what the context can render.
LinearImage accumulateShutter(Renderer& renderer, const std::function<Camera(double)>& cameraAt,
                              const RenderSettings& settings, const AccumulationOptions& options);

// The aperture reference for depth of field (effects/dof/DepthOfFieldEffect.h): the mean of `samples` pinhole renders
// from points spread over the thin lens of the settings' dof.* parameters (whether `dof` is on or not), each through
// the camera moved to its lens point (looking the same way) with its frustum sheared so that the plane in focus stays
// where it is in the image (FrameOptions::projectionShift): points on that plane land on the same pixel from every
// lens point, and a point at depth D is spread over a disc of the thin lens's CoC. The lens points are Vogel's
// golden-angle spiral over the disc (each stands for an equal share of its area). Sub-frames are rendered with
// withoutTemporalEffects(settings) and the depth of field off, at `supersample` times the size. The focus is dof.focus,
// or for `auto` the G-buffer's depth at the autofocus pixel (autofocusDistance). An orthographic camera has no lens:
// its sub-frames tilt its parallel rays about the plane in focus over a disc of slopes (FrameOptions::projectionShear;
// ThinLens::parallelAperture), which spreads a point over the orthographic CoC. Throws InputError for samples < 1.
// The mean is of the sub-frames' HDR colour as the tone mapping reads it (scene-color), tone-mapped on the CPU with
// tonemap.* (ToneMapInUse): the reference of what the lens gathers, without what comes after the tone curve (the
// display stages: grading, vignette, grain, dithering; edges, motion blur, FXAA) or what the tone mapping adds (auto
// exposure, the lens flare's and glare's light), which the sub-frames leave out. Compare it with frames rendered
// without them (`--no-dither`: dithering is on by default).
struct ApertureOptions {
  int samples = 64;
  int supersample = 1;
  double time = 0.0;
  AnimationChoice animation;
};
LinearImage accumulateAperture(Renderer& renderer, const Camera& camera, const RenderSettings& settings,
                               const ApertureOptions& options);
// The lens point i of n: Vogel's spiral, radius sqrt((i + 1/2) / n), turned by the golden angle per point, in a disc
// of radius 1.
glm::vec2 lensPoint(int i, int n);
// The depth along the view axis (metres) of the G-buffer at the settings' autofocus pixel: what dof.focus=auto
// focuses on (the far plane where nothing was drawn). Renders one frame through `renderer`.
float autofocusDistance(Renderer& renderer, const Camera& camera, const RenderSettings& settings, double time = 0.0,
                        const AnimationChoice& animation = {});

}  // namespace obscura
