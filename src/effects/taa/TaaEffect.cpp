#include "effects/taa/TaaEffect.h"

#include <algorithm>
#include <cmath>

#include "frame/PassContext.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

ProgramSpec resolveSpec() {
  return {"taa[resolve]", "lib/fullscreen.vert", "taa/taa.frag", {{"TAA_STAGE", "0"}, {"FAR_RAY", "1"}}};
}
ProgramSpec outputSpec(bool sharpen) {
  return {std::string("taa[output") + (sharpen ? ",sharpen" : "") + "]",
          "lib/fullscreen.vert",
          "taa/taa.frag",
          {{"TAA_STAGE", "1"}, {"TAA_SHARPEN", sharpen ? "1" : "0"}, {"FAR_RAY", "0"}}};
}
ProgramSpec depthSpec() {
  return {"taa[depth]", "lib/fullscreen.vert", "taa/taa.frag", {{"TAA_STAGE", "2"}, {"FAR_RAY", "0"}}};
}

}  // namespace

glm::vec3 taaToYCoCg(const glm::vec3& c) {
  return {0.25f * c.r + 0.5f * c.g + 0.25f * c.b, 0.5f * c.r - 0.5f * c.b, -0.25f * c.r + 0.5f * c.g - 0.25f * c.b};
}

glm::vec3 taaFromYCoCg(const glm::vec3& c) { return {c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z}; }

glm::vec3 taaToneWeight(const glm::vec3& ycocg) { return ycocg / (1.0f + std::max(ycocg.x, 0.0f)); }

glm::vec3 taaToneUnweight(const glm::vec3& t) { return t / std::max(1.0f - t.x, 1.0f / 65536.0f); }

glm::vec3 taaClipTowardsMean(const glm::vec3& history, const glm::vec3& mean, const glm::vec3& extent) {
  const glm::vec3 offset = history - mean;
  const glm::vec3 units = glm::abs(offset) / glm::max(extent, glm::vec3(1.0f / 65536.0f));
  const float largest = std::max(units.x, std::max(units.y, units.z));
  return largest > 1.0f ? mean + offset / largest : history;
}

float taaFeedback(float feedback, int historyFrames) {
  if (historyFrames <= 0) return 0.0f;
  // The running mean until the 16 jitter phases are in (the n-th frame weighs 1 / (n + 1)): a still image is their
  // exact mean after 16 frames; from then on the exponential history of weight `feedback`.
  if (historyFrames < kTaaJitterPhases)
    return static_cast<float>(historyFrames) / static_cast<float>(historyFrames + 1);
  return feedback;
}

const std::vector<Parameter<TaaSettings>>& TaaSettings::parameters() {
  using S = TaaSettings;
  static const std::vector<Parameter<S>> table = {
      switchParameter<S>("taa", "temporal antialiasing on or off (jitters the projection)", &S::enabled).primary(),
      numberParameter<S>("feedback", 0, 0.98, "", "the history's weight per frame (0.9: about the last 10 frames)",
                         &S::feedback)
          .primary(),
      numberParameter<S>("sharpen", 0, 1, "", "sharpening of the output (0 off)", &S::sharpen)};
  return table;
}

EffectInfo TaaEffect::info() {
  EffectInfo info{"taa", "Temporal antialiasing", true, true, {"taa"}, {}};
  info.temporal = true;
  return info;
}

std::vector<ProgramSpec> TaaEffect::programSpecs() {
  return {resolveSpec(), outputSpec(false), outputSpec(true), depthSpec()};
}

TaaEffect::TaaEffect(const EffectResources& resources) : resources_(resources) {
  resolve_.program = resources_.build(resolveSpec());
  gl::Program& r = resolve_.program;
  resolve_.reconstruction = ReconstructionUniforms(r);
  resolve_.color = r.uniform("u_color");
  resolve_.velocity = r.uniform("u_velocity");
  resolve_.gbuffer = r.uniform("u_gbuffer");
  resolve_.history = r.uniform("u_history");
  resolve_.previousGbuffer = r.uniform("u_previousGbuffer");
  resolve_.texel = r.uniform("u_texel");
  resolve_.size = r.uniform("u_size");
  resolve_.feedback = r.uniform("u_feedback");
  resolve_.gamma = r.uniform("u_gamma");
  resolve_.viewToPreviousView = r.uniform("u_viewToPreviousView");
  for (bool sharpen : {false, true}) {
    OutputProgram& o = sharpen ? sharpened_ : copy_;
    o.program = resources_.build(outputSpec(sharpen));
    o.resolved = o.program.uniform("u_resolved");
    if (sharpen) {
      o.texel = o.program.uniform("u_texel");
      o.sharpen = o.program.uniform("u_sharpen");
    }
  }
  depthCopy_ = resources_.build(depthSpec());
  depthCopyGbuffer_ = depthCopy_.uniform("u_gbuffer");
}

void TaaEffect::plan(FramePlanner& planner) {
  const TaaSettings settings = planner.settings().of<TaaSettings>();
  if (!settings.enabled) return;
  PassDecl pass;
  pass.name = "taa";
  pass.reads = {"scene-color", "velocity", "gbuffer"};
  pass.writes = {{"scene-color", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
  pass.run = [this, settings](PassContext& context) { render(context, settings); };
  planner.add(std::move(pass));
}

void TaaEffect::render(PassContext& context, const TaaSettings& settings) {
  using gl::Program;
  RenderTargetPool::History& color = context.history("taa-color", TargetSize::full(), GL_NEAREST);
  RenderTargetPool::History& depth = context.history("taa-depth", TargetSize::full(), GL_NEAREST);
  // Both histories are made and dropped together; one frame of this effect per frame of the Renderer (a split view
  // comparing another switch runs the pass twice in one frame, over the same history).
  const FrameContext& frame = context.frame();
  if (!color.valid() || !depth.valid() || !frame.hasPrevious) {
    historyFrames_ = 0;
  } else if (frame.index != lastFrameIndex_) {
    ++historyFrames_;
  }
  lastFrameIndex_ = frame.index;

  const glm::ivec2 size = context.size("scene-color");
  const glm::vec2 texel(1.0f / static_cast<float>(size.x), 1.0f / static_cast<float>(size.y));

  // 1. Resolve into the history.
  color.current().bindForDrawing();
  resolve_.program.use();
  resolve_.reconstruction.set(context.camera().reconstruction);
  context.texture("scene-color").bind(0);
  context.texture("velocity").bind(1);
  context.texture("gbuffer").bind(2);
  color.previous().color().bind(3);
  depth.previous().color().bind(4);
  Program::set(resolve_.color, 0);
  Program::set(resolve_.velocity, 1);
  Program::set(resolve_.gbuffer, 2);
  Program::set(resolve_.history, 3);
  Program::set(resolve_.previousGbuffer, 4);
  Program::set(resolve_.texel, texel);
  Program::set(resolve_.size, glm::vec2(size));
  Program::set(resolve_.feedback, taaFeedback(settings.feedback, historyFrames_));
  Program::set(resolve_.gamma, kTaaClipGamma);
  Program::set(resolve_.viewToPreviousView, frame.previousCamera.view * glm::inverse(context.camera().view));
  resources_.triangle.draw();

  // 2. The depth this frame saw, for the next frame's disocclusion test.
  depth.current().bindForDrawing();
  depthCopy_.use();
  context.texture("gbuffer").bind(0);
  Program::set(depthCopyGbuffer_, 0);
  resources_.triangle.draw();

  // 3. The resolved colour out, sharpened or as it is.
  context.bindForWriting("scene-color");
  const OutputProgram& out = settings.sharpen > 0.0f ? sharpened_ : copy_;
  out.program.use();
  color.current().color().bind(0);
  Program::set(out.resolved, 0);
  if (settings.sharpen > 0.0f) {
    Program::set(out.texel, texel);
    Program::set(out.sharpen, settings.sharpen);
  }
  resources_.triangle.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
