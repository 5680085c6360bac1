#include "renderer/EffectTable.h"

#include <set>

#include "effects/ao/AoEffect.h"
#include "effects/auto_exposure/AutoExposureEffect.h"
#include "effects/bloom/BloomEffect.h"
#include "effects/chromatic_aberration/ChromaticAberrationEffect.h"
#include "effects/dither/Dither.h"
#include "effects/dof/DepthOfFieldEffect.h"
#include "effects/edges/EdgesEffect.h"
#include "effects/fog/FogEffect.h"
#include "effects/fxaa/FxaaEffect.h"
#include "effects/gbuffer/GBufferEffect.h"
#include "effects/glare/GlareEffect.h"
#include "effects/grading/ColorGrading.h"
#include "effects/grain/Grain.h"
#include "effects/lens_flare/LensFlareEffect.h"
#include "effects/lighting/LightingEffect.h"
#include "effects/lines/LinesEffect.h"
#include "effects/motion_blur/MotionBlurEffect.h"
#include "effects/resolution/ResolutionEffect.h"
#include "effects/taa/TaaEffect.h"
#include "effects/tonemap/TonemapEffect.h"
#include "effects/transparency/TransparencyEffect.h"
#include "effects/velocity/VelocityEffect.h"
#include "effects/vignette/Vignette.h"
#include "frame/DebugViewPass.h"
#include "frame/Stage.h"

namespace obscura {

// The frame, in order. Adding an effect: a class with info(), programSpecs(), Settings and plan() (docs/
// architecture.md, "Adding an effect"), one shader, and one row here, where it runs.
const std::vector<EffectEntry>& effectTable() {
  static const std::vector<EffectEntry> table = [] {
    std::vector<EffectEntry> rows = {
        EffectEntry::of<GBufferEffect>(),   // scene -> gbuffer (normal + 16-bit depth, own depth buffer)
        EffectEntry::of<VelocityEffect>(),  // scene, gbuffer (and its depth) -> velocity (motion vectors)
        EffectEntry::of<AoEffect>(),        // gbuffer -> ao
        EffectEntry::of<LightingEffect>(),  // scene, ao, the G-buffer's depth -> scene-color (HDR)
        EffectEntry::of<LinesEffect>(),     // scene-color, the G-buffer's depth, points and lines -> scene-color
        EffectEntry::of<FogEffect>(),       // scene-color, gbuffer -> scene-color (HDR)
        // scene-color, the G-buffer's depth, the transparent layer -> scene-color (HDR; blended, transmission)
        EffectEntry::of<TransparencyEffect>(),
        EffectEntry::of<TaaEffect>(),       // scene-color, velocity, gbuffer, history -> scene-color (HDR)
        EffectEntry::of<BloomEffect>(),     // scene-color -> scene-color (HDR, its own chain of 1/2 .. 1/64 targets),
                                            // bloom-bright (its level 2, also alone when read with bloom off)
        EffectEntry::of<LensFlareEffect>(),  // bloom-bright -> lens-light (1/4: ghosts, halo)
        EffectEntry::of<GlareEffect>(),     // bloom-bright, lens-light -> lens-light (1/4: the streaks added)
        EffectEntry::of<DepthOfFieldEffect>(),  // scene-color, gbuffer -> scene-color (HDR: near and far fields)
        EffectEntry::of<AutoExposureEffect>(),  // scene-color, its history -> exposure (1 x 1: the adapted EV)
        EffectEntry::of<TonemapEffect>(),   // scene-color (exposure, lens-light) -> display-color (sRGB, luma in alpha)
        // The display stages, fused into the tone curve's pass: grade the display-referred picture the curve made,
        // then the vignette and the grain on it, and the dithering last, before the 8-bit quantisation (Dither.h).
        EffectEntry::of<GradingEffect>(),   // display-color -> display-color (white balance, CDL, contrast, LUT)
        EffectEntry::of<VignetteEffect>(),  // display-color -> display-color (darker towards the edges)
        EffectEntry::of<GrainEffect>(),     // display-color -> display-color (film grain, new each frame)
        EffectEntry::of<DitherEffect>(),    // display-color -> display-color (triangular noise of one 8-bit step)
        EffectEntry::of<EdgesEffect>(),     // gbuffer, display-color -> display-color (lines; toon bands)
        EffectEntry::of<MotionBlurEffect>(),  // display-color, velocity, gbuffer -> display-color
        EffectEntry::of<ChromaticAberrationEffect>(),  // display-color -> display-color (red and blue fringes)
        EffectEntry::of<FxaaEffect>(),      // display-color -> display-color
        // display-color at the render scale -> the output at its size (only below scale 1; FXAA's pass where it runs)
        EffectEntry::of<ResolutionEffect>(),
    };
    // Names are how everything finds effects, passes and targets: each is used once.
    std::set<std::string> effects, passes, targets;
    for (const EffectEntry& row : rows) {
      if (!effects.insert(row.info.name).second) throw PipelineError("effect '" + row.info.name + "' is listed twice");
      for (const std::string& pass : row.info.passes)
        if (!passes.insert(pass).second) throw PipelineError("pass name '" + pass + "' is used twice");
      for (const TargetInfo& target : row.info.targets)
        if (!targets.insert(target.name).second) throw PipelineError("target '" + target.name + "' is declared twice");
    }
    return rows;
  }();
  return table;
}

const EffectEntry& effectEntry(const std::string& effect) {
  for (const EffectEntry& row : effectTable())
    if (row.info.name == effect) return row;
  throw InputError("unknown effect '" + effect + "'");
}

const std::vector<std::string>& framePassNames() {
  static const std::vector<std::string> names = [] {
    // "pose": the scene's animation, skinning and morphing work before the passes (Renderer::render: evaluating the
    // pose, uploading joint textures and CPU-deformed vertices), timed like a pass.
    std::vector<std::string> out = {"pose"};
    for (const EffectEntry& row : effectTable()) out.insert(out.end(), row.info.passes.begin(), row.info.passes.end());
    out.push_back("view");
    out.push_back("present");
    return out;
  }();
  return names;
}

const std::vector<TargetInfo>& frameTargets() {
  static const std::vector<TargetInfo> targets = [] {
    std::vector<TargetInfo> out;
    for (const EffectEntry& row : effectTable())
      out.insert(out.end(), row.info.targets.begin(), row.info.targets.end());
    return out;
  }();
  return targets;
}

const std::vector<std::string>& frameViewNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out = {"final", "split"};
    for (const TargetInfo& target : frameTargets())
      for (const TargetView& view : target.views) out.push_back(view.name);
    return out;
  }();
  return names;
}

std::vector<ProgramSpec> fusedProgramSpecs() {
  // Every stage variant, in table order, each with the index of its row; and every head.
  std::vector<std::pair<size_t, StageDecl>> stages;
  std::vector<StageHeadSpec> heads;
  for (size_t row = 0; row < effectTable().size(); ++row) {
    for (StageDecl& stage : effectTable()[row].stages()) stages.emplace_back(row, std::move(stage));
    for (auto& head : effectTable()[row].stageHeads()) heads.push_back(std::move(head));
  }
  // The chains: each variant alone, and each pair of stages of two rows that follow each other in colour space with
  // one side at its first variant (every variant of each is then fused beside another stage at least once); and the
  // whole chain, every stage of the table in order at each row's first variant (fog, the tone curve, grading, the
  // vignette, the grain and the dithering in one program), and the display colour's at each row's last (the
  // heaviest) after the tone curve's first.
  std::vector<std::vector<StageDecl>> chains;
  std::vector<StageDecl> firstOfEach, heaviestDisplay;
  for (size_t i = 0; i < stages.size(); ++i) {
    const bool first = i == 0 || stages[i - 1].first != stages[i].first;
    const bool last = i + 1 == stages.size() || stages[i + 1].first != stages[i].first;
    const StageDecl& stage = stages[i].second;
    if (first) firstOfEach.push_back(stage);
    if (first && stage.inputSpace == ColorSpace::Hdr && stage.outputSpace == ColorSpace::Display)
      heaviestDisplay = {stage};
    if (last && stage.inputSpace == ColorSpace::Display && !heaviestDisplay.empty()) heaviestDisplay.push_back(stage);
  }
  chains.push_back(firstOfEach);
  if (heaviestDisplay.size() > 1) chains.push_back(heaviestDisplay);
  for (const auto& [row, stage] : stages) chains.push_back({stage});
  for (size_t a = 0; a < stages.size(); ++a)
    for (size_t b = 0; b < stages.size(); ++b) {
      const auto& [rowA, first] = stages[a];
      const auto& [rowB, second] = stages[b];
      if (rowA >= rowB || first.outputSpace != second.inputSpace) continue;
      const bool firstVariantA = a == 0 || stages[a - 1].first != rowA;
      const bool firstVariantB = b == 0 || stages[b - 1].first != rowB;
      if (firstVariantA || firstVariantB) chains.push_back({first, second});
    }
  std::vector<ProgramSpec> specs;
  for (const std::vector<StageDecl>& chain : chains) {
    specs.push_back(fusedProgram(stagePassHead(chain), chain, chain.front().inputSpace));
    for (const StageHeadSpec& head : heads)
      if (head.space == chain.front().inputSpace) specs.push_back(fusedProgram(head.program, chain, head.space));
  }
  return specs;
}

std::vector<ProgramSpec> frameProgramSpecs() {
  std::vector<ProgramSpec> specs;
  for (const EffectEntry& row : effectTable()) {
    const std::vector<ProgramSpec> list = row.programSpecs();
    specs.insert(specs.end(), list.begin(), list.end());
  }
  const std::vector<ProgramSpec> fused = fusedProgramSpecs();
  specs.insert(specs.end(), fused.begin(), fused.end());
  const std::vector<ProgramSpec> views = DebugViewPass::programSpecs();
  specs.insert(specs.end(), views.begin(), views.end());
  return specs;
}

}  // namespace obscura
