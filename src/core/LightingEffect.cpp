#include "core/LightingEffect.h"

#include <glm/geometric.hpp>

#include "core/HdrEncoding.h"
#include "core/LinearDepthPacking.h"
#include "core/PassContext.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

ProgramSpec spec(bool countShading) {
  return ProgramSpec{countShading ? "lighting[count-shading]" : "lighting",
                     "geometry.vert",
                     "lighting.frag",
                     {{"COUNT_SHADING", countShading ? "1" : "0"}},
                     {}};
}

}  // namespace

EffectInfo LightingEffect::info() {
  return {"lighting",
          "Lighting",
          false,
          false,
          {"lighting", "shading-count"},
          {{"scene-color", "linear HDR colour in the RGBA8 encoding of lib/hdr.glsl (" + kHdrColorEncoding.name() +
                                ", core/HdrEncoding.h): fetch NEAREST, decode, then filter",
            GL_NEAREST,
            {{"scene-color", ViewDecoding::HdrColor}}},
           {"shading-count", "R: fragments the lighting pass shaded at this pixel, / 255 (diagnostic)", GL_NEAREST,
            {{"shading-count", ViewDecoding::Count}}}}};
}

std::vector<ProgramSpec> LightingEffect::programSpecs() { return {spec(false), spec(true)}; }

LightingEffect::Variant::Variant(gl::Program built)
    : program(std::move(built)),
      geometry(program),
      projection(program.uniform("u_projection")),
      lightDirection(program.optionalUniform("u_lightDirection")),
      viewUp(program.optionalUniform("u_viewUp")),
      lightColor(program.optionalUniform("u_lightColor")),
      skyColor(program.optionalUniform("u_skyColor")),
      groundColor(program.optionalUniform("u_groundColor")),
      ao(program.optionalUniform("u_ao")) {}

LightingEffect::LightingEffect(const EffectResources& resources)
    : shade_(resources.build(spec(false))),
      countShading_(resources.build(spec(true))),
      white_(1, 1, GL_NEAREST, std::vector<std::uint8_t>{255, 255, 255, 255}.data()),
      stencil_(resources.caps.packedDepthStencil) {
  // The lit program uses every uniform: resolve them strictly there (the counting one has none of the lights).
  for (const char* name : {"u_lightDirection", "u_viewUp", "u_lightColor", "u_skyColor", "u_groundColor", "u_ao"})
    shade_.program.uniform(name);
}

void LightingEffect::plan(FramePlanner& planner) {
  const bool withAo = planner.settings().ao().enabled;
  // The counting pass is planned only for its view, beside the lit pass (which that view's plan then drops). It
  // has the lit pass's reads, so the plan, and with it the depth set-up, is the one the lit pass would have.
  for (const char* output : {"scene-color", "shading-count"}) {
    const bool counting = std::string(output) == "shading-count";
    if (counting && planner.viewTarget() != output) continue;
    PassDecl pass;
    pass.name = counting ? "shading-count" : "lighting";
    if (withAo) pass.reads = {"ao"};
    pass.optionalReads = {"gbuffer"};  // its depth, when the G-buffer pass runs anyway
    pass.writes = {{output, TargetSize::full(), PassDecl::Write::Depth::Shared, "gbuffer"}};
    pass.run = [this, output](PassContext& context) { render(context, output); };
    planner.add(std::move(pass));
  }
}

void LightingEffect::render(const PassContext& context, const std::string& output) const {
  using gl::Program;
  const FrameCamera& camera = context.camera();
  const bool counting = output == "shading-count";
  const Variant& v = counting ? countShading_ : shade_;
  context.bindForWriting(output);

  if (counting) {
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  } else {
    // Where no geometry is, the background's radiance, encoded as the lit pixels are.
    const std::array<std::uint8_t, 4> background = encodeHdr(light_.background);
    glClearColor(LinearDepthPacking::channelFromByte(background[0]), LinearDepthPacking::channelFromByte(background[1]),
                 LinearDepthPacking::channelFromByte(background[2]), LinearDepthPacking::channelFromByte(background[3]));
  }
  glEnable(GL_DEPTH_TEST);
  if (context.sharesDepth(output) && stencil_) {
    // The G-buffer's depth holds each pixel's nearest surface: GL_EQUAL lets only that surface's fragments through,
    // and the stencil (0, set to 1 by the first that passes) only the first of them. A coplanar or edge-on face at
    // exactly that depth is not shaded again: GL_EQUAL alone would shade it too (the shading-count test caught it at
    // the edges of the built-in scene's boxes).
    glClearStencil(0);
    glClear(GL_COLOR_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 0, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
  } else if (context.sharesDepth(output)) {
    // Without a stencil buffer: GL_LESS against that depth pulled one resolvable step towards the camera, writing
    // depth, so a later fragment of the same depth fails. Faces seen exactly edge-on may still shade a pixel twice
    // (a hidden one within that step, drawn first); the visible surface, drawn after, still wins.
    glClear(GL_COLOR_BUFFER_BIT);
    glDepthFunc(GL_LESS);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0.0f, -1.0f);
  } else {
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDepthFunc(GL_LESS);
  }
  if (counting) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
  }

  v.program.use();
  Program::set(v.projection, camera.projection);
  if (!counting) {
    const glm::mat3 viewRotation(camera.view);
    Program::set(v.lightDirection, glm::normalize(viewRotation * light_.directionToLight));
    Program::set(v.viewUp, viewRotation * glm::vec3(0.0f, 1.0f, 0.0f));
    Program::set(v.lightColor, light_.lightColor);
    Program::set(v.skyColor, light_.skyColor);
    Program::set(v.groundColor, light_.groundColor);
    (context.has("ao") ? context.texture("ao") : white_).bind(1);
    Program::set(v.ao, 1);
  }
  context.scene().draw(v.geometry, camera.view);
  gl::restoreBaselineState();
}

}  // namespace obscura
