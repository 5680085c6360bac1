#include "effects/velocity/VelocityEffect.h"

#include "frame/FramePlan.h"
#include "frame/PassContext.h"

namespace obscura {

EffectInfo VelocityEffect::info() {
  return {"velocity",
          "Motion vectors",
          false,
          false,
          {"velocity"},
          {{"velocity",
            "RG: x, BA: y of the screen-space motion since the previous frame in uv units (y up), each a 16-bit code "
            "round(v * 32767) + 32768, high byte first (encoding/VelocityPacking.h)",
            GL_NEAREST,
            {{"velocity", ViewDecoding::Velocity}}}}};
}

namespace {

ProgramSpec cameraSpec() {
  return {"velocity[camera]", "lib/fullscreen.vert", "velocity/velocity.frag",
          {{"VELOCITY_CAMERA", "1"}, {"FAR_RAY", "1"}}};
}

ProgramSpec geometrySpec(MaterialKind material, VertexKind vertex) {
  // The fragment stage reads the base colour only for the alpha test.
  const MaterialKind kind = material.forAlphaOnly();
  ProgramSpec s{"velocity[geometry" + kind.nameSuffix() + vertex.nameSuffix() + "]", "lib/geometry.vert",
                "velocity/velocity.frag", {{"VELOCITY_CAMERA", "0"}, {"PREVIOUS", "1"}}};
  for (auto& define : kind.defines()) s.defines.push_back(define);
  for (auto& define : vertex.defines()) s.defines.push_back(define);
  return s;
}

}  // namespace

std::vector<ProgramSpec> VelocityEffect::programSpecs() {
  std::vector<ProgramSpec> specs = {cameraSpec()};
  for (MaterialKind kind : MaterialKind::all())
    if (kind.forAlphaOnly() == kind) specs.push_back(geometrySpec(kind, {}));
  for (VertexKind vertex : VertexKind::validated()) specs.push_back(geometrySpec({}, vertex));
  return specs;
}

VelocityEffect::VelocityEffect(const EffectResources& resources)
    : resources_(resources),
      geometry_(resources.programs) {
  // The camera's program is built now, so a broken one fails when the renderer is made; the geometry variants on
  // first use, as the G-buffer's are (GBufferEffect.cpp).
  resources_.program(cameraSpec());
}

void VelocityEffect::plan(FramePlanner& planner) {
  using Write = PassDecl::Write;
  PassDecl pass;
  pass.name = "velocity";
  pass.reads = {"gbuffer"};
  pass.writes = {{"velocity", TargetSize::full(), Write::Depth::Shared, "gbuffer"}};
  pass.programs = {cameraSpec().name};
  pass.run = [this](PassContext& context) { render(context); };
  planner.add(std::move(pass));
}

void VelocityEffect::render(const PassContext& context) {
  const FrameCamera& camera = context.camera();
  const FrameCamera& previous = context.frame().previousCamera;
  const glm::mat4 previousViewProjection = previous.unjitteredProjection * previous.view;

  {  // 1. The camera's motion everywhere, from depth.
    FullscreenDraw draw = context.draw(cameraSpec(), "velocity");
    draw.read("u_gbuffer", "gbuffer");
    setReconstruction(draw.program(), camera.reconstruction);
    draw.set("u_unjitteredProjection", camera.unjitteredProjection);
    draw.set("u_viewToPreviousClip", previousViewProjection * glm::inverse(camera.view));
    draw.draw();
  }

  // 2. What moves, over it, where it is the visible surface.
  GpuScene::DrawOptions options;
  options.onlyMoving = !resources_.options.velocityDrawsEverything;
  if (context.sharesDepth("velocity") && (!options.onlyMoving || context.scene().anyMoving())) {
    context.drawScene(
        GL_LEQUAL, false,
        [&](MaterialKind kind, VertexKind vertex) -> const gl::Program& {
          const gl::Program& program =
              geometry_({kind.forAlphaOnly(), vertex}, [&] { return geometrySpec(kind, vertex); });
          program.use();
          program.set("u_projection", camera.projection);
          program.set("u_unjitteredProjection", camera.unjitteredProjection);
          program.set("u_previousViewProjection", previousViewProjection);
          return program;
        },
        options);
  }
}

}  // namespace obscura
