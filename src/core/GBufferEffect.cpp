#include "core/GBufferEffect.h"

#include "core/LinearDepthPacking.h"
#include "core/NormalEncoding.h"
#include "core/PassContext.h"
#include "gl/PipelineState.h"

namespace obscura {

EffectInfo GBufferEffect::info() {
  return {"gbuffer",
          "G-buffer",
          false,
          false,
          {"gbuffer"},
          {{"gbuffer",
            "RG: octahedral view-space normal (254 steps); BA: 16-bit linear depth, high byte in B (65535: background)",
            GL_NEAREST,
            {{"normals", ViewDecoding::Normals}, {"depth", ViewDecoding::Depth}, {"mask", ViewDecoding::Mask}}}}};
}

std::vector<ProgramSpec> GBufferEffect::programSpecs() {
  return {ProgramSpec{"gbuffer", "geometry.vert", "gbuffer.frag", {}, {}}};
}

GBufferEffect::GBufferEffect(const EffectResources& resources)
    : program_(resources.build(programSpecs().front())),
      geometry_(program_),
      projection_(program_.uniform("u_projection")),
      near_(program_.uniform("u_near")),
      depthRange_(program_.uniform("u_depthRange")) {}

void GBufferEffect::plan(FramePlanner& planner) {
  PassDecl pass;
  pass.name = "gbuffer";
  pass.writes = {{"gbuffer", TargetSize::full(), PassDecl::Write::Depth::Own, ""}};
  pass.run = [this](PassContext& context) { render(context); };
  planner.add(std::move(pass));
}

void GBufferEffect::render(const PassContext& context) const {
  const FrameCamera& camera = context.camera();
  context.bindForWriting("gbuffer");
  // Background: normal (0, 0, 1) and depth code 65535. A channel of 1.0 stores byte 255.
  const auto normal = encodeNormal(glm::vec3(0.0f, 0.0f, 1.0f));
  glClearColor(LinearDepthPacking::channelFromByte(normal[0]), LinearDepthPacking::channelFromByte(normal[1]), 1.0f,
               1.0f);
  glClearDepthf(1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);

  program_.use();
  gl::Program::set(projection_, camera.projection);
  gl::Program::set(near_, camera.near);
  gl::Program::set(depthRange_, camera.far - camera.near);
  context.scene().draw(geometry_, camera.view);
  gl::restoreBaselineState();
}

}  // namespace obscura
