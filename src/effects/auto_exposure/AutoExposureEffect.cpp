#include "effects/auto_exposure/AutoExposureEffect.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "frame/FullscreenPass.h"
#include "frame/PassContext.h"

namespace obscura {
namespace {

namespace em = ExposureMetering;
using Metering = em::Metering;

constexpr int kStageMeter = 0, kStageReduce = 1, kStageBins = 2, kStageAdapt = 3, kStageCount = 4;
// The grids' sizes, as TargetSize tiles of the frame: the meter's 8 x 8 pixels, then 16 x 16 texels per reduction.
constexpr int kLevelTile[3] = {em::kMeterBlock, em::kMeterBlock * em::kReduceBlock,
                               em::kMeterBlock * em::kReduceBlock * em::kReduceBlock};
const char* const kLevelTargets[3] = {"exposure-meter", "exposure-level-1", "exposure-level-2"};
const char* const kReducePasses[2] = {"exposure-reduce", "exposure-reduce-2"};

const char* meteringName(Metering metering) {
  switch (metering) {
    case Metering::Average: return "average";
    case Metering::Centre: return "centre";
    case Metering::Percentile: return "percentile";
  }
  return "?";
}

ProgramSpec spec(int stage, Metering metering) {
  static const char* const stages[] = {"meter", "reduce", "bins", "adapt", "count"};
  const bool metered = stage == kStageMeter || stage == kStageAdapt;
  return ProgramSpec{std::string("auto-exposure[") + stages[stage] + (metered ? std::string(",") +
                                                                                    meteringName(metering)
                                                                              : std::string()) + "]",
                     stage == kStageCount ? "auto_exposure/histogram.vert" : "lib/fullscreen.vert",
                     "auto_exposure/auto_exposure.frag",
                     {{"EXPOSURE_STAGE", std::to_string(stage)},
                      {"METERING", std::to_string(static_cast<int>(metering))},
                      {"FAR_RAY", "0"}}};
}

}  // namespace

const std::vector<Parameter<AutoExposureSettings>>& AutoExposureSettings::parameters() {
  using S = AutoExposureSettings;
  static const std::vector<Parameter<S>> table = {
      switchParameter<S>("auto-exposure", "auto exposure on or off (the scene's log-average luminance, metered on "
                         "the GPU, brought to mid grey; replaces tonemap.exposure)",
                         &S::enabled)
          .primary(),
      numberParameter<S>("compensation", -8, 8, "EV", "added to the metered exposure (positive: brighter)",
                         &S::compensation)
          .primary(),
      numberParameter<S>("min-ev", -16, 16, "EV", "the darkest exposure auto exposure chooses (for a bright scene)",
                         &S::minEv),
      numberParameter<S>("max-ev", -16, 16, "EV", "the brightest exposure auto exposure chooses (for a dark scene)",
                         &S::maxEv),
      numberParameter<S>("speed-up", 0.01, 100, "per second",
                         "adaptation towards a brighter scene: the fraction 1 - e^(-speed dt) of the way per frame",
                         &S::speedUp)
          .primary(),
      numberParameter<S>("speed-down", 0.01, 100, "per second",
                         "adaptation towards a darker scene: the fraction 1 - e^(-speed dt) of the way per frame",
                         &S::speedDown)
          .primary(),
      choiceParameter<S, Metering>("metering",
                                   "average (the log-average), centre (weighted towards the middle) or percentile "
                                   "(the mean between two percentiles of a histogram)",
                                   &S::metering,
                                   {{"average", Metering::Average},
                                    {"centre", Metering::Centre},
                                    {"percentile", Metering::Percentile}})
          .primary(),
      numberParameter<S>("percentile-low", 0, 100, "%", "percentile metering: the darkest samples left out",
                         &S::percentileLow),
      numberParameter<S>("percentile-high", 0, 100, "%",
                         "percentile metering: the samples up to here are averaged (the rest, the brightest, left "
                         "out)",
                         &S::percentileHigh)};
  return table;
}

EffectInfo AutoExposureEffect::info() {
  return {"auto-exposure",
          "Auto exposure",
          true,
          false,
          {"exposure-meter", kReducePasses[0], kReducePasses[1], "exposure-histogram", "exposure-bins",
           "exposure-adapt"},
          {{kLevelTargets[0], "RG the weighted mean log2 luminance of 8 x 8 pixels (16-bit, -16 .. 16), BA their "
            "weight (16-bit)", GL_NEAREST, {}},
           {kLevelTargets[1], "as exposure-meter, over 16 x 16 of its texels", GL_NEAREST, {}},
           {kLevelTargets[2], "as exposure-meter, over 16 x 16 of exposure-level-1's texels", GL_NEAREST, {}},
           {"exposure-histogram", "128 bins x 64 rows: one count per byte (percentile metering)", GL_NEAREST, {}},
           {"exposure-bins", "128 x 1: RG each bin's count (16-bit)", GL_NEAREST, {}},
           {"exposure", "1 x 1: RG the adapted log2 luminance, BA the exposure in EV (16-bit, -16 .. 16)", GL_NEAREST,
            {}}}};
}

std::vector<ProgramSpec> AutoExposureEffect::programSpecs() {
  return {spec(kStageMeter, Metering::Average), spec(kStageMeter, Metering::Centre),
          spec(kStageReduce, Metering::Average), spec(kStageBins, Metering::Average),
          spec(kStageAdapt, Metering::Average),  spec(kStageAdapt, Metering::Percentile),
          spec(kStageCount, Metering::Percentile)};
}

bool AutoExposureEffect::histogramAvailable(const gl::GlCaps& caps) { return caps.maxVertexTextureImageUnits > 0; }

AutoExposureEffect::AutoExposureEffect(const EffectResources& resources) : resources_(resources) {}

void AutoExposureEffect::plan(FramePlanner& planner) {
  const AutoExposureSettings settings = planner.settings().of<AutoExposureSettings>();
  if (!settings.enabled) return;
  using Write = PassDecl::Write;
  const bool percentile =
      settings.metering == Metering::Percentile && histogramAvailable(resources_.caps);
  const Metering metering = settings.metering == Metering::Centre ? Metering::Centre : Metering::Average;

  planner.add(fullscreenPass("exposure-meter", spec(kStageMeter, metering), {{"u_color", "scene-color"}},
                             {kLevelTargets[0], TargetSize::tiles(kLevelTile[0])},
                             [metering](FullscreenDraw& draw, const PassContext& context) {
                               const glm::vec2 frame(context.size("scene-color"));
                               draw.set("u_frameSize", frame);
                               if (metering == Metering::Centre)
                                 draw.set("u_centreScale", glm::vec2(2.0f * frame.x / frame.y, 2.0f));
                             }));

  std::string last = kLevelTargets[0];
  if (percentile) {
    PassDecl scatter;
    scatter.name = "exposure-histogram";
    scatter.reads = {last};
    scatter.writes = {{"exposure-histogram", TargetSize::fixed(em::kHistogramBins, em::kHistogramRows),
                       Write::Depth::None, ""}};
    scatter.run = [this](PassContext& context) { histogram(context); };
    planner.add(std::move(scatter));
    // The bins' source has a fixed size, known to the shader.
    planner.add(fullscreenPass("exposure-bins", spec(kStageBins, Metering::Average),
                               {{"u_histogram", "exposure-histogram"}},
                               {"exposure-bins", TargetSize::fixed(em::kHistogramBins, 1)}));
    last = "exposure-bins";
  } else {
    const glm::ivec2 frame(planner.frame().camera.width, planner.frame().camera.height);
    const int reductions = em::reductionCount(frame);
    if (reductions > 2) throw PipelineError("auto exposure: a frame this large needs more than two reductions");
    for (int k = 1; k <= reductions; ++k) {
      const std::string from = kLevelTargets[k - 1];
      planner.add(fullscreenPass(kReducePasses[k - 1], spec(kStageReduce, Metering::Average), {{"u_source", from}},
                                 {kLevelTargets[k], TargetSize::tiles(kLevelTile[k])},
                                 [from](FullscreenDraw& draw, const PassContext& context) {
                                   draw.set("u_sourceSize", glm::vec2(context.size(from)));
                                 }));
    }
    last = kLevelTargets[reductions];
  }

  PassDecl adaptPass;
  adaptPass.name = "exposure-adapt";
  adaptPass.reads = {last};
  adaptPass.writes = {{"exposure", TargetSize::fixed(1, 1), Write::Depth::None, ""}};
  // This frame's settings (the plan is cached: only the metering shapes it).
  adaptPass.run = [this, percentile, last](PassContext& context) {
    adapt(context, context.settings().of<AutoExposureSettings>(), percentile, last);
  };
  planner.add(std::move(adaptPass));
}

void AutoExposureEffect::histogram(const PassContext& context) {
  const glm::ivec2 grid = context.size(kLevelTargets[0]);
  const int texels = grid.x * grid.y;
  const int samples = std::min(texels, em::kHistogramMaxSamples);
  if (!sampleIndices_) {  // 0 .. kHistogramMaxSamples - 1, made on first use
    std::vector<float> indices(em::kHistogramMaxSamples);
    for (size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<float>(i);
    sampleIndices_ = gl::BufferHandle::create();
    glBindBuffer(GL_ARRAY_BUFFER, sampleIndices_.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(float)), indices.data(),
                 GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
  }
  context.bindForWriting("exposure-histogram");
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  {
    // The program, its texture and uniforms as a full-screen draw's; the draw is the samples' points.
    FullscreenDraw scatter = context.draw(spec(kStageCount, Metering::Percentile));
    scatter.read("u_meter", kLevelTargets[0]);
    scatter.set("u_meterSize", glm::vec2(grid));
    scatter.set("u_stride", static_cast<float>(texels) / static_cast<float>(samples));
    glBindBuffer(GL_ARRAY_BUFFER, sampleIndices_.id());
    glEnableVertexAttribArray(gl::kAttribPosition);
    glVertexAttribPointer(gl::kAttribPosition, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
    glDrawArrays(GL_POINTS, 0, samples);
    glDisableVertexAttribArray(gl::kAttribPosition);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
  }
  // The blending this pass set (the draw has put back its program and texture, and the block above its stream).
  glDisable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ZERO);
}

void AutoExposureEffect::adapt(const PassContext& context, const AutoExposureSettings& settings, bool percentile,
                               const std::string& from) {
  RenderTargetPool::History& history = context.history("auto-exposure", TargetSize::fixed(1, 1), GL_NEAREST);
  // One step of 1 - e^(-speed dt) towards the metered value (ExposureMetering::adapt).
  const float dt = static_cast<float>(context.frame().frameInterval);
  const glm::vec2 fraction(1.0f - std::exp(-settings.speedUp * dt), 1.0f - std::exp(-settings.speedDown * dt));
  const float low = std::min(settings.percentileLow, settings.percentileHigh) / 100.0f;
  const float high = std::max(settings.percentileLow, settings.percentileHigh) / 100.0f;
  const ProgramSpec program = spec(kStageAdapt, percentile ? Metering::Percentile : Metering::Average);
  auto draw = [&] {
    FullscreenDraw d = context.draw(program);
    d.read("u_source", from);
    d.texture("u_history", history.previous().color());
    // The percentile adaptation's source (the bins) has a fixed size, known to the shader.
    if (!percentile) d.set("u_sourceSize", glm::vec2(context.size(from)));
    d.set("u_hasHistory", history.valid() ? 1.0f : 0.0f);
    d.set("u_fraction", fraction);
    if (percentile) d.set("u_percentiles", glm::vec2(low, high));
    d.set("u_exposure", glm::vec3(std::min(settings.minEv, settings.maxEv), std::max(settings.minEv, settings.maxEv),
                                  settings.compensation));
    d.draw();
  };
  // The same texel twice: into the history for the next frame, and into the frame's `exposure` for the tone mapping.
  history.current().bindForDrawing();
  draw();
  context.bindForWriting("exposure");
  draw();
}

}  // namespace obscura
