#include "effects/auto_exposure/AutoExposureEffect.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "frame/PassContext.h"
#include "gl/PipelineState.h"

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

AutoExposureEffect::Programs& AutoExposureEffect::programs() {
  if (programs_) return *programs_;
  auto p = std::make_unique<Programs>();
  for (Metering metering : {Metering::Average, Metering::Centre}) {
    Meter& m = metering == Metering::Average ? p->meterAverage : p->meterCentre;
    m.program = resources_.build(spec(kStageMeter, metering));
    m.color = m.program.uniform("u_color");
    m.frameSize = m.program.uniform("u_frameSize");
    if (metering == Metering::Centre) m.centreScale = m.program.uniform("u_centreScale");
  }
  // The bins' and the percentile adaptation's sources have a fixed size, known to the shader.
  auto grid = [&](Grid& g, int stage, Metering metering, const char* source) {
    g.program = resources_.build(spec(stage, metering));
    g.source = g.program.uniform(source);
    if (stage != kStageBins && metering != Metering::Percentile) g.sourceSize = g.program.uniform("u_sourceSize");
  };
  grid(p->reduce, kStageReduce, Metering::Average, "u_source");
  grid(p->bins, kStageBins, Metering::Average, "u_histogram");
  for (bool percentile : {false, true}) {
    Adapt& a = percentile ? p->adaptPercentile : p->adaptMean;
    grid(a.grid, kStageAdapt, percentile ? Metering::Percentile : Metering::Average, "u_source");
    if (percentile) a.percentiles = a.grid.program.uniform("u_percentiles");
    a.history = a.grid.program.uniform("u_history");
    a.hasHistory = a.grid.program.uniform("u_hasHistory");
    a.fraction = a.grid.program.uniform("u_fraction");
    a.exposure = a.grid.program.uniform("u_exposure");
  }
  if (histogramAvailable(resources_.caps)) {
    p->scatter = resources_.build(spec(4, Metering::Percentile));
    p->scatterMeter = p->scatter.uniform("u_meter");
    p->scatterMeterSize = p->scatter.uniform("u_meterSize");
    p->scatterStride = p->scatter.uniform("u_stride");
    std::vector<float> indices(em::kHistogramMaxSamples);
    for (size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<float>(i);
    p->sampleIndices = gl::BufferHandle::create();
    glBindBuffer(GL_ARRAY_BUFFER, p->sampleIndices.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(float)), indices.data(),
                 GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
  }
  programs_ = std::move(p);
  return *programs_;
}

void AutoExposureEffect::plan(FramePlanner& planner) {
  const AutoExposureSettings settings = planner.settings().of<AutoExposureSettings>();
  if (!settings.enabled) return;
  using Write = PassDecl::Write;
  const bool percentile =
      settings.metering == Metering::Percentile && histogramAvailable(resources_.caps);
  const Metering metering = settings.metering == Metering::Centre ? Metering::Centre : Metering::Average;

  PassDecl meterPass;
  meterPass.name = "exposure-meter";
  meterPass.reads = {"scene-color"};
  meterPass.writes = {{kLevelTargets[0], TargetSize::tiles(kLevelTile[0]), Write::Depth::None, ""}};
  meterPass.run = [this, metering](PassContext& context) { meter(context, metering); };
  planner.add(std::move(meterPass));

  std::string last = kLevelTargets[0];
  if (percentile) {
    PassDecl scatter;
    scatter.name = "exposure-histogram";
    scatter.reads = {last};
    scatter.writes = {{"exposure-histogram", TargetSize::fixed(em::kHistogramBins, em::kHistogramRows),
                       Write::Depth::None, ""}};
    scatter.run = [this](PassContext& context) { histogram(context); };
    planner.add(std::move(scatter));
    PassDecl sum;
    sum.name = "exposure-bins";
    sum.reads = {"exposure-histogram"};
    sum.writes = {{"exposure-bins", TargetSize::fixed(em::kHistogramBins, 1), Write::Depth::None, ""}};
    sum.run = [this](PassContext& context) { bins(context); };
    planner.add(std::move(sum));
    last = "exposure-bins";
  } else {
    const glm::ivec2 frame(planner.frame().camera.width, planner.frame().camera.height);
    const int reductions = em::reductionCount(frame);
    if (reductions > 2) throw PipelineError("auto exposure: a frame this large needs more than two reductions");
    for (int k = 1; k <= reductions; ++k) {
      PassDecl pass;
      pass.name = kReducePasses[k - 1];
      pass.reads = {kLevelTargets[k - 1]};
      pass.writes = {{kLevelTargets[k], TargetSize::tiles(kLevelTile[k]), Write::Depth::None, ""}};
      pass.run = [this, from = std::string(kLevelTargets[k - 1]), to = std::string(kLevelTargets[k])](
                     PassContext& context) { reduce(context, from, to); };
      planner.add(std::move(pass));
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

void AutoExposureEffect::meter(PassContext& context, Metering metering) {
  const Meter& m = metering == Metering::Centre ? programs().meterCentre : programs().meterAverage;
  const glm::vec2 frame(context.size("scene-color"));
  context.bindForWriting(kLevelTargets[0]);
  m.program.use();
  context.texture("scene-color").bind(0);
  gl::Program::set(m.color, 0);
  gl::Program::set(m.frameSize, frame);
  if (metering == Metering::Centre) gl::Program::set(m.centreScale, glm::vec2(2.0f * frame.x / frame.y, 2.0f));
  resources_.triangle.draw();
  gl::restoreBaselineState();
}

void AutoExposureEffect::reduce(PassContext& context, const std::string& from, const std::string& to) {
  const Grid& g = programs().reduce;
  context.bindForWriting(to);
  g.program.use();
  context.texture(from).bind(0);
  gl::Program::set(g.source, 0);
  gl::Program::set(g.sourceSize, glm::vec2(context.size(from)));
  resources_.triangle.draw();
  gl::restoreBaselineState();
}

void AutoExposureEffect::histogram(PassContext& context) {
  Programs& p = programs();
  const glm::ivec2 grid = context.size(kLevelTargets[0]);
  const int texels = grid.x * grid.y;
  const int samples = std::min(texels, em::kHistogramMaxSamples);
  context.bindForWriting("exposure-histogram");
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  p.scatter.use();
  context.texture(kLevelTargets[0]).bind(0);
  gl::Program::set(p.scatterMeter, 0);
  gl::Program::set(p.scatterMeterSize, glm::vec2(grid));
  gl::Program::set(p.scatterStride, static_cast<float>(texels) / static_cast<float>(samples));
  glBindBuffer(GL_ARRAY_BUFFER, p.sampleIndices.id());
  glEnableVertexAttribArray(gl::kAttribPosition);
  glVertexAttribPointer(gl::kAttribPosition, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
  glDrawArrays(GL_POINTS, 0, samples);
  glDisableVertexAttribArray(gl::kAttribPosition);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  gl::restoreBaselineState();
}

void AutoExposureEffect::bins(PassContext& context) {
  const Grid& g = programs().bins;
  context.bindForWriting("exposure-bins");
  g.program.use();
  context.texture("exposure-histogram").bind(0);
  gl::Program::set(g.source, 0);
  resources_.triangle.draw();
  gl::restoreBaselineState();
}

void AutoExposureEffect::adapt(PassContext& context, const AutoExposureSettings& settings, bool percentile,
                               const std::string& from) {
  const Adapt& a = percentile ? programs().adaptPercentile : programs().adaptMean;
  RenderTargetPool::History& history = context.history("auto-exposure", TargetSize::fixed(1, 1), GL_NEAREST);
  // One step of 1 - e^(-speed dt) towards the metered value (ExposureMetering::adapt).
  const float dt = static_cast<float>(context.frame().frameInterval);
  const glm::vec2 fraction(1.0f - std::exp(-settings.speedUp * dt), 1.0f - std::exp(-settings.speedDown * dt));
  const float low = std::min(settings.percentileLow, settings.percentileHigh) / 100.0f;
  const float high = std::max(settings.percentileLow, settings.percentileHigh) / 100.0f;
  auto draw = [&] {
    a.grid.program.use();
    context.texture(from).bind(0);
    history.previous().color().bind(1);
    gl::Program::set(a.grid.source, 0);
    if (!percentile) gl::Program::set(a.grid.sourceSize, glm::vec2(context.size(from)));
    gl::Program::set(a.history, 1);
    gl::Program::set(a.hasHistory, history.valid() ? 1.0f : 0.0f);
    gl::Program::set(a.fraction, fraction);
    if (percentile) gl::Program::set(a.percentiles, glm::vec2(low, high));
    gl::Program::set(a.exposure, glm::vec3(std::min(settings.minEv, settings.maxEv),
                                           std::max(settings.minEv, settings.maxEv), settings.compensation));
    resources_.triangle.draw();
  };
  // The same texel twice: into the history for the next frame, and into the frame's `exposure` for the tone mapping.
  history.current().bindForDrawing();
  draw();
  context.bindForWriting("exposure");
  draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
