#include "effects/ao/DepthPeelPass.h"

#include <algorithm>

#include "encoding/LinearDepthPacking.h"
#include "gl/PipelineState.h"
#include "gpu/TextureUnits.h"

namespace obscura {
namespace {

ProgramSpec peelSpec(MaterialKind material, VertexKind vertex) {
  // The fragment stage reads the base colour only for the alpha test.
  const MaterialKind kind = material.forAlphaOnly();
  ProgramSpec s{"depth-peel[" + kind.nameSuffix().substr(1) + vertex.nameSuffix() + "]", "lib/geometry.vert",
                "ao/depth_peel.frag", {}};
  for (auto& define : kind.defines()) s.defines.push_back(define);
  for (auto& define : vertex.defines()) s.defines.push_back(define);
  return s;
}

}  // namespace

std::vector<ProgramSpec> DepthPeelPass::programSpecs() {
  std::vector<ProgramSpec> specs;
  for (MaterialKind kind : MaterialKind::all())
    if (kind.forAlphaOnly() == kind) specs.push_back(peelSpec(kind, {}));
  for (VertexKind vertex : VertexKind::validated()) specs.push_back(peelSpec({}, vertex));
  return specs;
}

float DepthPeelPass::separation(const AoSettings& settings, const FrameCamera& camera) {
  return std::max(settings.layerSeparation * settings.radius / (camera.far - camera.near), 2.0f / 65535.0f);
}

std::uint16_t DepthPeelPass::secondLayerCode(std::uint16_t firstCode, const std::vector<float>& crossings,
                                             float separation) {
  const float first = LinearDepthPacking::depthFromCode(firstCode);
  float nearest = 2.0f;
  for (float d : crossings)
    if (!(d < first + separation) && d <= 1.0f) nearest = std::min(nearest, d);  // depth_peel.frag's discard
  return nearest > 1.0f ? LinearDepthPacking::kBackgroundCode : LinearDepthPacking::codeFromDepth(nearest);
}

void DepthPeelPass::render(const PassContext& context, const gl::Texture2D& gbuffer,
                           const AoSettings& settings) const {
  const FrameCamera& camera = context.camera();
  // Nothing behind: depth code 65535, as the G-buffer's background.
  glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
  glClearDepthf(1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const float minSeparation = separation(settings, camera);
  // The G-buffer on a unit the scene's textures leave alone (the base colour, for the alpha test, is on 0).
  constexpr int kGBufferUnit = TextureUnits::kPeeledGBuffer;
  gbuffer.bind(kGBufferUnit);
  GpuScene::DrawOptions options;
  options.bothFaces = true;
  context.drawScene(
      GL_LESS, true,
      [&](MaterialKind kind, VertexKind vertex) -> const gl::Program& {
        const gl::Program& program =
            programs_({kind.forAlphaOnly(), vertex}, [&] { return peelSpec(kind, vertex); });
        program.use();
        program.set("u_projection", camera.projection);
        program.set("u_near", camera.near);
        program.set("u_depthRange", camera.far - camera.near);
        program.set("u_gbuffer", kGBufferUnit);
        program.set("u_minSeparation", minSeparation);
        return program;
      },
      options);
  gl::unbindTextureUnits({kGBufferUnit});
}

}  // namespace obscura
