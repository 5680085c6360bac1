#pragma once
// The G-buffer: the scene drawn once into one RGBA8 target (RG octahedral view-space normal, BA 16-bit linear depth;
// shaders_es2/gbuffer/gbuffer.frag) with its own depth renderbuffer, which the lighting pass then shares. Cleared to
// depth code 65535, the background marker. Always part of the frame; the plan drops it when no running pass reads it
// (the AO off: the lighting then depth-tests on its own).
//
// Where the context has several render targets (EXT_draw_buffers, WEBGL_draw_buffers), the same pass also writes
// the material's base colour into "base-color", so the lighting can be a full-screen pass instead of drawing the
// scene again: on a CPU rasteriser a pass over a 110k-triangle model costs about 50 ms whatever the size.
#include <tuple>
#include <vector>

#include "frame/EffectEntry.h"
#include "frame/GBufferSettings.h"
#include "gpu/GpuScene.h"

namespace obscura {

class GBufferEffect : public Effect {
 public:
  using Settings = GBufferSettings;  // gbuffer.normals: read by the AO (frame/GBufferSettings.h)
  static constexpr bool kHasSwitch = false;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit GBufferEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;

 private:
  // What a pass writes: the G-buffer, the base colour, or both at once (several render targets).
  enum class Output { GBuffer = 0, BaseColor = 1, Both = 2 };
  void render(const PassContext& context, Output output) const;
  const gl::Program& program(Output output, MaterialKind kind, VertexKind vertex) const;

  bool drawBuffers_;  // the context can write both in one pass (and RendererOptions allows it)
  bool shadingNormals_;  // RendererOptions::gbufferShadingNormals
  // (output, the material kind as that output reads it, the vertex kind)
  ProgramVariants<std::tuple<int, MaterialKind, VertexKind>> programs_;
};

}  // namespace obscura
