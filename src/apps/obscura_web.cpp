// obscura-core.wasm: the Obscura core behind the JS API of web/obscura.js (documented in web/README.md).
//
// Each function below is exported under its C name and wrapped by web/obscura.js; none is meant to be called
// directly by a page. Functions that can fail return 0 and leave a one-line message for obscura_error(). Returned
// strings stay valid until the next call into the module.
//
// Frames are drawn on requestAnimationFrame into the canvas the JS API handed over (platform/WebCanvas), through the
// same Viewer session obscura-view uses: only when something changed (a parameter, the view, the camera, the scene,
// the canvas size, a restored context), on every animation frame while the timeline plays, or on every animation
// frame in continuous mode, which the timings need. The timeline's clock is requestAnimationFrame's time.
#include <emscripten/emscripten.h>
#include <emscripten/html5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include "base/Error.h"
#include "base/Text.h"
#include "base/TimeSpent.h"
#include "effects/ao/DepthHierarchyPass.h"
#include "environment/Environment.h"
#include "frame/Resolution.h"
#include "gl/GlObjects.h"
#include "gl/RenderTarget.h"
#include "platform/GpuPassTimer.h"
#include "platform/Viewer.h"
#include "platform/WebCanvas.h"

using namespace obscura;
using Json = nlohmann::json;

namespace {

// Exponential moving average weight of the newest frame in the displayed timings.
constexpr double kSmoothing = 0.1;
// The most frames drawn after a change for dynamic resolution to find its scale (DynamicResolution::refining).
constexpr int kRefineFrames = 120;

// Where the time between obscura_create and the first frame went, in ms by name (base/TimeSpent.h).
Json timesSpent(const std::map<std::string, TimeSpent::Total>& totals) {
  Json out = Json::object();
  for (const auto& [name, total] : totals) out[name] = total.ms;
  return out;
}

class WebApp {
 public:
  // `dynamicResolution`, `quickStart`: this page's defaults for resolution.dynamic and resolution.quick-start (the
  // demo page's: on).
  WebApp(const RendererOptions& options, bool dynamicResolution, bool quickStart)
      : canvas_([this] { contextLost(); }, [this] { contextRestored(); }),
        viewer_(gl::GlCaps::query(), options),
        timer_(std::make_unique<GpuPassTimer>(viewer_.caps(), &WebCanvas::procAddress)) {
    if (dynamicResolution) viewer_.state().setDefault("resolution.dynamic", "on");
    if (quickStart) viewer_.state().setDefault("resolution.quick-start", "on");
    emscripten_request_animation_frame_loop(&WebApp::animationFrame, this);
  }

  // The next frame's programs begun (Viewer::prepare), for the state as it is now: Chromium's GPU process compiles
  // them while the page builds its controls and waits for the animation frame that draws (docs/resolution.md,
  // "Start-up"). obscura_create calls it where asked (createObscura's default), a restored context again, and
  // obscura_prepare at a caller's request (after changing the state first).
  size_t prepare() {
    if (canvas_.lost()) return 0;
    fit(&width_, &height_);
    const size_t begun = viewer_.prepare(0, width_, height_);
    programsPrepared_ += begun;
    return begun;
  }

  // Start-up: what making the app took (obscura_create: the context, the renderer's programs, the sky, the scene),
  // measured by its caller around the constructor.
  void created(double ms) {
    createMs_ = ms;
    createParts_ = timesSpent(TimeSpent::take());
    createdAt_ = emscripten_get_now();
  }

  Viewer& viewer() { return viewer_; }
  WebCanvas& canvas() { return canvas_; }

  // Something the user changed: draw it on the next animation frame (a frame that failed may succeed now).
  void changed() {
    renderError_.clear();
    frameWanted_ = true;
    refineFrames_ = kRefineFrames;
  }
  void setContinuous(bool continuous) {
    continuous_ = continuous;
    frameWanted_ = true;
  }

  // Draws one frame at the canvas's display size; returns false (and keeps the message) if the renderer failed.
  // `allowCheapFrame` false: the full frame even during quick start (a snapshot).
  bool draw(GpuPassTimer* timer, bool allowCheapFrame = true) {
    if (canvas_.lost() || !renderError_.empty()) return false;
    fit(&width_, &height_);
    try {
      // The host time: the render call alone (the page's canvas work around it is not the renderer's).
      const double start = emscripten_get_now();
      viewer_.render(0, width_, height_, timer, time_, allowCheapFrame);
      lastHostMs_ = emscripten_get_now() - start;
      return true;
    } catch (const std::exception& e) {
      renderError_ = e.what();
      // EM_LOG_CONSOLE: console.error (without it Emscripten writes to stderr, which the page shows as a warning).
      emscripten_log(EM_LOG_CONSOLE | EM_LOG_ERROR, "obscura: cannot render: %s", e.what());
      return false;
    }
  }

  Json stats() const {
    Json passes = nullptr;
    if (timer_ && timer_->hasResult()) {
      passes = Json::object();
      const std::vector<std::string>& names = framePassNames();
      for (size_t p = 0; p < names.size(); ++p) {
        const double ms = timer_->lastResult()[p];
        passes[names[p]] = ms >= 0.0 ? Json(ms) : Json(nullptr);
      }
    }
    // The frame the renderer drew last: how many frames its history has survived, and the passes it ran.
    Json history = nullptr, ran = Json::array(), doneBy = Json::object();
    if (const Renderer* renderer = viewer_.renderer()) {
      history = {{"frames", renderer->lastFrame().historyFrames},
                 {"drops", renderer->historyDrops()},
                 {"frameIndex", renderer->lastFrame().index}};
      for (const PlannedPass& pass : renderer->lastPlan().passes())
        if (pass.live) {
          ran.push_back(pass.decl.name);
          for (const std::string& absorbed : pass.absorbed) doneBy[absorbed] = pass.decl.name;
        }
    }
    const gl::LiveObjects& live = gl::liveObjects();
    const ResolutionSettings& resolution = settings().of<ResolutionSettings>();
    const DynamicResolution& dynamic = viewer_.dynamicResolution();
    Json render = {{"scale", viewer_.renderScale()},
                   {"pixelRatio", canvas_.pixelRatio()},
                   {"devicePixelRatio", WebCanvas::devicePixelRatio()},
                   {"dynamic", resolution.dynamic},
                   {"measuredBy", timer_ && timer_->available() ? "gpu" : "cpu"},
                   {"meanMs", dynamic.meanMs()},
                   {"framesMeasured", dynamic.framesMeasured()},
                   {"refining", dynamic.refining()},
                   {"step", dynamic.step()},
                   {"targetMs", resolution.targetMs},
                   {"changes", dynamic.changes()}};
    if (const Renderer* renderer = viewer_.renderer()) {
      render["width"] = renderer->lastFrame().camera.width;
      render["height"] = renderer->lastFrame().camera.height;
    }
    // Quick start (resolution.quick-start): the cheap frames, the passes warmed, the first full frame.
    Json quickStart = nullptr;
    bool cheapFrame = false;
    if (const Renderer* renderer = viewer_.renderer()) {
      const QuickStartReport& report = renderer->quickStart();
      Json warmed = Json::array();
      for (const QuickStartReport::Warmed& w : report.warmed)
        warmed.push_back({{"pass", w.pass}, {"frame", w.frame}, {"atMs", w.atMs}, {"cpuMs", w.cpuMs}});
      quickStart = {{"cheapFrames", report.cheapFrames},
                    {"firstFullFrame", report.firstFullFrame >= 0 ? Json(report.firstFullFrame) : Json(nullptr)},
                    {"fullAtMs", report.fullAtMs >= 0.0 ? Json(report.fullAtMs) : Json(nullptr)},
                    {"warmed", warmed}};
      cheapFrame = renderer->lastFrameCheap();
    }
    Json startup = {{"createMs", createMs_}, {"createParts", createParts_},
                    {"firstFrameMs", firstFrameMs_ > 0.0 ? Json(firstFrameMs_) : Json(nullptr)},
                    {"firstFrameCpuMs", firstFrameCpuMs_ > 0.0 ? Json(firstFrameCpuMs_) : Json(nullptr)},
                    {"firstFrameParts", firstFrameParts_},
                    {"fullFrameMs", fullFrameMs_ > 0.0 ? Json(fullFrameMs_) : Json(nullptr)},
                    {"programsPrepared", programsPrepared_},
                    {"quickStart", quickStart}};
    // The frame's pooled targets and what its last geometry pass drew (null before the renderer is made).
    Json pooledTargets = nullptr, triangles = nullptr, drawCalls = nullptr;
    if (const Renderer* renderer = viewer_.renderer()) {
      const GpuScene::Counts counts = renderer->gpuScene().lastDrawCounts();
      pooledTargets = renderer->pooledTargets();
      triangles = counts.triangles;
      drawCalls = counts.drawCalls;
    }
    return Json{{"width", width_},
                {"height", height_},
                {"render", render},
                {"startup", startup},
                {"continuous", continuous_},
                {"pending", frameWanted_},
                {"frameMs", frameMs_},
                {"cpuMs", cpuMs_},
                {"lastCpuMs", lastCpuMs_},
                {"hostMs", hostMs_},
                {"lastHostMs", lastHostMs_},
                {"frames", frames_},
                {"cheapFrame", cheapFrame},
                {"timerQueries", timer_ && timer_->available()},
                {"passMs", passes},
                {"passesRun", ran},
                {"passesDoneBy", doneBy},
                {"history", history},
                {"pooledTargets", pooledTargets},
                {"triangles", triangles},
                {"drawCalls", drawCalls},
                {"contextLost", canvas_.lost()},
                {"contextRestores", restores_},
                {"glObjects", {{"textures", live.textures},
                               {"buffers", live.buffers},
                               {"framebuffers", live.framebuffers},
                               {"renderbuffers", live.renderbuffers},
                               {"shaders", live.shaders},
                               {"programs", live.programs}}},
                {"error", renderError_}};
  }

 private:
  static EM_BOOL animationFrame(double timeMs, void* self) {
    static_cast<WebApp*>(self)->frame(timeMs);
    return EM_TRUE;  // keep the loop going; frames are simply skipped while the context is lost
  }

  void frame(double timeMs) {
    time_ = timeMs * 0.001;
    if (canvas_.lost()) return;
    // The first frame is done once the browser runs the next animation frame (it has presented it): start-up's end.
    if (frames_ > 0 && firstFrameMs_ == 0.0) {
      firstFrameMs_ = emscripten_get_now() - createdAt_;
      firstFrameParts_ = timesSpent(TimeSpent::take());
    }
    // Likewise the first full frame (after quick start's cheap ones; the first frame itself without them).
    if (fullDrawn_ && fullFrameMs_ == 0.0) fullFrameMs_ = emscripten_get_now() - createdAt_;
    GpuPassTimer* timer = timer_ && timer_->available() ? timer_.get() : nullptr;
    if (timer) {
      timer->collectResults();
      // Dynamic resolution measures by the GPU's time where the timer queries are there (a frame's passes).
      if (timer->results() != timerResults_) {
        timerResults_ = timer->results();
        double ms = 0.0;
        for (double pass : timer->lastResult()) ms += std::max(pass, 0.0);
        viewer_.frameMeasured(ms, static_cast<float>(timer->lastResultTag()));
      }
    }
    int width = 0, height = 0;
    if (fit(&width, &height)) {
      frameWanted_ = true;
      refineFrames_ = kRefineFrames;  // a new size: dynamic resolution measures afresh
    }
    if (viewer_.playing()) frameWanted_ = true;  // a playing timeline changes every frame by itself
    // The temporal AO accumulates over frames: a still view keeps drawing until its history holds
    // ao.temporal-frames frames (the last drawn frame's history held historyFrames + 1).
    const AoSettings& ao = settings().ao();
    if (const Renderer* renderer = viewer_.renderer())
      if (ao.enabled && ao.temporal && renderer->lastFrame().historyFrames + 1 < ao.temporalFrames) frameWanted_ = true;
    // Dynamic resolution starts at its smallest scale and climbs while frames show room (DynamicResolution::refining):
    // a still view draws on until it is there, within a budget of frames per change (timer results may never come).
    if (settings().of<ResolutionSettings>().dynamic) {
      if (viewer_.dynamicResolution().scale() != lastScale_) frameWanted_ = true;  // it chose another scale
      if (viewer_.dynamicResolution().refining() && refineFrames_ > 0) {
        frameWanted_ = true;
        --refineFrames_;
      }
    }
    // Auto exposure adapts over the frames' intervals (each at most Viewer::kLongestFrameInterval): after a change,
    // frames are drawn until their intervals add up to the adaptation's time, however long a slow device takes.
    if (!frameWanted_ && !continuous_ && settleFrames_ <= 0 && adaptationLeft_ <= 0.0) {
      lastFrameTime_ = 0.0;  // the next drawn frame does not follow this one
      return;
    }
    // A change is drawn over framesPerChange() frames (temporal antialiasing converges over its jitter's phases).
    if (frameWanted_) {
      settleFrames_ = viewer_.framesPerChange();
      adaptationLeft_ = viewer_.adaptationSeconds();
    }
    frameWanted_ = false;
    // Without timer queries, dynamic resolution measures the interval from the last frame to this one, when the two
    // were drawn back to back (the last frame's cost, drawing and presenting).
    if (!timer && lastFrameTime_ > 0.0) viewer_.frameMeasured(timeMs - lastFrameTime_, lastScale_);
    // The first frame after a pause is measured: a still view draws a change in a frame or a few.
    const bool dynamic = settings().of<ResolutionSettings>().dynamic;
    if (timer) timer->beginFrame(dynamic ? nextScale() : 1.0, dynamic || lastFrameTime_ == 0.0);
    const double start = emscripten_get_now();
    const bool drawn = draw(timer);
    lastScale_ = viewer_.renderScale();
    if (timer) timer->endFrame();
    if (!drawn) {
      lastFrameTime_ = 0.0;
      return;
    }
    if (settleFrames_ > 0) --settleFrames_;
    // Quick start: after a cheap frame the next one warms or is the full frame (Renderer::lastFrameCheap).
    if (const Renderer* renderer = viewer_.renderer()) {
      if (renderer->lastFrameCheap()) frameWanted_ = true;
      else fullDrawn_ = true;
    }
    if (const Renderer* renderer = viewer_.renderer()) adaptationLeft_ -= renderer->lastFrame().frameInterval;
    lastCpuMs_ = emscripten_get_now() - start;
    if (frames_ == 0) firstFrameCpuMs_ = lastCpuMs_;
    cpuMs_ = frames_ == 0 ? lastCpuMs_ : cpuMs_ + kSmoothing * (lastCpuMs_ - cpuMs_);
    hostMs_ = frames_ == 0 ? lastHostMs_ : hostMs_ + kSmoothing * (lastHostMs_ - hostMs_);
    // The frame time is the interval between animation frames drawn back to back (continuous mode, or a drag).
    if (lastFrameTime_ > 0.0) {
      const double interval = timeMs - lastFrameTime_;
      frameMs_ = frameMs_ == 0.0 ? interval : frameMs_ + kSmoothing * (interval - frameMs_);
    }
    lastFrameTime_ = timeMs;
    ++frames_;
  }

  // The settings, read only.
  const RenderSettings& settings() const { return std::as_const(viewer_).state().settings; }

  // The drawing buffer fitted to the canvas's CSS size, at the pixel ratio resolution.max-pixel-ratio allows.
  bool fit(int* width, int* height) {
    return canvas_.fitToDisplay(viewer_.caps().maxRenderSize(),
                                settings().of<ResolutionSettings>().maxPixelRatio, width, height);
  }
  // The scale the next frame draws at, with dynamic resolution on.
  double nextScale() const { return viewer_.dynamicResolution().scale(); }

  void contextLost() {
    timer_.reset();  // its queries belong to the lost context: viewer_.contextLost() abandons them with the rest
    viewer_.contextLost();
  }

  void contextRestored() {
    try {
      viewer_.contextRestored(gl::GlCaps::query());
      timer_ = std::make_unique<GpuPassTimer>(viewer_.caps(), &WebCanvas::procAddress);
      ++restores_;
      prepare();  // as at start-up: the first frame's programs begun before it
      changed();
    } catch (const std::exception& e) {
      renderError_ = std::string("cannot rebuild after the context was restored: ") + e.what();
      emscripten_log(EM_LOG_CONSOLE | EM_LOG_ERROR, "obscura: %s", renderError_.c_str());
    }
  }

  WebCanvas canvas_;
  Viewer viewer_;
  std::unique_ptr<GpuPassTimer> timer_;
  bool frameWanted_ = true;  // something changed since the last drawn frame
  int settleFrames_ = 0;     // frames still to draw after the last change
  double adaptationLeft_ = 0.0;  // the frame time (seconds) auto exposure still adapts over after the last change
  bool continuous_ = false;
  int width_ = 0, height_ = 0;
  double lastFrameTime_ = 0.0, frameMs_ = 0.0, cpuMs_ = 0.0;
  double time_ = 0.0;  // seconds, the clock the timeline plays by (the last animation frame's time)
  double lastCpuMs_ = 0.0;  // time in the renderer of the last drawn frame, unsmoothed
  // Host time: the render call alone (planning, the passes' GL calls), smoothed and of the last drawn frame.
  double hostMs_ = 0.0, lastHostMs_ = 0.0;
  long frames_ = 0;
  int restores_ = 0;
  std::string renderError_;
  float lastScale_ = 1.0f;              // the render scale of the last frame drawn
  int refineFrames_ = kRefineFrames;    // frames dynamic resolution may still draw on since the last change
  std::uint64_t timerResults_ = 0;      // the GPU timer's results fed to dynamic resolution
  size_t programsPrepared_ = 0;  // programs begun by prepare() (at start-up, and after a restored context)
  double createMs_ = 0.0, createdAt_ = 0.0, firstFrameMs_ = 0.0, firstFrameCpuMs_ = 0.0, fullFrameMs_ = 0.0;
  bool fullDrawn_ = false;  // a full frame was drawn (fullFrameMs_ is taken at the next animation frame)
  Json createParts_ = Json::object(), firstFrameParts_ = Json::object();
};

std::unique_ptr<WebApp> g_app;
std::string g_error;     // the message of the last failed call
std::string g_returned;  // the text of the last call that returns one
std::vector<std::uint8_t> g_snapshot;
std::map<std::string, std::vector<std::uint8_t>> g_sideFiles;  // gathered for the next obscura_load_scene
std::vector<std::string> g_sceneWarnings;                      // what the loader repaired or ignored

// Runs `body`, turning an exception into 0 and its message into obscura_error()'s text.
template <typename Body>
int attempt(Body&& body) {
  try {
    body();
    return 1;
  } catch (const std::exception& e) {
    g_error = e.what();
    return 0;
  }
}

// attempt() for a call that changes what is shown: a frame is drawn for it if it succeeds.
template <typename Body>
int change(Body&& body) {
  const int ok = attempt(std::forward<Body>(body));
  if (ok) g_app->changed();
  return ok;
}

// The step a user interface rounds a number parameter's value to (the page's number fields): a power of ten near a
// thousandth of its range, a slider's resolution (sun elevation -90 .. 90: 0.1); 1 for integers. 0 for a range that
// spans two decades or more above zero (the page's slider is logarithmic there): three significant figures.
double parameterStep(const ParameterInfo& p) {
  if (p.kind == ParameterKind::Integer) return 1.0;
  if (p.min > 0.0 && p.max / p.min >= 100.0) return 0.0;
  return std::pow(10.0, std::floor(std::log10((p.max - p.min) / 1000.0)));
}

const char* returned(std::string text) {
  g_returned = std::move(text);
  return g_returned.c_str();
}

// The renderer made again with its options (checkGlErrors among them) changed by `change`; returns what `report`
// reads from the new renderer, or null where the change is refused (obscura_error says why).
template <typename Change, typename Report>
const char* changeRendererOptions(Change&& change, Report&& report) {
  std::string used;
  if (!attempt([&] {
        RendererOptions options = g_app->viewer().rendererOptions();
        change(options);
        g_app->viewer().setRendererOptions(options);
        used = report(*g_app->viewer().renderer());
      }))
    return nullptr;
  g_app->changed();
  return returned(used);
}

}  // namespace

extern "C" {

// checkGlErrors: glGetError after every pass; an error stops the frame and is logged as a console error naming the
// pass (the browser tests turn it on; it costs a round trip per pass). dynamicResolution: resolution.dynamic's
// default on this page (the demo page's: on; the API's: off). quickStart: resolution.quick-start's (the same).
// prepare: the first frame's programs begun before it returns (WebApp::prepare), as part of start-up.
EMSCRIPTEN_KEEPALIVE int obscura_create(int checkGlErrors, int dynamicResolution, int quickStart, int prepare) {
  return attempt([checkGlErrors, dynamicResolution, quickStart, prepare] {
    RendererOptions options;
    options.checkGlErrors = checkGlErrors != 0;
    // One app per canvas: the old one lets go of the canvas's context and event handlers before a new one takes
    // them (made first, the new app lost its context-loss handlers to the old one's destructor; found natively by
    // tests/test_web_api.cpp).
    g_app.reset();
    TimeSpent::take();  // start-up's figures start here
    const double start = emscripten_get_now();
    g_app = std::make_unique<WebApp>(options, dynamicResolution != 0, quickStart != 0);
    if (prepare != 0) g_app->prepare();
    g_app->created(emscripten_get_now() - start);
  });
}

EMSCRIPTEN_KEEPALIVE const char* obscura_error() { return g_error.c_str(); }

// Everything a user interface needs to build its controls, read from the core's tables: the effect table (effects,
// their parameters, passes and targets), the views, the presets and the keys.
EMSCRIPTEN_KEEPALIVE const char* obscura_describe() {
  const RenderSettings defaults;
  Json parameters = Json::array();
  for (const ParameterInfo& p : RenderSettings::parameters()) {
    Json item{{"name", p.name}, {"effect", p.effect}, {"kind", parameterKindName(p.kind)}, {"range", p.range},
              {"help", p.help}, {"default", defaults.get(p.name)}, {"primary", p.primary}, {"slow", p.slow}};
    if (!p.alias.empty()) item["alias"] = p.alias;
    if (p.kind == ParameterKind::Number || p.kind == ParameterKind::Integer) {
      item["min"] = p.min;
      item["max"] = p.max;
      item["step"] = parameterStep(p);
    }
    if (!p.choices.empty()) item["choices"] = p.choices;  // for a number: words accepted besides numbers ("auto")
    parameters.push_back(item);
  }
  Json effects = Json::array();
  for (const EffectEntry& row : effectTable()) {
    Json names = Json::array(), targets = Json::array();
    for (const ParameterInfo& p : RenderSettings::parameters())
      if (p.effect == row.info.name) names.push_back(p.name);
    for (const TargetInfo& t : row.info.targets) {
      Json views = Json::array();
      for (const TargetView& v : t.views) views.push_back(v.name);
      targets.push_back({{"name", t.name}, {"encoding", t.encoding}, {"views", views}});
    }
    effects.push_back({{"name", row.info.name}, {"title", row.info.title}, {"switch", row.info.hasSwitch},
                       {"passes", row.info.passes}, {"targets", targets}, {"parameters", names}});
  }
  Json presets = Json::array();
  for (const PresetInfo& p : qualityPresets())
    presets.push_back({{"name", p.name}, {"samples", p.samples}, {"turns", p.spiralTurns},
                       {"blurRadius", p.blurRadius}, {"blurStride", p.blurStride},
                       {"halfResolution", p.halfResolution}});
  Json keys = Json::array();
  for (const Viewer::KeyBinding& k : Viewer::keyBindings())
    keys.push_back({{"key", k.key}, {"label", k.label}, {"description", k.description}});
  Json context = nullptr;
  if (g_app) {
    const gl::GlCaps& caps = g_app->viewer().caps();
    context = {{"version", caps.version}, {"renderer", caps.renderer}, {"vendor", caps.vendor},
               {"shadingLanguage", caps.shadingLanguage}, {"maxRenderSize", caps.maxRenderSize()},
               {"depth24", caps.depth24}, {"elementIndexUint", caps.elementIndexUint},
               {"timerQuery", caps.timerQuery}};
  }
  return returned(Json{{"parameters", parameters}, {"effects", effects}, {"presets", presets},
                       {"views", ViewerState::viewModes()}, {"compareSwitches", splitSwitches()}, {"keys", keys},
                       {"passes", framePassNames()}, {"context", context}}.dump());
}

EMSCRIPTEN_KEEPALIVE int obscura_set(const char* name, const char* value) {
  return change([&] { g_app->viewer().state().settings.set(name, value); });
}

EMSCRIPTEN_KEEPALIVE const char* obscura_get(const char* name) {
  std::string value;
  if (!attempt([&] { value = g_app->viewer().state().settings.get(name); })) return nullptr;
  return returned(value);
}

EMSCRIPTEN_KEEPALIVE const char* obscura_get_effective(const char* name) {
  std::string value;
  if (!attempt([&] { value = g_app->viewer().state().settings.effective(name); })) return nullptr;
  return returned(value);
}

// Forces how the depth hierarchy is stored ("separate", "atlas", "mipchain"; "auto": the best this context offers)
// and returns the storage now in use; the page's tests compare the storages' AO on WebGL 1.
EMSCRIPTEN_KEEPALIVE const char* obscura_set_hierarchy_storage(const char* name) {
  return changeRendererOptions(
      [&](RendererOptions& options) {
        options.hierarchyStorage.reset();  // "auto"
        const std::string wanted = name;
        if (wanted == "separate") options.hierarchyStorage = HierarchyStorage::SeparateTextures;
        else if (wanted == "atlas") options.hierarchyStorage = HierarchyStorage::Atlas;
        else if (wanted == "mipchain") options.hierarchyStorage = HierarchyStorage::MipChain;
        else if (wanted != "auto")
          throw InputError("hierarchy storage: expected auto, separate, atlas or mipchain, got '" + wanted + "'");
      },
      [](const Renderer& renderer) { return DepthHierarchyPass::storageName(renderer.hierarchyStorage()); });
}

// Forces where the prefiltered environment's levels live ("halffloat", half floats the hardware filters; "mipchain",
// read with EXT_shader_texture_lod; "atlas"; "auto": the first of these the context can take) and returns the layout
// now in use; the page's tests compare them on WebGL 1.
EMSCRIPTEN_KEEPALIVE const char* obscura_set_environment_layout(const char* name) {
  std::optional<EnvironmentLayout> layout;
  return changeRendererOptions(
      [&](RendererOptions& options) {
        const std::string wanted = name;
        if (wanted == "atlas") layout = EnvironmentLayout::Atlas;
        else if (wanted == "mipchain") layout = EnvironmentLayout::MipChain;
        else if (wanted == "halffloat") layout = EnvironmentLayout::HalfFloatAtlas;
        else if (wanted != "auto")
          throw InputError("environment layout: expected auto, halffloat, atlas or mipchain, got '" + wanted + "'");
        options.environmentLayout = layout;  // none: "auto"
      },
      [&](const Renderer&) {
        return std::string(environmentLayoutName(GpuEnvironment::layoutFor(g_app->viewer().caps(), layout)));
      });
}

// Allows or refuses vertex array objects (OES_vertex_array_object) for the scene's draws, and returns "on" where the
// scene now draws with them, "off" where not (refused, or the context lacks the extension); the page's tests compare
// the images and count the calls both ways.
EMSCRIPTEN_KEEPALIVE const char* obscura_set_vertex_arrays(int allow) {
  return changeRendererOptions([&](RendererOptions& options) { options.allowVertexArrays = allow != 0; },
                               [](const Renderer& renderer) {
                                 return std::string(renderer.gpuScene().usesVertexArrays() ? "on" : "off");
                               });
}

// Allows or refuses static batches (the still instances that share a material drawn as one piece: gpu/GpuScene.h),
// and returns how many the scene now draws; the page's tests compare the images and count the calls both ways.
EMSCRIPTEN_KEEPALIVE const char* obscura_set_static_batches(int allow) {
  return changeRendererOptions([&](RendererOptions& options) { options.batchStaticInstances = allow != 0; },
                               [](const Renderer& renderer) {
                                 return std::to_string(renderer.gpuScene().staticBatchCount());
                               });
}

EMSCRIPTEN_KEEPALIVE int obscura_set_view(const char* mode) {
  return change([&] { g_app->viewer().state().setViewMode(mode); });
}

EMSCRIPTEN_KEEPALIVE const char* obscura_view() { return returned(g_app->viewer().state().viewMode()); }

EMSCRIPTEN_KEEPALIVE int obscura_set_compare(const char* name) {
  return change([&] { g_app->viewer().state().view.compare = parseCompare(name); });
}

EMSCRIPTEN_KEEPALIVE const char* obscura_compare() { return returned(g_app->viewer().state().view.compare); }

EMSCRIPTEN_KEEPALIVE const char* obscura_state() { return returned(g_app->viewer().state().toQuery()); }

EMSCRIPTEN_KEEPALIVE int obscura_set_state(const char* query) {
  return change([&] { g_app->viewer().state().applyQuery(query); });
}

EMSCRIPTEN_KEEPALIVE void obscura_orbit(float dx, float dy, int viewportHeight) {
  g_app->viewer().orbit(dx, dy, viewportHeight);
  g_app->changed();
}

EMSCRIPTEN_KEEPALIVE void obscura_pan(float dx, float dy, int viewportHeight) {
  g_app->viewer().pan(dx, dy, viewportHeight);
  g_app->changed();
}

EMSCRIPTEN_KEEPALIVE void obscura_zoom(float factor) {
  g_app->viewer().zoom(factor);
  g_app->changed();
}

EMSCRIPTEN_KEEPALIVE void obscura_reset_camera() {
  g_app->viewer().resetCamera();
  g_app->changed();
}

// The camera looked through: {choice: "free" or the scene camera's state name, orthographic, cameras: [the scene's
// cameras: {name, orthographic}], and the free camera's eye, target, up, fovy, ymag}.
EMSCRIPTEN_KEEPALIVE const char* obscura_camera() {
  const ViewerState& state = g_app->viewer().state();
  Json cameras = Json::array();
  for (size_t i = 0; i < state.sceneCameras.size(); ++i)
    cameras.push_back(
        {{"name", state.sceneCameras[i].label(i)}, {"orthographic", state.sceneCameras[i].orthographic}});
  const Camera shown = g_app->viewer().cameraShown();
  const Camera& free = state.camera;
  return returned(Json{{"choice", state.cameraChoice()},
                       {"orthographic", shown.orthographic},
                       {"cameras", cameras},
                       {"eye", {free.eye.x, free.eye.y, free.eye.z}},
                       {"target", {free.target.x, free.target.y, free.target.z}},
                       {"up", {free.up.x, free.up.y, free.up.z}},
                       {"fovy", free.fovyDegrees},
                       {"ymag", free.ymag}}
                      .dump());
}

// "free" or one of the scene's cameras, by name or index.
EMSCRIPTEN_KEEPALIVE int obscura_set_camera(const char* choice) {
  return change([&] { g_app->viewer().setCamera(choice); });
}

EMSCRIPTEN_KEEPALIVE int obscura_set_orthographic(int orthographic) {
  return change([&] { g_app->viewer().setOrthographic(orthographic != 0); });
}

// 1: the key is bound and acted; 0 with an empty obscura_error(): not bound; 0 with a message: refused.
EMSCRIPTEN_KEEPALIVE int obscura_handle_key(const char* key) {
  bool bound = false;
  g_error.clear();
  if (!attempt([&] { bound = g_app->viewer().handleKey(key); }) || !bound) return 0;
  g_app->changed();
  return 1;
}

// Side files (a .gltf's buffers and images, by the URI it uses) for the next obscura_load_scene.
EMSCRIPTEN_KEEPALIVE void obscura_add_side_file(const char* uri, const std::uint8_t* bytes, int size) {
  g_sideFiles[uri].assign(bytes, bytes + size);
}

// Loads a .gltf or .glb from memory with the side files added before; on failure the current scene stays.
// The scene's name, triangle count and the loader's warnings are then in obscura_scene(). The AO radius becomes the
// scene's default unless a state text gave one (platform/Viewer.h).
EMSCRIPTEN_KEEPALIVE int obscura_load_scene(const char* name, const std::uint8_t* bytes, int size) {
  std::map<std::string, std::vector<std::uint8_t>> sideFiles;
  sideFiles.swap(g_sideFiles);
  return change([&] {
    const GltfLoadReport report = g_app->viewer().loadGltf(std::vector<std::uint8_t>(bytes, bytes + size), name,
                                                           sideFiles);
    g_sceneWarnings = report.warnings;
  });
}

// An equirectangular environment (.hdr, or a PNG of RGBE bytes) from memory, kept in the module's memory file system
// as /environments/<name> and decoded once here, so a bad file is refused now (the lighting keeps its environment).
// Returns the path for lighting.environment, or "" (obscura_error() says why).
EMSCRIPTEN_KEEPALIVE const char* obscura_add_environment(const char* name, const std::uint8_t* bytes, int size) {
  std::string base = name;
  const size_t slash = base.find_last_of("/\\");
  if (slash != std::string::npos) base = base.substr(slash + 1);
  const std::string path = "/environments/" + (base.empty() ? std::string("environment.hdr") : base);
  const int ok = attempt([&] {
    mkdir("/environments", 0777);  // exists already after the first: the error is harmless
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes), size);
    loadEnvironmentImage(path);
  });
  return returned(ok ? path : "");
}

// A 3D LUT (Adobe / Resolve .cube text) from memory, kept in the module's memory file system as /luts/<name>, for
// grading.lut: setting that parameter to the path returned reads it, and refuses a malformed file there with its line
// (the grade in use stays). Returns the path, or "" (obscura_error() says why).
EMSCRIPTEN_KEEPALIVE const char* obscura_add_lut(const char* name, const std::uint8_t* bytes, int size) {
  std::string base = name;
  const size_t slash = base.find_last_of("/\\");
  if (slash != std::string::npos) base = base.substr(slash + 1);
  const std::string path = "/luts/" + (base.empty() ? std::string("grade.cube") : base);
  const int ok = attempt([&] {
    mkdir("/luts", 0777);  // exists already after the first: the error is harmless
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes), size);
  });
  return returned(ok ? path : "");
}

EMSCRIPTEN_KEEPALIVE int obscura_load_builtin_scene() {
  return change([] {
    g_app->viewer().loadBuiltinScene();
    g_sceneWarnings.clear();
  });
}

// The scene's name, triangle count, loader warnings, and the AO radius it gets when nobody sets one
// (scene/SceneScale.h; as written, so that 0.42 reads 0.42 and not the float's nearest double).
EMSCRIPTEN_KEEPALIVE const char* obscura_scene() {
  return returned(Json{{"name", g_app->viewer().sceneName()},
                       {"triangles", g_app->viewer().sceneTriangles()},
                       {"warnings", g_sceneWarnings},
                       {"defaultRadius", std::stod(formatShortest(g_app->viewer().sceneDefaultRadius()))},
                       {"radiusGiven", g_app->viewer().state().radiusGiven}}.dump());
}

// The current scene's default AO radius as text ("42"), without the rest of obscura_scene().
EMSCRIPTEN_KEEPALIVE const char* obscura_default_radius() {
  return returned(formatShortest(g_app->viewer().sceneDefaultRadius()));
}

// The timeline (platform/Timeline.h): the scene's animation names ('' for an unnamed one), the choice ("none",
// "all", a name, or an index where the animation has no name of its own), the time and the chosen animations'
// duration in seconds, playing, speed, loop, and the frame step's interval.
EMSCRIPTEN_KEEPALIVE const char* obscura_timeline() {
  const Timeline& timeline = g_app->viewer().state().timeline;
  return returned(Json{{"animations", timeline.animationNames()},
                       {"animation", timeline.animationName()},
                       {"time", timeline.time()},
                       {"duration", timeline.duration()},
                       {"playing", timeline.playing()},
                       {"speed", timeline.speed()},
                       {"loop", timeline.loop()},
                       {"frameInterval", Timeline::kFrameInterval}}.dump());
}

// The time alone, without the JSON (the page reads it on every animation frame while playing).
EMSCRIPTEN_KEEPALIVE double obscura_time() { return g_app->viewer().state().timeline.time(); }
EMSCRIPTEN_KEEPALIVE int obscura_playing() { return g_app->viewer().state().timeline.playing() ? 1 : 0; }

// Play does nothing where nothing plays (no animations, or "none"); both draw a frame for the change.
EMSCRIPTEN_KEEPALIVE void obscura_play() {
  g_app->viewer().state().timeline.play();
  g_app->changed();
}

EMSCRIPTEN_KEEPALIVE void obscura_pause() {
  g_app->viewer().state().timeline.pause();
  g_app->changed();
}

EMSCRIPTEN_KEEPALIVE int obscura_set_time(double seconds) {
  return change([seconds] {
    if (!std::isfinite(seconds)) throw InputError("time: expected a finite number of seconds");
    g_app->viewer().state().timeline.setTime(seconds);
  });
}

// Pauses and moves by frames x the frame interval (1/60 s).
EMSCRIPTEN_KEEPALIVE void obscura_step_frames(int frames) {
  g_app->viewer().state().timeline.stepFrames(frames);
  g_app->changed();
}

EMSCRIPTEN_KEEPALIVE int obscura_set_animation(const char* choice) {
  return change([&] { g_app->viewer().state().timeline.setAnimation(choice); });
}

EMSCRIPTEN_KEEPALIVE int obscura_set_speed(double factor) {
  return change([factor] { g_app->viewer().state().timeline.setSpeed(factor); });
}

EMSCRIPTEN_KEEPALIVE void obscura_set_loop(int loop) {
  g_app->viewer().state().timeline.setLoop(loop != 0);
  g_app->changed();
}

EMSCRIPTEN_KEEPALIVE const char* obscura_stats() { return returned(g_app->stats().dump()); }

// Continuous mode draws on every animation frame (for live timings); otherwise only after a change.
EMSCRIPTEN_KEEPALIVE void obscura_set_continuous(int continuous) { g_app->setContinuous(continuous != 0); }

// Begins compiling the programs of the next frame (WebApp::prepare: stats' startup.programsPrepared counts them);
// 0 if it failed (obscura_error).
EMSCRIPTEN_KEEPALIVE int obscura_prepare() {
  return attempt([] { g_app->prepare(); });
}

// Draws a frame now into the canvas (for embedders that draw on their own schedule, and for benchmarks that bound a
// frame with gl.finish); 0 if no frame could be drawn (context lost, renderer failure).
EMSCRIPTEN_KEEPALIVE int obscura_draw() {
  if (g_app->draw(nullptr)) return 1;
  g_error = g_app->canvas().lost() ? "the WebGL context is lost" : g_app->stats()["error"].get<std::string>();
  return 0;
}

// Draws a frame now and reads it back: {"width", "height", "pointer"} to width * height RGBA8 pixels, rows top to
// bottom, valid until the next snapshot. 0 if no frame could be drawn (context lost, renderer failure).
EMSCRIPTEN_KEEPALIVE const char* obscura_snapshot() {
  if (!g_app->draw(nullptr, false)) {
    g_error = g_app->canvas().lost() ? "the WebGL context is lost" : g_app->stats()["error"].get<std::string>();
    return nullptr;
  }
  const Json stats = g_app->stats();
  const int width = stats["width"], height = stats["height"];
  g_snapshot = gl::readPixelsTopDown(width, height);
  return returned(Json{{"width", width}, {"height", height},
                       {"pointer", reinterpret_cast<std::uintptr_t>(g_snapshot.data())}}.dump());
}

}  // extern "C"
