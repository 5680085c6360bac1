#include "effects/gbuffer/GBufferEffect.h"

#include "encoding/LinearDepthPacking.h"
#include "encoding/NormalEncoding.h"
#include "frame/PassContext.h"

namespace obscura {

EffectInfo GBufferEffect::info() {
  return {"gbuffer",
          "G-buffer",
          false,
          false,
          {"gbuffer", "base-color"},
          {{"gbuffer",
            "RG: octahedral view-space normal (254 steps); BA: 16-bit linear depth, high byte in B (65535: background)",
            GL_NEAREST,
            {{"normals", ViewDecoding::Normals},
             {"normals-from-depth", ViewDecoding::NormalsFromDepth},
             {"depth", ViewDecoding::Depth},
             {"mask", ViewDecoding::Mask}}},
           {"base-color",
            "RGB: the material's base colour (factor x texture), sRGB-encoded; A: 1. Written beside the G-buffer where "
            "there are several render targets (the deferred lighting reads it); background undefined",
            GL_NEAREST,
            {{"base-color", ViewDecoding::Color}}}}};
}

namespace {

// The G-buffer alone reads the base colour only for the alpha test, and the other textures only for the shading
// normal (RendererOptions::gbufferShadingNormals).
MaterialKind readKind(int output, MaterialKind kind, bool shadingNormals) {
  if (output != 0) return kind;
  MaterialKind read = kind.forAlphaOnly();
  read.pbr = shadingNormals && kind.pbr;
  return read;
}

ProgramSpec spec(int output, MaterialKind kind, VertexKind vertex, bool shadingNormals) {
  static const char* outputs[] = {"gbuffer", "base-color", "gbuffer+base-color"};
  const bool shading = shadingNormals && kind.pbr && output != 1;
  ProgramSpec s{"gbuffer[" + std::string(outputs[output]) + kind.nameSuffix() + vertex.nameSuffix() +
                    (shading ? ",shading-normal" : "") + "]",
                "lib/geometry.vert", "gbuffer/gbuffer.frag",
                {{"GBUFFER_OUTPUT", std::to_string(output)}, {"GBUFFER_SHADING_NORMAL", shading ? "1" : "0"}}};
  for (auto& define : kind.defines()) s.defines.push_back(define);
  for (auto& define : vertex.defines()) s.defines.push_back(define);
  if (output == 2) s.extensions = {"GL_EXT_draw_buffers"};
  return s;
}

}  // namespace

std::vector<ProgramSpec> GBufferEffect::programSpecs() {
  std::vector<ProgramSpec> specs;
  for (bool shadingNormals : {false, true})
    for (int output = 0; output < 3; ++output)
      for (MaterialKind kind : MaterialKind::all())
        if (readKind(output, kind, shadingNormals) == kind && (!shadingNormals || kind.pbr))
          specs.push_back(spec(output, kind, {}, shadingNormals));
  for (VertexKind vertex : VertexKind::validated()) specs.push_back(spec(0, {}, vertex, false));
  return specs;
}

GBufferEffect::GBufferEffect(const EffectResources& resources)
    : drawBuffers_(resources.caps.drawBuffers && resources.options.allowDrawBuffers),
      shadingNormals_(resources.options.gbufferShadingNormals),
      programs_(resources.programs) {
  // Every variant is built on first use: the material kinds a scene has. Building all eight here cost the page's
  // start-up a program each (docs/resolution.md, "Start-up"); the shader tests build every variant
  // (Shaders.EveryVariantCompilesAndLinks), so a broken one still fails there.
}

const gl::Program& GBufferEffect::program(Output output, MaterialKind kind, VertexKind vertex) const {
  const int o = static_cast<int>(output);
  const MaterialKind read = readKind(o, kind, shadingNormals_);
  const VertexKind stage = vertex.forCurrentFrame();
  return programs_({o, read, stage}, [&] { return spec(o, read, stage, shadingNormals_); });
}

void GBufferEffect::plan(FramePlanner& planner) {
  using Write = PassDecl::Write;
  PassDecl pass;
  pass.name = "gbuffer";
  pass.writes = {{"gbuffer", TargetSize::full(), Write::Depth::Own, ""}};
  // The base colour beside the G-buffer, for the deferred lighting, unless the scene's materials need more than it
  // carries (effects/lighting/LightingEffect.h).
  const bool both = drawBuffers_ && !planner.frame().forwardLighting;
  if (both) pass.writes.push_back({"base-color", TargetSize::full(), Write::Depth::None, ""});
  const Output output = both ? Output::Both : Output::GBuffer;
  pass.run = [this, output](PassContext& context) { render(context, output); };
  planner.add(std::move(pass));
  // Otherwise the base colour has a pass of its own, for its view only.
  if (!both && planner.viewTarget() == "base-color") {
    PassDecl base;
    base.name = "base-color";
    base.writes = {{"base-color", TargetSize::full(), Write::Depth::Own, ""}};
    base.run = [this](PassContext& context) { render(context, Output::BaseColor); };
    planner.add(std::move(base));
  }
}

void GBufferEffect::render(const PassContext& context, Output output) const {
  const FrameCamera& camera = context.camera();
  if (output == Output::Both) context.bindForWriting(std::vector<std::string>{"gbuffer", "base-color"});
  else context.bindForWriting(output == Output::GBuffer ? "gbuffer" : "base-color");
  // Background: normal (0, 0, 1) and depth code 65535. A channel of 1.0 stores byte 255.
  // (With several render targets the base colour is cleared to the same bytes: the background is not read there.)
  const auto normal = encodeNormal(glm::vec3(0.0f, 0.0f, 1.0f));
  if (output == Output::BaseColor) glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  else glClearColor(LinearDepthPacking::channelFromByte(normal[0]), LinearDepthPacking::channelFromByte(normal[1]),
                    1.0f, 1.0f);
  glClearDepthf(1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  context.drawScene(GL_LESS, true, [&](MaterialKind kind, VertexKind vertex) -> const gl::Program& {
    const gl::Program& p = program(output, kind, vertex);
    p.use();
    p.set("u_projection", camera.projection);
    if (output != Output::BaseColor) {  // the base colour alone computes no depth
      p.set("u_near", camera.near);
      p.set("u_depthRange", camera.far - camera.near);
    }
    return p;
  });
}

}  // namespace obscura
