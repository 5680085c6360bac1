#include "platform/Viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "base/Error.h"
#include "base/TimeSpent.h"
#include "effects/auto_exposure/AutoExposureEffect.h"
#include "effects/taa/TaaEffect.h"
#include "frame/Resolution.h"
#include "gl/GlObjects.h"
#include "platform/CameraControls.h"
#include "scene/BuiltinScene.h"
#include "scene/SceneScale.h"

namespace obscura {

struct Viewer::KeyAction {
  const char* key;
  const char* description;
  std::function<void(Viewer&)> apply;
};

const std::vector<Viewer::KeyAction>& Viewer::keyActions() {
  auto view = [](const char* mode) { return [mode](Viewer& v) { v.state_.setViewMode(mode); }; };
  auto toggle = [](const char* name) {
    return [name](Viewer& v) { v.state_.settings.set(name, v.state_.settings.get(name) == "on" ? "off" : "on"); };
  };
  // Keys name parameters by their full names ("ao.radius"); RenderSettings also takes the old ones.
  auto scale = [](const char* name, double factor) {
    return [name, factor](Viewer& v) { v.adjustParameter(name, [factor](double x) { return x * factor; }); };
  };
  auto step = [](const char* name, double delta) {
    return [name, delta](Viewer& v) { v.adjustParameter(name, [delta](double x) { return x + delta; }); };
  };
  static const std::vector<KeyAction> actions = {
      {"1", "final image", view("final")},
      {"2", "AO (blurred)", view("ao")},
      {"3", "raw AO", view("ao-raw")},
      {"4", "normals", view("normals")},
      {"5", "depth", view("depth")},
      {"6", "split screen: the compared switch (AO at first) off | on", view("split")},
      {"c", "split screen, comparing the next switch (AO, its blur, ..., each effect)",
       [](Viewer& v) {
         const std::vector<std::string>& switches = splitSwitches();
         const auto at = std::find(switches.begin(), switches.end(), v.state_.view.compare);
         v.state_.view.compare = at == switches.end() || at + 1 == switches.end() ? switches.front() : *(at + 1);
         v.state_.setViewMode("split");
       }},
      {"a", "AO on / off", toggle("ao")},
      {"b", "blur on / off", toggle("ao.blur")},
      {"t", "tone mapping on / off", toggle("tonemap")},
      {"f", "FXAA on / off", toggle("fxaa")},
      {"m", "motion blur on / off", toggle("motion-blur")},
      {"g", "bloom (glow) on / off", toggle("bloom")},
      {"y", "fog on / off", toggle("fog")},
      {"p", "next quality preset",
       [](Viewer& v) {
         // From the preset the AO's settings came from, even after some of its values were changed.
         const std::vector<QualityPreset>& presets = allQualityPresets();
         size_t next = 0;
         for (size_t i = 0; i < presets.size(); ++i)
           if (v.state_.settings.ao().preset == presets[i]) next = (i + 1) % presets.size();
         v.state_.settings.set("preset", presetName(presets[next]));
       }},
      {"[", "AO radius / 1.25", scale("ao.radius", 1.0 / 1.25)},
      {"]", "AO radius x 1.25", scale("ao.radius", 1.25)},
      {"-", "AO intensity - 0.1", step("ao.intensity", -0.1)},
      {"=", "AO intensity + 0.1", step("ao.intensity", 0.1)},
      {"{", "AO bias - 0.01 r", step("ao.bias", -0.01)},
      {"}", "AO bias + 0.01 r", step("ao.bias", 0.01)},
      {";", "AO contrast - 0.5", step("ao.contrast", -0.5)},
      {"'", "AO contrast + 0.5", step("ao.contrast", 0.5)},
      {"0", "AO intensity, bias, contrast back to auto (fitted)",
       [](Viewer& v) {
         for (const char* name : {"ao.intensity", "ao.bias", "ao.contrast"}) v.state_.settings.set(name, "auto");
       }},
      {",", "one AO sample fewer", step("ao.samples", -1)},
      {".", "one AO sample more", step("ao.samples", 1)},
      {"<", "AO blur radius - 1", step("ao.blur-radius", -1)},
      {">", "AO blur radius + 1", step("ao.blur-radius", 1)},
      {"(", "exposure - 0.5 EV", step("tonemap.exposure", -0.5)},
      {")", "exposure + 0.5 EV", step("tonemap.exposure", 0.5)},
      {"r", "reset the camera", [](Viewer& v) { v.resetCamera(); }},
      {"v", "next camera: the free one, then each of the scene's own",
       [](Viewer& v) {
         const int count = static_cast<int>(v.state_.sceneCameras.size());
         if (count == 0) throw InputError("no other camera: the scene has no cameras of its own");
         v.state_.sceneCamera = v.state_.sceneCamera + 1 < count ? v.state_.sceneCamera + 1 : -1;
       }},
      {"x", "orthographic / perspective (the free camera, from the view shown)",
       [](Viewer& v) { v.setOrthographic(!v.cameraShown().orthographic); }},
      {" ", "play / pause the animation",
       [](Viewer& v) {
         Timeline& timeline = v.requireTimeline(true);
         if (timeline.playing()) timeline.pause();
         else timeline.play();
       }},
      {"ArrowLeft", "animation: one frame back (1/60 s; pauses)",
       [](Viewer& v) { v.requireTimeline(true).stepFrames(-1); }},
      {"ArrowRight", "animation: one frame on (1/60 s; pauses)",
       [](Viewer& v) { v.requireTimeline(true).stepFrames(1); }},
      {"Home", "animation: back to the start", [](Viewer& v) { v.requireTimeline(true).setTime(0.0); }},
      {"n", "next animation (each, all together, none)", [](Viewer& v) { v.requireTimeline(false).nextAnimation(); }},
      {"/", "animation speed / 2",
       [](Viewer& v) {
         Timeline& timeline = v.requireTimeline(false);
         timeline.setSpeed(std::max(Timeline::kMinSpeed, timeline.speed() / 2.0));
       }},
      {"*", "animation speed x 2",
       [](Viewer& v) {
         Timeline& timeline = v.requireTimeline(false);
         timeline.setSpeed(std::min(Timeline::kMaxSpeed, timeline.speed() * 2.0));
       }},
      {"l", "animation loop on / off",
       [](Viewer& v) {
         Timeline& timeline = v.requireTimeline(false);
         timeline.setLoop(!timeline.loop());
       }},
  };
  return actions;
}

std::vector<Viewer::KeyBinding> Viewer::keyBindings() {
  std::vector<KeyBinding> out;
  for (const KeyAction& a : keyActions()) {
    const std::string key = a.key;
    const std::string label = key == " "            ? "space"
                              : key == "ArrowLeft"  ? "left arrow"
                              : key == "ArrowRight" ? "right arrow"
                              : key == "Home"       ? "home"
                                                    : key;
    out.push_back({key, label, a.description});
  }
  return out;
}

Timeline& Viewer::requireTimeline(bool playable) {
  // A key that would do nothing visible says why, where a page's controls would be hidden or disabled.
  Timeline& timeline = state_.timeline;
  if (!timeline.hasAnimations()) throw InputError("nothing to play: the scene has no animations");
  if (playable && !(timeline.duration() > 0.0))
    throw InputError(timeline.animation().kind == AnimationChoice::Kind::None
                         ? "nothing to play: the animation chosen is none (the rest pose); n chooses another"
                         : "nothing to play: animation " + timeline.animationName() + " lasts 0 s");
  return timeline;
}

Viewer::Viewer(const gl::GlCaps& caps, const RendererOptions& options)
    : caps_(caps), options_(options), renderer_(std::make_unique<Renderer>(caps, options)) {
  loadBuiltinScene();
}

Viewer::~Viewer() = default;

void Viewer::showScene(Scene scene, const std::string& name, const Camera& camera) {
  if (renderer_) renderer_->setScene(scene);  // first: if the upload fails, nothing has changed
  dynamic_.forget();                          // another scene costs otherwise
  scene_ = std::move(scene);
  sceneName_ = name;
  sceneBounds_ = scene_.worldBounds();
  sceneCamera_ = camera;
  state_.camera = camera;
  state_.sceneCameras = scene_.cameras;
  state_.sceneCamera = -1;
  state_.sceneLoaded(defaultAoRadius(scene_));  // the scene's own radius, unless a state text gave one
  state_.timeline.sceneLoaded(scene_);           // its first animation, from time 0
}

void Viewer::loadBuiltinScene() {
  Scene scene;
  {
    const TimedScope timed("built-in scene");
    scene = makeBuiltinScene();
  }
  showScene(std::move(scene), "built-in scene", builtinSceneCamera());
}

GltfLoadReport Viewer::loadGltf(const std::vector<std::uint8_t>& bytes, const std::string& name,
                                const std::map<std::string, std::vector<std::uint8_t>>& sideFiles) {
  GltfLoadReport report;
  Scene scene = loadGltfMemory(bytes, name, sideFiles, &report);
  const Camera camera = Camera::fit(scene.worldBounds(), state_.camera.width, state_.camera.height);
  showScene(std::move(scene), name, camera);
  return report;
}

GltfLoadReport Viewer::loadGltfFile(const std::string& path) {
  GltfLoadReport report;
  Scene scene = obscura::loadGltfFile(path, &report);
  const Camera camera = Camera::fit(scene.worldBounds(), state_.camera.width, state_.camera.height);
  const size_t slash = path.find_last_of('/');
  showScene(std::move(scene), slash == std::string::npos ? path : path.substr(slash + 1), camera);
  return report;
}

Camera Viewer::cameraShown() const {
  if (state_.sceneCamera < 0) return state_.camera;
  FrameOptions options;
  state_.timeline.applyTo(options);
  const ScenePose pose = evaluatePose(scene_, options.time, PoseOptions{options.animation, options.loop});
  return sceneCameraAt(scene_, state_.sceneCamera, pose, sceneBounds_, state_.camera.width, state_.camera.height);
}

void Viewer::takeOverSceneCamera() {
  if (state_.sceneCamera < 0) return;
  state_.camera = cameraShown();
  state_.sceneCamera = -1;
}

void Viewer::setCamera(const std::string& choice) { state_.setCameraChoice(choice); }

void Viewer::setOrthographic(bool orthographic) {
  takeOverSceneCamera();
  state_.camera = orthographic ? state_.camera.asOrthographic() : state_.camera.asPerspective();
  fitDepthRange(state_.camera, sceneBounds_);
}

void Viewer::orbit(float dxPixels, float dyPixels, int viewportHeight) {
  takeOverSceneCamera();
  orbitCamera(state_.camera, dxPixels, dyPixels, viewportHeight);
  fitDepthRange(state_.camera, sceneBounds_);
}

void Viewer::pan(float dxPixels, float dyPixels, int viewportHeight) {
  takeOverSceneCamera();
  panCamera(state_.camera, dxPixels, dyPixels, viewportHeight);
  fitDepthRange(state_.camera, sceneBounds_);
}

void Viewer::zoom(float factor) {
  takeOverSceneCamera();
  zoomCamera(state_.camera, factor, sceneBounds_.empty() ? 1.0f : sceneBounds_.radius());
  fitDepthRange(state_.camera, sceneBounds_);
}

void Viewer::resetCamera() {
  state_.camera = sceneCamera_;
  state_.sceneCamera = -1;
}

void Viewer::adjustParameter(const std::string& name, const std::function<double(double)>& change) {
  const auto& params = RenderSettings::parameters();
  const auto info = std::find_if(params.begin(), params.end(), [&](const ParameterInfo& p) { return name == p.name; });
  // From the value in use: an "auto" intensity steps from the value fitted for the preset and radius.
  const double current = std::strtod(state_.settings.effective(name).c_str(), nullptr);
  const double value = std::clamp(change(current), info->min, info->max);
  state_.settings.set(name, info->kind == ParameterKind::Integer ? std::to_string(std::lround(value))
                                                                 : formatShortest(static_cast<float>(value)));
}

bool Viewer::handleKey(const std::string& key) {
  for (const KeyAction& a : keyActions()) {
    if (key == a.key) {
      a.apply(*this);
      return true;
    }
  }
  return false;
}

FrameOptions Viewer::frameOptions(int width, int height) {
  FrameOptions options;
  state_.timeline.applyTo(options);  // time, animation, loop
  const ResolutionSettings& resolution = state_.settings.of<ResolutionSettings>();
  renderScale_ = resolution.scale;
  if (width != lastWidth_ || height != lastHeight_) dynamic_.forget();
  lastWidth_ = width;
  lastHeight_ = height;
  if (resolution.dynamic) {
    dynamic_.configure(resolution.targetMs, std::min(resolution.minScale, resolution.scale), resolution.scale);
    renderScale_ = dynamic_.scale();
    options.renderScale = renderScale_;
  }
  options.sceneCamera = state_.sceneCamera;
  return options;
}

void Viewer::render(GLuint framebuffer, int width, int height, PassTimer* timer, double clockSeconds,
                    bool allowCheapFrame) {
  // The size is remembered so a scene loaded next is framed for this aspect ratio.
  state_.camera.width = width;
  state_.camera.height = height;
  state_.timeline.tick(clockSeconds);
  if (!renderer_) return;
  FrameOptions options = frameOptions(width, height);
  options.timer = timer;
  options.allowCheapFrame = allowCheapFrame;
  if (lastClock_ >= 0.0 && clockSeconds > lastClock_)
    options.frameInterval = std::min(clockSeconds - lastClock_, kLongestFrameInterval);
  lastClock_ = clockSeconds;
  renderer_->render(state_.camera, state_.settings, state_.view, OutputTarget{framebuffer, width, height, {}},
                    options);
}

size_t Viewer::prepare(GLuint framebuffer, int width, int height) {
  state_.camera.width = width;
  state_.camera.height = height;
  if (!renderer_ || !(state_.view == View::Final)) return 0;  // the final view's programs only (Renderer::prepare)
  return renderer_->prepare(state_.camera, state_.settings, OutputTarget{framebuffer, width, height, {}},
                            frameOptions(width, height));
}

double Viewer::adaptationSeconds() const {
  const AutoExposureSettings& exposure = state_.settings.of<AutoExposureSettings>();
  if (!exposure.enabled) return 0.0;
  return std::log(100.0) / std::min(exposure.speedUp, exposure.speedDown);
}

void Viewer::contextLost() {
  gl::abandonContextObjects();
  renderer_.reset();
}

HierarchyStorage Viewer::setRendererOptions(const RendererOptions& options) {
  auto renderer = std::make_unique<Renderer>(caps_, options);  // first: if it fails, nothing has changed
  renderer->setScene(scene_);
  options_ = options;
  renderer_ = std::move(renderer);
  return renderer_->hierarchyStorage();
}

void Viewer::contextRestored(const gl::GlCaps& caps) {
  caps_ = caps;
  auto renderer = std::make_unique<Renderer>(caps_, options_);
  renderer->setScene(scene_);
  renderer_ = std::move(renderer);
}

int Viewer::framesPerChange() const { return Renderer::jitters(state_.settings) ? kTaaJitterPhases : 1; }

}  // namespace obscura
