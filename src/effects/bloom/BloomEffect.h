#pragma once
// Bloom (shaders_es2/bloom/bloom.frag) on the HDR scene colour, after TAA and before tone mapping, following Jimenez
// 2014 ("Next generation post processing in Call of Duty: Advanced Warfare", SIGGRAPH course): the light above a
// threshold is taken out of the frame, downsampled in a chain to 1/64 of the frame with a 13-tap filter, upsampled
// back with a 3x3 tent, each level blended with the one below, and added to the frame. The lecture deck's glow
// (Samuelcik, "Post-processing", "Glow": threshold, blur downsampled, add back) with the modern filters.
//
//   bloom-prefilter-blocks  scene-color (full) -> bloom-blocks: each texel's colour scaled by the soft threshold
//                    below (per texel, so a single bright pixel keeps its energy), and averaged in 2 x 2 blocks on the
//                    even grid (texels 2k, 2k + 1 per axis) and on the odd grid (2k - 1, 2k), side by side
//   bloom-prefilter  bloom-blocks -> bloom-1 (1/2): the 13-tap filter of the thresholded frame from 9 even blocks
//                    and 4 odd ones (below): each frame texel is read and thresholded twice, not 9 times
//   bloom-down-k     bloom-(k-1) -> bloom-k (1/2^k), k = 2 .. 6: the 13-tap filter
//   bloom-up-k       bloom-k (its own size) + up k+1 (tent-filtered, 4 x 4 texels by hand) -> bloom-up-k, k = 5 .. 1:
//                    up_k = (1 - radius) level_k + radius tent(up_k+1)  (up_6 is level 6)
//   bloom            scene-color + intensity x tent(up_1) -> scene-color (full): the composite
// Each is a pass of the plan, its target pooled (fewer levels where 1/2^k of the frame would be under 2 pixels).
// The tent is separable: each upsample and the composite take it in two passes, bloom-tent-k along x into a target
// of the finer width and the coarser height (4 fetches), then along y in the up's own draw (4 more): 8 decoded
// texels instead of 16 (measured in docs/bloom-and-fog.md).
// Every filter's weights sum to 1 and every level covers the frame, so each level holds the same light as the
// thresholded frame, and so does up_1 whatever the radius: the glow adds `intensity` times the light above the
// threshold (tests/test_bloom.cpp measures it); the radius moves it between the narrow levels and the wide ones.
//
// 13-tap downsample (Jimenez 2014, slide 150): 13 bilinear taps on texel corners, the centre 2 x 2 boxes at
// (+-1, +-1) weighing 0.5 and the nine boxes at (0, +-2) x (0, +-2) with (1, 2, 1) x (1, 2, 1) / 32. By hand over the
// 6 x 6 texels it covers: w(i, j) = a_i a_j / 2 + b_i b_j / 2, a = (1, 1, 2, 2, 1, 1) / 8, b = (0, 1, 1, 1, 1, 0) / 4.
// Both parts are made of 2 x 2 blocks: a is (1, 2, 1) / 4 over the three blocks of texel pairs (2o - 2, 2o - 1),
// (2o, 2o + 1), (2o + 2, 2o + 3) (the even grid), b the mean of the two pairs (2o - 1, 2o), (2o + 1, 2o + 2) (the
// odd grid). The prefilter uses it: the blocks first (4 thresholded texels each, each texel in one block per grid),
// then level 1 from 9 + 4 blocks, 2 + 3.25 decoded texels per frame pixel instead of 9 (and 2 thresholds instead of
// 9): on SwiftShader at 1280 x 720, 68.5 ms -> 14.7 + 18.1 (docs/bloom-and-fog.md). One more RGB9E5 rounding. The
// blocks are aligned on the frame's texels, so on a frame of odd width (or height) level 1 lies on the frame's first
// 2 floor(w / 2) texels, the last one reached at the edge's clamp; the 13 taps texel by texel spread it over all w
// (its centres up to a frame pixel apart, at the far edge). The other levels keep the 13 taps texel by texel: below
// 1/2 they cost a sixth of the frame's pixels together.
//
// Soft threshold (per texel, on its largest channel m; T threshold, K = knee x T): the colour is scaled by
// c(m) / m with c(m) = 0 for m <= T, (m - T)^2 / (4K) up to T + 2K, m - T - K above: continuous with its slope, and
// nothing at or below the threshold blooms, so a frame with no pixel above it is unchanged. (Unity's and
// Jimenez's knee is centred on T instead, and lets a little light below the threshold bloom.) No Karis average on
// the first level: it would take most of a lone bright pixel's energy away; TAA, before bloom, steadies fireflies.
//
// The bright pass for other effects: level 2 (1/4 of the frame: the thresholded light, twice downsampled) is also the
// frame's `bloom-bright` target, which the lens flare and the glare read (effects/lens_flare, effects/glare), so they
// need no full-resolution pass of their own. With bloom off, the `bloom-bright` pass makes it alone (prefilter and one
// downsample), and runs only when something reads it.
//
// Encoding: every level is RGBA8 holding RGB9E5 (lib/hdr.glsl), fetched NEAREST, decoded texel by texel and filtered
// in the shader. No RGBA8 encoding of HDR colour filters correctly under the hardware's bilinear filter (it averages
// the bytes: RGBM and RGB9E5 multiply a filtered mantissa by a filtered exponent, LogLuv averages logarithms), and
// linear 8-bit bands: measured in tests/test_bloom.cpp ("HardwareFilteringOfEncodedTexelsIsWrong") and
// docs/bloom-and-fog.md.
#include <functional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "frame/EffectEntry.h"
#include "frame/Stage.h"
#include "gl/RenderTarget.h"

namespace obscura {

struct BloomSettings : ParameterAccess<BloomSettings> {
  bool enabled = false;
  float threshold = 1.0f;  // linear HDR: display white at exposure 0 (Unity's, Filament's default)
  float knee = 0.5f;       // soft knee width as a fraction of the threshold (Unity's soft knee, 0.5)
  float intensity = 0.1f;  // the fraction of the light above the threshold added as glow (Filament's strength, 0.1)
  float radius = 0.75f;    // the weight of the wider levels in each upsample, 0 (only 1/2) .. 1 (only 1/64)

  static const std::vector<Parameter<BloomSettings>>& parameters();
  void validate() const { validateParameters("bloom"); }
};

// CPU mirror of the shader's arithmetic.
// The soft threshold's factor for a colour: c(m) / m (0 for black).
float bloomThresholdScale(const glm::vec3& color, float threshold, float knee);
// The 13-tap filter's 1-D parts over the 6 texels it covers (index 0 .. 5: texel offsets -3 .. 2 from the corner at
// the destination pixel's centre).
float bloomDownsampleWeight(int i, int j);
// The tent-filtered upsample's 1-D weight of source texel i0 - 1 + k (k = 0 .. 3) for a fraction f of the way from
// texel i0's centre to the next's.
float bloomUpsampleWeight(int k, float f);
// The number of levels for a frame: 6 (1/64), fewer where 1/2^k of the frame would be under 2 pixels.
int bloomLevels(glm::ivec2 frame);

class BloomEffect : public Effect {
 public:
  using Settings = BloomSettings;
  static constexpr bool kHasSwitch = true;
  static constexpr int kMaxLevels = 6;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();
  // The composite offers the stages after it (frame/Stage.h: fullscreenStageHead): with bloom on and nothing else
  // reading its colour first, the tone curve and the display colour's stages run in its program. Its program without
  // stages and the fragment uniform vectors it keeps for itself (u_sourceSize, u_intensity).
  static std::vector<StageHeadSpec> stageHeads();
  static constexpr int kCompositeUniformVectors = 2;

  explicit BloomEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;

  // The whole chain on targets of its own, made for the call: reads `sceneColor` (RGB9E5, `size` pixels) and draws
  // the frame with its glow into whatever `bindOutput` binds (its viewport covering `size`). The frame runs the same
  // draws as its passes, on pooled targets; tests call this on frames of their own.
  void render(const BloomSettings& settings, const gl::Texture2D& sceneColor, glm::ivec2 size,
              const std::function<void()>& bindOutput) const;

 private:
  const EffectResources& resources_;
};

}  // namespace obscura
