#include "effects/lines/LinesEffect.h"

#include <algorithm>
#include <cmath>

#include "frame/PassContext.h"

namespace obscura {
namespace {

// Desktop GL (OSMesa) takes gl_PointSize only with GL_VERTEX_PROGRAM_POINT_SIZE on; GLES 2 and WebGL always do.
constexpr GLenum kVertexProgramPointSize = 0x8642;

ProgramSpec copySpec() {
  return ProgramSpec{"lines[copy]", "lib/fullscreen.vert", "lines/lines.frag",
                     {{"LINES_COPY", "1"}, {"FAR_RAY", "0"}}, {}};
}
ProgramSpec linesSpec() {
  return ProgramSpec{"lines", "lines/lines.vert", "lines/lines.frag", {{"LINES_COPY", "0"}}, {}};
}

}  // namespace

EffectInfo LinesEffect::info() { return {"lines", "Points and lines", false, false, {"lines"}, {}}; }

std::vector<ProgramSpec> LinesEffect::programSpecs() { return {copySpec(), linesSpec()}; }

LinesEffect::LinesEffect(const EffectResources& resources) : resources_(resources) {
  GLfloat range[2] = {1.0f, 1.0f};
  glGetFloatv(GL_ALIASED_POINT_SIZE_RANGE, range);
  maxPointSize_ = std::max(1.0f, range[1]);
}

void LinesEffect::plan(FramePlanner& planner) {
  if (!planner.frame().linesOrPoints) return;
  using Write = PassDecl::Write;
  PassDecl pass;
  pass.name = "lines";
  pass.reads = {"scene-color", "gbuffer"};
  pass.writes = {{"scene-color", TargetSize::full(), Write::Depth::Shared, "gbuffer"}};
  pass.programs = {copySpec().name, linesSpec().name};
  pass.run = [this](PassContext& context) { run(context); };
  planner.add(std::move(pass));
}

void LinesEffect::run(const PassContext& context) const {
  context.draw(copySpec(), "scene-color").read("u_color", "scene-color").draw();

  // Without the G-buffer's depth (the plan's fallback), nothing hides them: the target's own depth starts clear.
  if (!context.sharesDepth("scene-color")) glClear(GL_DEPTH_BUFFER_BIT);
  context.drawDepthTested(GL_LEQUAL, false, [&] { drawLines(context); });
}

void LinesEffect::drawLines(const PassContext& context) const {
  if (resources_.caps.desktopGl) glEnable(kVertexProgramPointSize);
  const gl::Program& lines = context.program(linesSpec());
  lines.use();
  const FrameCamera& camera = context.camera();
  const float pointSize = std::clamp(std::round(static_cast<float>(context.size("scene-color").y) / 360.0f), 1.0f,
                                     maxPointSize_);
  lines.set("u_pointSize", pointSize);
  // The per-draw matrix and the attributes by location (GpuLines sets them for every piece). The attributes are
  // looked up each frame, not kept: the program may be a rehearsal's stand-in (ProgramCache::Rehearsal), whose GL
  // name a later program may take once it is deleted (a lookup is a name in the program's table: no round trip).
  const GLint position = glGetAttribLocation(lines.id(), "a_position");
  const GLint color = glGetAttribLocation(lines.id(), "a_color");
  const GLint modelViewProjection = lines.uniform("u_modelViewProjection");
  const glm::mat4 viewProjection = camera.projection * camera.view;
  context.scene().lines().draw(viewProjection, false, modelViewProjection, position, color);
  context.scene().lines().draw(viewProjection, true, modelViewProjection, position, color);
  if (resources_.caps.desktopGl) glDisable(kVertexProgramPointSize);
}

}  // namespace obscura
