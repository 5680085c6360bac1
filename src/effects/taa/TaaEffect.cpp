#include "effects/taa/TaaEffect.h"

#include <algorithm>
#include <cmath>

#include "frame/PassContext.h"


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
      numberParameter<S>("sharpen", 0, 1, "", "sharpening of the output (0 off)", &S::sharpen)
          .shapesPlan()};  // above 0 the sharpening output
  return table;
}

EffectInfo TaaEffect::info() {
  EffectInfo info{"taa",
                  "Temporal antialiasing",
                  true,
                  true,
                  {"taa", "taa-depth", "taa-output"},
                  {{"taa-color", "the resolved HDR colour, RGB9E5 (lib/hdr.glsl); a history target", GL_NEAREST, {}},
                   {"taa-depth", "the G-buffer as this frame saw it (its BA depth code); a history target", GL_NEAREST,
                    {}}}};
  info.temporal = true;
  info.waitsForFullFrame = true;
  return info;
}

std::vector<ProgramSpec> TaaEffect::programSpecs() {
  return {resolveSpec(), outputSpec(false), outputSpec(true), depthSpec()};
}

TaaEffect::TaaEffect(const EffectResources&) {}

void TaaEffect::plan(FramePlanner& planner) {
  const TaaSettings& settings = planner.settings().of<TaaSettings>();
  if (!settings.enabled) return;
  using Write = PassDecl::Write;
  // 1. The resolve: this frame's colour blended into the history ("taa-color", this frame's side of it).
  planner.add(fullscreenPass(
      "taa", resolveSpec(), {{"u_color", "scene-color"}, {"u_velocity", "velocity"}, {"u_gbuffer", "gbuffer"}},
      {"taa-color", TargetSize::full(), Write::Depth::None, "", true},
      [this](FullscreenDraw& draw, const PassContext& context) {
        RenderTargetPool::History& color = context.history("taa-color", TargetSize::full(), GL_NEAREST);
        RenderTargetPool::History& depth = context.history("taa-depth", TargetSize::full(), GL_NEAREST);
        // Both histories are made and dropped together; one frame of this effect per frame of the Renderer (a split
        // view comparing another switch runs the pass twice in one frame, over the same history).
        const FrameContext& frame = context.frame();
        if (!color.valid() || !depth.valid() || !frame.hasPrevious) {
          historyFrames_ = 0;
        } else if (frame.index != lastFrameIndex_) {
          ++historyFrames_;
        }
        lastFrameIndex_ = frame.index;
        const glm::ivec2 size = context.size("scene-color");
        draw.texture("u_history", color.previous().color());
        draw.texture("u_previousGbuffer", depth.previous().color());
        setReconstruction(draw.program(), context.camera().reconstruction);
        draw.set("u_texel", 1.0f / glm::vec2(size));
        draw.set("u_size", glm::vec2(size));
        draw.set("u_feedback", taaFeedback(context.settings().of<TaaSettings>().feedback, historyFrames_));
        draw.set("u_gamma", kTaaClipGamma);
        draw.set("u_viewToPreviousView", frame.previousCamera.view * glm::inverse(context.camera().view));
      }));

  // 2. The depth this frame saw, for the next frame's disocclusion test.
  PassDecl depth = fullscreenPass("taa-depth", depthSpec(), {{"u_gbuffer", "gbuffer"}},
                                  {"taa-depth", TargetSize::full(), Write::Depth::None, "", true});
  depth.keep = true;
  planner.add(std::move(depth));

  // 3. The resolved colour out, sharpened or as it is.
  const bool sharpen = settings.sharpen > 0.0f;
  planner.add(fullscreenPass("taa-output", outputSpec(sharpen), {{"u_resolved", "taa-color"}}, {"scene-color"},
                             [sharpen](FullscreenDraw& draw, const PassContext& context) {
                               if (!sharpen) return;
                               draw.set("u_texel", context.texelSize("scene-color"));
                               draw.set("u_sharpen", context.settings().of<TaaSettings>().sharpen);
                             }));
}

}  // namespace obscura
