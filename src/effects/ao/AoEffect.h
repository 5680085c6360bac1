#pragma once
// Ambient obscurance from the G-buffer (the estimators of ao.estimator, GTAO by default; SAO's depth hierarchy; an
// optional second depth layer) and a separable bilateral blur, at full or half resolution. Settings:
// effects/ao/AoSettings.h.
//
// Passes (each skipped when its settings turn it off):
//   peel       scene, G-buffer -> second-layer (ao.layers 2: the nearest surface behind the visible one;
//              effects/ao/DepthPeelPass.h)
//   hierarchy  G-buffer (+ second-layer) -> depth-hierarchy (its own storage: an atlas 1.5 times the frame's width,
//              or a mip chain; effects/ao/DepthHierarchyPass.h)
//   sao        G-buffer (+ hierarchy, + second-layer) -> ao-raw (full or half size)
//   ao-temporal  ao-raw, velocity, G-buffer, history -> ao-temporal (ao.temporal: effects/ao/AoTemporalPass.h)
//   blur-h     ao-raw (or ao-temporal) -> ao-blur-h   blur-v   ao-blur-h -> ao   (without the blur, ao is its input)
//   upsample   ao (half size) -> ao (full size), at half resolution
// The lighting reads "ao".
#include <optional>
#include <vector>

#include "effects/ao/AoSettings.h"
#include "effects/ao/AoTemporalPass.h"
#include "effects/ao/AoUpsamplePass.h"
#include "effects/ao/BilateralBlurPass.h"
#include "effects/ao/DepthHierarchyPass.h"
#include "effects/ao/DepthPeelPass.h"
#include "effects/ao/SaoPass.h"
#include "frame/EffectEntry.h"

namespace obscura {

class AoEffect : public Effect {
 public:
  using Settings = AoSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit AoEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;

  // The depth hierarchy's storage in use (tests and tools compare them).
  DepthHierarchyPass::Storage hierarchyStorage() const { return hierarchy_.storage(); }

 private:
  DepthHierarchyPass hierarchy_;
  DepthPeelPass peel_;
  SaoPass sao_;
  AoTemporalPass temporal_;
  BilateralBlurPass blur_;
  AoUpsamplePass upsample_;
};

}  // namespace obscura
