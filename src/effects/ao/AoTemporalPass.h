#pragma once
// Temporal accumulation of the raw AO (ao.temporal): shaders_es2/ao/ao_temporal.frag, arithmetic and CPU mirror in
// effects/ao/AoTemporal.h. Draws into the bound target (the pooled "ao-temporal", in the ao-raw layout plus the
// history's frame count in A), then copies it into the history target the next frame reads (RenderTargetPool::History):
// one draw and a glCopyTexSubImage2D, since GLES 2 has no multiple render targets to write both at once.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "effects/ao/AoSettings.h"
#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"
#include "frame/RenderTargetPool.h"

namespace obscura {

class AoTemporalPass {
 public:
  static std::vector<ProgramSpec> programSpecs();

  explicit AoTemporalPass(const EffectResources& resources) : resources_(resources) {}
  // `history` sized like the AO; `aoScale` 1 or 2 (half resolution). The bound framebuffer is `aoSize` pixels.
  // `objectsMove`: some instance's pose differs from the previous frame's (GpuScene::anyMoving).
  void render(const gl::Texture2D& rawAo, const gl::Texture2D& velocity, const gl::Texture2D& gbuffer,
              RenderTargetPool::History& history, const FrameContext& frame, const AoSettings& settings,
              int aoScale, glm::ivec2 aoSize, bool objectsMove);

 private:
  // What must match for the history to hold this AO: a history written with other settings, or not in the previous
  // frame (the effect was off, or the history was dropped), is not used.
  struct Written {
    std::uint64_t frame;
    AoEstimator estimator;
    int samples, aoScale;
    float radius;
    bool operator==(const Written& o) const {
      return frame == o.frame && estimator == o.estimator && samples == o.samples && aoScale == o.aoScale &&
             radius == o.radius;
    }
  };

  const EffectResources& resources_;
  std::optional<Written> written_;
  bool historyWasValid_ = false;  // in the frame written_ names
};

}  // namespace obscura
