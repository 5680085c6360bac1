#pragma once
// The obscurance estimator pass (ao.estimator; GTAO by default): from the G-buffer into the bound RGBA8 target,
// R = ambient visibility, GB = the centre's 16-bit depth code (the blur's key, so the blur reads a single texture).
// Shaders: shaders_es2/ao/gtao.frag, sao.frag (CPU mirror and equations: effects/ao/SaoKernel.h), hbao.frag, vo.frag or
// crytek.frag; all share ao/ao_estimator.glsl. Far taps read the depth hierarchy when one is given.
#include <array>
#include <optional>
#include <tuple>
#include <vector>

#include "effects/ao/AoSettings.h"
#include "effects/ao/DepthHierarchyPass.h"
#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"

namespace obscura {

class SaoPass {
 public:
  using Storage = DepthHierarchyPass::Storage;
  // The program variant for an estimator, a sample count, spiral turns, falloff (SAO) and depth source
  // (compile-time constants): no hierarchy (every tap reads the G-buffer), or the hierarchy in the given storage.
  // `layers` 2: the variant that also reads the second depth layer (ao.layers 2). `normalsFromDepth`: the centre's
  // normal reconstructed from the depth (gbuffer.normals reconstructed: lib/normal_from_depth.glsl).
  static ProgramSpec programSpec(AoEstimator estimator, int samples, int spiralTurns, Falloff falloff,
                                 std::optional<Storage> hierarchy, int layers = 1, bool normalsFromDepth = false);
  // GTAO's split of `samples` taps: slices per pixel, sides of each (2, or 1 below 8 samples) and taps per side
  // (sides x slices x steps, about samples).
  struct GtaoSampling {
    int slices, steps, sides;
  };
  static GtaoSampling gtaoSampling(int samples);
  // HBAO's split of `samples` taps: directions per pixel and taps per direction (directions x steps <= samples).
  struct HbaoSampling {
    int directions, steps;
  };
  static HbaoSampling hbaoSampling(int samples);
  // The estimators that take their taps in mirrored pairs (volumetric obscurance's line samples, Crytek's kernel
  // points): floor(samples / 2) pairs (at least one), so 2 x pairs <= samples taps (10 at the medium preset's 11).
  static int mirroredPairs(int samples);
  // The factor the estimator's obscurance is multiplied by before the contrast (ao/ao_estimator.glsl): SAO's
  // 5 sigma / s or 2 sigma / s (SaoKernel::intensityScale); sigma for the others, whose obscurance is in [0, 1].
  static float intensityScale(const AoSettings& settings, float intensity);
  // Every variant the presets and the documented sample counts (4, 8, 11, 16, 24, 32) use.
  static std::vector<ProgramSpec> programSpecs();

  explicit SaoPass(const EffectResources& resources) : resources_(resources) {}
  // Draws into the bound framebuffer, whose size is `aoSize`: the G-buffer's, or floor(size / 2) at half
  // resolution (`aoScale` 2). `hierarchy` null: every tap reads the G-buffer.
  // `frameOffset`: the taps' per-frame rotation and distance jitter (AoTemporal::frameOffset; zero without
  // ao.temporal).
  // `secondLayer` (ao.layers 2): the depth peel's target, or null for one layer. `normalsFromDepth`: gbuffer.normals
  // reconstructed.
  void render(const gl::Texture2D& gbuffer, const DepthHierarchyPass* hierarchy, const gl::Texture2D* secondLayer,
              const FrameCamera& camera, const AoSettings& settings, bool normalsFromDepth, int aoScale,
              glm::ivec2 aoSize, glm::vec2 frameOffset = glm::vec2(0.0f)) const;

 private:
  // What render() derives from the settings, kept from the last frame and derived again only when its inputs change:
  // the program's spec (its name is text, formatted from every define) and the estimator's packed knots (a lookup in
  // the tuned table). Building both every frame was about 0.05 ms of the page's host time (docs/benchmarks.md).
  using SpecInputs = std::tuple<AoEstimator, int, int, Falloff, std::optional<Storage>, int, bool>;
  // estimator, preset, layers read, samples, falloff, and the bias, intensity, contrast and thickness set by hand.
  using KnotInputs = std::tuple<AoEstimator, QualityPreset, int, int, Falloff, std::optional<float>,
                                std::optional<float>, std::optional<float>, std::optional<float>>;
  const ProgramSpec& cachedSpec(const SpecInputs& inputs) const;
  const std::array<glm::vec4, kEstimatorKnots>& packedKnots(const AoSettings& settings) const;

  const EffectResources& resources_;
  mutable std::optional<SpecInputs> specInputs_;
  mutable ProgramSpec spec_;
  mutable std::optional<KnotInputs> knotInputs_;
  mutable std::array<glm::vec4, kEstimatorKnots> knots_{};
};

}  // namespace obscura
