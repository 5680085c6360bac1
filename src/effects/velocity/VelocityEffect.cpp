#include "effects/velocity/VelocityEffect.h"

#include "frame/FramePlan.h"
#include "frame/PassContext.h"
#include "gl/PipelineState.h"

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

VelocityEffect::GeometryVariant::GeometryVariant(gl::Program built)
    : program(std::move(built)),
      geometry(program),
      projection(program.uniform("u_projection")),
      unjitteredProjection(program.uniform("u_unjitteredProjection")),
      previousViewProjection(program.uniform("u_previousViewProjection")) {}

const VelocityEffect::GeometryVariant& VelocityEffect::variant(MaterialKind material, VertexKind vertex) {
  const auto key = std::make_tuple(material.forAlphaOnly(), vertex);
  auto it = variants_.find(key);
  if (it == variants_.end())
    it = variants_.emplace(key, GeometryVariant(resources_.build(geometrySpec(material, vertex)))).first;
  return it->second;
}

VelocityEffect::VelocityEffect(const EffectResources& resources) : resources_(resources) {
  camera_.program = resources_.build(cameraSpec());
  camera_.reconstruction = ReconstructionUniforms(camera_.program);
  camera_.gbuffer = camera_.program.uniform("u_gbuffer");
  camera_.unjitteredProjection = camera_.program.uniform("u_unjitteredProjection");
  camera_.viewToPreviousClip = camera_.program.uniform("u_viewToPreviousClip");
  // The geometry variants are built on first use, as the G-buffer's are (GBufferEffect.cpp).
}

void VelocityEffect::plan(FramePlanner& planner) {
  using Write = PassDecl::Write;
  PassDecl pass;
  pass.name = "velocity";
  pass.reads = {"gbuffer"};
  pass.writes = {{"velocity", TargetSize::full(), Write::Depth::Shared, "gbuffer"}};
  pass.run = [this](PassContext& context) { render(context); };
  planner.add(std::move(pass));
}

void VelocityEffect::render(const PassContext& context) {
  using gl::Program;
  const FrameCamera& camera = context.camera();
  const FrameCamera& previous = context.frame().previousCamera;
  const glm::mat4 previousViewProjection = previous.unjitteredProjection * previous.view;
  context.bindForWriting("velocity");

  // 1. The camera's motion everywhere, from depth.
  camera_.program.use();
  camera_.reconstruction.set(camera.reconstruction);
  context.texture("gbuffer").bind(0);
  Program::set(camera_.gbuffer, 0);
  Program::set(camera_.unjitteredProjection, camera.unjitteredProjection);
  Program::set(camera_.viewToPreviousClip, previousViewProjection * glm::inverse(camera.view));
  resources_.triangle.draw();

  // 2. What moves, over it, where it is the visible surface.
  GpuScene::DrawOptions options;
  options.onlyMoving = !resources_.options.velocityDrawsEverything;
  if (context.sharesDepth("velocity") && (!options.onlyMoving || context.scene().anyMoving())) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    context.scene().draw(
        camera.view,
        [&](MaterialKind kind, VertexKind vertex) -> const GeometryUniforms& {
          const GeometryVariant& v = variant(kind, vertex);
          v.program.use();
          Program::set(v.projection, camera.projection);
          Program::set(v.unjitteredProjection, camera.unjitteredProjection);
          Program::set(v.previousViewProjection, previousViewProjection);
          return v.geometry;
        },
        options);
  }
  gl::restoreBaselineState();
}

}  // namespace obscura
