#include "frame/Stage.h"

#include <algorithm>

#include "frame/PassContext.h"
#include "gl/GlCaps.h"

namespace obscura {
namespace {

ColorSpace finalSpace(const std::vector<StageDecl>& chain, ColorSpace space) {
  return chain.empty() ? space : chain.back().outputSpace;
}

// A full-screen head's draw binds what its chain's stages read: targets of the frame, and textures their effects own.
void readStageTextures(FullscreenDraw& draw, const std::vector<StageDecl>& chain) {
  for (const StageDecl& stage : chain) {
    for (const auto& [sampler, target] : stage.textures) draw.read(sampler, target);
    for (const auto& [sampler, texture] : stage.ownTextures) draw.texture(sampler, texture());
  }
}

}  // namespace

bool chainNeedsPosition(const std::vector<StageDecl>& chain) {
  return std::any_of(chain.begin(), chain.end(), [](const StageDecl& s) { return s.position; });
}

bool chainNeedsNormal(const std::vector<StageDecl>& chain) {
  return std::any_of(chain.begin(), chain.end(), [](const StageDecl& s) { return s.normal; });
}

std::string fusedProgramName(const std::string& head, const std::vector<StageDecl>& chain) {
  std::string name = head;
  for (const StageDecl& stage : chain) name += "+" + stage.label();
  return name;
}

ProgramSpec fusedProgram(const ProgramSpec& head, const std::vector<StageDecl>& chain, ColorSpace space) {
  ProgramSpec spec = head;
  spec.name = fusedProgramName(head.name, chain);
  spec.defines.push_back({"STAGE_OUTPUT_DISPLAY", finalSpace(chain, space) == ColorSpace::Display ? "1" : "0"});
  spec.defines.push_back({"STAGE_POSITION", chainNeedsPosition(chain) ? "1" : "0"});
  spec.defines.push_back({"STAGE_NORMAL", chainNeedsNormal(chain) ? "1" : "0"});
  std::string text = "#include \"lib/precision.glsl\"\n#include \"lib/stage.glsl\"\n";
  for (const StageDecl& stage : chain) {
    for (const auto& define : stage.defines) spec.defines.push_back(define);
    text += "#include \"" + stage.file + "\"\n";
  }
  text += "vec4 finishPixel(vec3 color, StagePixel pixel) {\n";
  for (const StageDecl& stage : chain) text += "  color = " + stage.function + "(color, pixel);\n";
  text += "  return stageOutput(color);\n}\n";
  text += "#include \"" + head.fragmentFile + "\"\n";
  spec.fragmentText = text;
  return spec;
}

ProgramSpec stagePassHead(const std::vector<StageDecl>& chain) {
  const bool gbuffer = chainNeedsPosition(chain) || chainNeedsNormal(chain);
  const bool display = !chain.empty() && chain.front().inputSpace == ColorSpace::Display;
  return ProgramSpec{std::string("stages[") + (display ? "display" : "hdr") + "]",
                     "lib/fullscreen.vert",
                     "frame/stage_pass.frag",
                     {{"STAGE_INPUT_DISPLAY", display ? "1" : "0"}, {"FAR_RAY", gbuffer ? "1" : "0"}}};
}

void setStageUniforms(const gl::Program& program, const std::vector<StageDecl>& chain, const PassContext& context,
                      bool writesOutput) {
  for (const StageDecl& stage : chain)
    if (stage.uniforms) stage.uniforms(program, context);
  if (!chain.empty() && chain.back().outputSpace == ColorSpace::Display)
    program.set("u_lumaInAlpha", writesOutput ? 0.0f : 1.0f);
}

void bindStageTextures(const std::vector<StageDecl>& chain, int firstUnit) {
  int unit = firstUnit;
  for (const StageDecl& stage : chain)
    for (const auto& [sampler, texture] : stage.ownTextures) {
      glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit++));
      glBindTexture(GL_TEXTURE_2D, texture());
    }
  glActiveTexture(GL_TEXTURE0);
}

void unbindStageTextures(const std::vector<StageDecl>& chain, int firstUnit) {
  int unit = firstUnit;
  for (const StageDecl& stage : chain)
    for (size_t k = 0; k < stage.ownTextures.size(); ++k) {
      glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit++));
      glBindTexture(GL_TEXTURE_2D, 0);
    }
  glActiveTexture(GL_TEXTURE0);
}

void setStageSamplers(const gl::Program& program, const std::vector<StageDecl>& chain, int firstUnit) {
  int unit = firstUnit;
  for (const StageDecl& stage : chain)
    for (const auto& [sampler, texture] : stage.ownTextures) program.set(sampler, unit++);
}

PassDecl fullscreenStageHead(const EffectResources& resources, std::string name, ProgramSpec program,
                             std::vector<TextureInput> inputs, PassDecl::Write output, ColorSpace space,
                             int uniformVectors, std::function<void(FullscreenDraw&, const PassContext&)> uniforms) {
  // fullscreenPass's reads, writes and program name; its draw is replaced by one whose program is the fused chain's.
  PassDecl pass = fullscreenPass(std::move(name), program, inputs, output, nullptr);
  StageHead head;
  head.color = output.target;
  head.space = space;
  head.uniformVectors = resources.caps.maxFragmentUniformVectors - uniformVectors;
  head.bindsTextures = true;
  // GLES 2's fragment texture units, less the pass's own inputs.
  head.textureUnits = FragmentLimits::gles2Minimum().textureUnits - static_cast<int>(inputs.size());
  head.pixelGeometry = false;
  pass.stageHead = head;
  pass.run = [program = std::move(program), inputs = std::move(inputs), space,
              uniforms = std::move(uniforms)](PassContext& context) {
    const std::vector<StageDecl>& chain = context.stages();
    const std::string& target = context.stageOutput();
    FullscreenDraw draw(context.program(program.name + context.stagesName(),
                                        [&] { return fusedProgram(program, chain, space); }),
                        context.resources().triangle, &context);
    context.bindForWriting(target);
    for (const TextureInput& input : inputs) draw.read(input.sampler, input.target);
    readStageTextures(draw, chain);
    setStageUniforms(draw.program(), chain, context, context.writesOutput(target));
    if (uniforms) uniforms(draw, context);
    draw.draw();
  };
  return pass;
}

StageDecl displayStage(const std::string& name, int uniformVectors) {
  StageDecl stage;
  stage.name = name;
  stage.file = name + "/" + name + ".glsl";
  stage.function = name + "Stage";
  stage.input = kFinalImageTarget;
  stage.inputSpace = stage.outputSpace = ColorSpace::Display;
  stage.uniformVectors = uniformVectors;
  return stage;
}

PassDecl stagePass(const EffectResources& resources, StageDecl stage, std::string output) {
  PassDecl pass;
  pass.name = stage.name;
  pass.reads = {stage.input};
  if (stage.position || stage.normal) pass.reads.push_back("gbuffer");
  for (const auto& [sampler, target] : stage.textures) pass.reads.push_back(target);
  pass.writes = {output};
  // GLES 2's fragment texture units, less those this stage's pass binds itself: its colour, the G-buffer, its
  // textures.
  const int units =
      FragmentLimits::gles2Minimum().textureUnits - static_cast<int>(pass.reads.size() + stage.ownTextures.size());
  pass.stageHead = StageHead{output, stage.outputSpace,
                             resources.caps.maxFragmentUniformVectors - kStagePassUniformVectors - stage.uniformVectors,
                             true, true, units};
  pass.stage = std::move(stage);
  pass.run = [](PassContext& context) {
    // This stage and those fused after it.
    std::vector<StageDecl> chain = {*context.pass().decl.stage};
    chain.insert(chain.end(), context.stages().begin(), context.stages().end());
    const ProgramSpec head = stagePassHead(chain);
    const std::string& target = context.stageOutput();
    const bool gbuffer = chainNeedsPosition(chain) || chainNeedsNormal(chain);
    FullscreenDraw draw(context.program(fusedProgramName(head.name, chain),
                                        [&] { return fusedProgram(head, chain, chain.front().inputSpace); }),
                        context.resources().triangle, &context);
    context.bindForWriting(target);
    draw.read("u_color", chain.front().input);
    if (gbuffer) {
      draw.read("u_gbuffer", "gbuffer");
      setReconstruction(draw.program(), context.camera().reconstruction);
    }
    readStageTextures(draw, chain);
    setStageUniforms(draw.program(), chain, context, context.writesOutput(target));
    draw.draw();
  };
  return pass;
}

}  // namespace obscura
