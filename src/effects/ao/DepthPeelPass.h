#pragma once
// The AO's second depth layer (ao.layers 2): depth peeling under GLES 2 with a minimum separation. The scene is drawn
// again, front and back faces alike, into a target of its own with its own depth buffer; a fragment survives only
// where it lies at least the separation behind the G-buffer's depth at its pixel (shaders_es2/ao/depth_peel.frag),
// so the depth test keeps, per pixel, the nearest surface behind the visible one: for a closed occluder, its back
// face. Everitt, "Interactive Order-Independent Transparency" (NVIDIA 2001) for peeling with a depth texture; Mara,
// McGuire, Nowrouzezahrai, Luebke, "Deep G-Buffers for Stable Global Illumination Approximation" (HPG 2016), sec. 3,
// for the minimum separation, which keeps the visible surface (its own fragments, within a depth code of the stored
// depth) and surfaces just behind it out of the second layer.
//
// Output (the "second-layer" target): BA = the second layer's 16-bit linear depth (the G-buffer's packing), 65535
// where nothing lies behind; RG unused (255). The depth hierarchy folds it into its texels' RG, so the estimator reads
// both layers in one fetch per tap (effects/ao/DepthHierarchyPass.h); without a hierarchy (or for taps that read the
// G-buffer, with the separate-texture or mip-chain storages) the estimator reads this target beside the G-buffer.
#include <cstdint>
#include <utility>
#include <vector>

#include "effects/ao/AoSettings.h"
#include "frame/EffectEntry.h"
#include "frame/PassContext.h"
#include "gpu/GpuScene.h"

namespace obscura {

class DepthPeelPass {
 public:
  static std::vector<ProgramSpec> programSpecs();
  // The minimum separation in linear depth (units of far - near): settings.layerSeparation r, and at least two depth
  // codes, so the visible surface drawn again (within half a code of its stored depth) never passes.
  static float separation(const AoSettings& settings, const FrameCamera& camera);
  // The CPU mirror of the peel at one pixel: the second layer's depth code, given the first layer's stored code and
  // the linear depths of every surface the pixel's ray crosses, front or back face (`crossings`): the nearest not less
  // than `separation` behind the first; the background code where there is none.
  static std::uint16_t secondLayerCode(std::uint16_t firstCode, const std::vector<float>& crossings,
                                       float separation);
  explicit DepthPeelPass(const EffectResources& resources) : programs_(resources.programs) {}
  // Draws the second layer into the bound framebuffer (with its own depth buffer), reading the first from `gbuffer`.
  void render(const PassContext& context, const gl::Texture2D& gbuffer, const AoSettings& settings) const;

 private:
  ProgramVariants<std::pair<MaterialKind, VertexKind>> programs_;  // per material (its alpha test) and vertex kind
};

}  // namespace obscura
