#pragma once
// Points and lines (glTF modes POINTS, LINES, LINE_LOOP, LINE_STRIP; gpu/GpuLines.h): drawn after the lighting
// into the lit HDR colour, unlit (the material's base colour factor times COLOR_0, as KHR_materials_unlit colours
// are: a point or a line has no normal to light), depth-tested against the surfaces through the G-buffer's depth
// renderbuffer, without writing depth. They are not surfaces: they are not in the G-buffer, so the AO neither sees
// nor darkens them. Lines are 1 pixel wide (WebGL 1 guarantees no other width); points are squares of
// max(1, round(height / 360)) pixels (2 at 720p), within the context's ALIASED_POINT_SIZE_RANGE.
//
// One pass, "lines", planned only when the scene has points or lines (FrameContext::linesOrPoints): it copies
// "scene-color" into its own target (the plan gives a pass that reads and writes one name a fresh target) and draws
// over it. Its reading the G-buffer keeps the G-buffer pass running with the AO off.
#include <vector>

#include "frame/EffectEntry.h"

namespace obscura {

class LinesEffect : public Effect {
 public:
  using Settings = NoSettings;
  static constexpr bool kHasSwitch = false;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();
  explicit LinesEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;

 private:
  void run(const PassContext& context) const;
  // The points and the lines over the copied colour, depth-tested against the G-buffer's depth (run).
  void drawLines(const PassContext& context) const;

  const EffectResources& resources_;
  float maxPointSize_ = 1.0f;
};

}  // namespace obscura
