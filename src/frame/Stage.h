#pragma once
// Per-pixel stages: the work of an effect that maps one pixel's colour from that pixel's own inputs (its colour, its
// view-space position and normal, its uv) and the frame's constants: fog, exposure and the tone curve. On a weak GPU
// a full-screen pass is the unit of cost, so such work does not take a pass of its own where it can run inside the
// pass before it: the plan fuses a stage into the pass that writes the colour it reads when nothing else reads that
// colour (frame/FramePlan.h, rule 4b), stage after stage, and the fused program skips the HDR encode and decode
// between them. The lighting takes stages (its forms' programs call finishPixel); so does a stage pass that runs
// alone, for the stages after it, and any full-screen pass declared with fullscreenStageHead (bloom's and depth of
// field's composites). pmndrs/postprocessing's EffectPass merges its effects' mainImage functions the same
// way at run time; here the chains come from the table, and each is a program built once, on first use.
//
// A stage is a folder's worth of code like any effect: its GLSL file (shaders_es2/NAME/NAME.glsl) defines
//   vec3 FUNCTION(vec3 color, StagePixel pixel)     (lib/stage.glsl: StagePixel holds uv, position, normal)
// and its uniforms, named after it (u_fogColor), as are its defines (FOG_MODE). Its effect declares the pass with
// stagePass() in plan(), with the function that sets its uniforms each frame, and lists its variants in stages() for
// the shader checks. The fused program is generated (fusedProgram): the head's defines and every stage's, the stages'
// files, and
//   vec4 finishPixel(vec3 color, StagePixel pixel) { color = fogStage(color, pixel); ...; return stageOutput(color); }
// before the head's own fragment file, whose main calls finishPixel. stageOutput encodes the chain's last colour:
// HDR (lib/hdr.glsl) or display colour with its luma in alpha (FXAA's input) or 1 (the output framebuffer).
//
// Programs: a head's program for each chain that fuses into it, built the first time a plan fuses that chain
// (docs/architecture.md counts them).
#include <functional>
#include <string>
#include <vector>

#include "frame/EffectEntry.h"
#include "frame/FullscreenPass.h"
#include "gl/ShaderLibrary.h"

namespace obscura {

class PassContext;

// The fragment uniform vectors a stand-alone stage pass takes itself (the depth-to-ray scale, the luma switch).
inline constexpr int kStagePassUniformVectors = 2;

// The pass of a stage that reads `stage.input` and writes `output`: where nothing takes it, a full-screen pass
// (shaders_es2/frame/stage_pass.frag) that decodes its colour, runs the chain (it and the stages fused after it)
// and encodes the result. It reads the G-buffer too where the stage needs its pixel's position or normal.
PassDecl stagePass(const EffectResources& resources, StageDecl stage, std::string output);

// A full-screen pass that offers the stages after it (fullscreenPass's arguments, frame/FullscreenPass.h): its
// fragment file's main hands its colour, in `space`, to finishPixel(color, stagePixel(v_uv)) instead of encoding it,
// and its program is fusedProgram(program, the fused chain, space), which with no stage encodes the colour as the
// pass did (stageOutput). `uniformVectors`: the fragment uniform vectors its own program takes; the rest, and the
// texture units its inputs leave, are the stages'. It gives no position or normal (StageHead::pixelGeometry).
PassDecl fullscreenStageHead(const EffectResources& resources, std::string name, ProgramSpec program,
                             std::vector<TextureInput> inputs, PassDecl::Write output, ColorSpace space,
                             int uniformVectors, std::function<void(FullscreenDraw&, const PassContext&)> uniforms);

// A stage on the frame's display colour (kFinalImageTarget, after the tone curve), reading and writing it: the
// effect `name`'s function `nameStage` in shaders_es2/name/name.glsl, whose uniforms take `uniformVectors` fragment
// uniform vectors (grading, the vignette, grain, dithering). The caller adds its variant, defines and uniforms.
StageDecl displayStage(const std::string& name, int uniformVectors);

// The program of `head` (a vertex file, a fragment file whose main calls finishPixel, its defines) running `chain`
// after a colour in `space`. Its name lists them: "lighting[deferred,atlas]+fog[exp]+tonemap[neutral]".
ProgramSpec fusedProgram(const ProgramSpec& head, const std::vector<StageDecl>& chain, ColorSpace space);
// The name fusedProgram gives, without building the text (a program cache's key).
std::string fusedProgramName(const std::string& head, const std::vector<StageDecl>& chain);
// The stand-alone stage pass's head for a chain (its first stage's input space; the G-buffer when a stage needs it).
ProgramSpec stagePassHead(const std::vector<StageDecl>& chain);
// Sets the chain's uniforms on the program in use: every stage's, and the output encoding's (writing the output
// framebuffer or not).
void setStageUniforms(const gl::Program& program, const std::vector<StageDecl>& chain, const PassContext& context,
                      bool writesOutput);
// For a head that binds its stages' own textures itself (StageDecl::ownTextures; the lighting): binds them to units
// firstUnit, firstUnit + 1, ... (unit 0 active again after), and sets their samplers on a program in use. The head
// unbinds them with the rest of its textures (unbindStageTextures, or gl::restoreBaselineState).
void bindStageTextures(const std::vector<StageDecl>& chain, int firstUnit);
void unbindStageTextures(const std::vector<StageDecl>& chain, int firstUnit);
void setStageSamplers(const gl::Program& program, const std::vector<StageDecl>& chain, int firstUnit);
// Whether some stage of the chain needs its pixel's position, or its normal.
bool chainNeedsPosition(const std::vector<StageDecl>& chain);
bool chainNeedsNormal(const std::vector<StageDecl>& chain);

}  // namespace obscura
