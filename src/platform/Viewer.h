#pragma once
// One interactive session, shared by obscura-view (GLFW window) and the web page (WebGL canvas): the scene kept on
// the CPU, the Renderer built from it, what is shown (ViewerState), the camera moves and the key bindings. The
// platform layer owns the window or canvas and its context, forwards input and calls render() each frame; both
// front-ends therefore start from the same defaults (the built-in scene, its camera, default parameters, the final
// view) and answer the same keys the same way.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gl/GlCaps.h"
#include "platform/DynamicResolution.h"
#include "platform/ViewerState.h"
#include "renderer/Renderer.h"
#include "scene/GltfLoader.h"
#include "scene/Scene.h"

namespace obscura {

class Viewer {
 public:
  // Builds the Renderer for the current context and shows the built-in scene. Throws GlError if the context cannot
  // run Obscura.
  explicit Viewer(const gl::GlCaps& caps, const RendererOptions& options = {});
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // --- Scenes. Each resets the camera to the scene's own view, and the AO radius to the scene's default
  // (scene/SceneScale.h: 5 % of its bounding-sphere diameter; the built-in scene's 1 m) unless a state text gave
  // one (ViewerState::sceneLoaded). A scene that fails to load throws (InputError for a bad file, GlError if the
  // context refuses it) and leaves the current scene on screen, radius included.
  void loadBuiltinScene();
  GltfLoadReport loadGltf(const std::vector<std::uint8_t>& bytes, const std::string& name,
                          const std::map<std::string, std::vector<std::uint8_t>>& sideFiles = {});
  GltfLoadReport loadGltfFile(const std::string& path);
  const std::string& sceneName() const { return sceneName_; }
  std::size_t sceneTriangles() const { return scene_.triangleCount(); }
  // The AO radius the current scene gets when nobody sets one (defaultAoRadius).
  float sceneDefaultRadius() const { return state_.defaultRadius; }

  // --- What is shown. Parameters and the view are set through the state (AoSettings::set, setViewMode, applyQuery).
  ViewerState& state() { return state_; }
  const ViewerState& state() const { return state_; }

  // --- Camera moves (see CameraControls.h); each refits near/far to the scene. A move while the view looks through
  // one of the scene's cameras starts from that camera's view, as the free camera.
  void orbit(float dxPixels, float dyPixels, int viewportHeight);
  void pan(float dxPixels, float dyPixels, int viewportHeight);
  void zoom(float factor);
  void resetCamera();  // the scene's own view, through the free camera

  // --- Cameras: the free one and the scene's own (ViewerState::sceneCameras), "free" or one by name or index.
  void setCamera(const std::string& choice);
  // The free camera made orthographic or perspective with the same view at its target (Camera::asOrthographic),
  // starting from the view shown.
  void setOrthographic(bool orthographic);
  // The camera the view looks through now: the free one, or the scene camera where the timeline puts it.
  Camera cameraShown() const;

  // --- Keys, the same on the desktop and on the web: what the keyboard types (e.g. "]", " " for space), or, for a
  // key that types nothing, its KeyboardEvent.key name ("ArrowLeft", "ArrowRight", "Home"), which obscura-view maps
  // from GLFW.
  struct KeyBinding {
    std::string key;
    std::string label;  // the key as a person reads it: "space", "left arrow", "home", else the key itself
    std::string description;
  };
  static std::vector<KeyBinding> keyBindings();
  // Applies the key's action; false if the key is not bound. Throws InputError if the action is refused.
  bool handleKey(const std::string& key);

  // Draws one frame of the current state into `framebuffer` (0: the window's or canvas's own) at width x height.
  // `clockSeconds` is the front end's clock (any origin): a playing timeline first advances by its change since the
  // previous frame (Timeline::tick); the frame shows the timeline's time. What adapts over real time (auto exposure)
  // steps by the clock's change since the previous frame, at most kLongestFrameInterval (a frame drawn after an idle
  // spell steps as one frame, not as the whole spell); 1/60 s where the clock does not move. Does nothing while the
  // context is lost (the timeline still advances). `allowCheapFrame` false: the frame asked for even during
  // resolution.quick-start (FrameOptions::allowCheapFrame: a snapshot).
  void render(GLuint framebuffer, int width, int height, PassTimer* timer = nullptr, double clockSeconds = 0.0,
              bool allowCheapFrame = true);
  // Begins compiling the programs of the frame render() would draw next at this size (Renderer::prepare), so that a
  // driver that compiles elsewhere (a browser's GPU process) does it while the front end goes on; returns how many.
  // Nothing for a view other than the final image (a debug view, split screen).
  size_t prepare(GLuint framebuffer, int width, int height);
  // --- Dynamic resolution (resolution.dynamic, frame/Resolution.h): with it on, render() draws at the scale the
  // controller chose (platform/DynamicResolution.h) from the frame times the front end measures: GPU timer queries
  // where the context has them, else the interval between frames drawn back to back. `scale`: the frame's.
  void frameMeasured(double ms, float scale) { dynamic_.measured(ms, scale); }
  // The render scale of the last frame drawn, and the controller.
  float renderScale() const { return renderScale_; }
  const DynamicResolution& dynamicResolution() const { return dynamic_; }

  // Whether frames change by themselves (a timeline playing): a front end drawing on change only then draws on.
  bool playing() const { return state_.timeline.playing(); }
  // Frames a front end drawing on change only draws after each change, the first included: 1, or while an effect that
  // jitters the projection is on (temporal antialiasing), the jitter's 16 phases, over which a still image converges.
  int framesPerChange() const;
  // Frame time (the intervals render steps by) a front end drawing on change only keeps drawing for after each
  // change, because frames keep changing by themselves for that long: with auto exposure on, until it has come
  // within 1 % of the new value at its slower speed (ln 100 / speed); else 0.
  double adaptationSeconds() const;
  static constexpr double kLongestFrameInterval = 0.1;

  // --- Context loss. contextLost() drops every GL object without deleting it (its names belong to the lost context,
  // see gl::abandonContextObjects); contextRestored() rebuilds the Renderer and the GPU scene from the CPU scene for
  // the new context. State, camera and scene are kept, so the same image comes back.
  void contextLost();
  void contextRestored(const gl::GlCaps& caps);
  bool hasContext() const { return renderer_ != nullptr; }
  const gl::GlCaps& caps() const { return caps_; }

  // Rebuilds the Renderer with other options (e.g. a forced depth-hierarchy storage, to compare the storages on
  // this context); the scene, state and camera stay. Returns the storage now in use.
  HierarchyStorage setRendererOptions(const RendererOptions& options);
  const RendererOptions& rendererOptions() const { return options_; }
  const Renderer* renderer() const { return renderer_.get(); }

 private:
  struct KeyAction;
  static const std::vector<KeyAction>& keyActions();
  // The timeline, for a key that acts on it: throws InputError saying why where the scene has no animations, or,
  // for a key that plays or steps it (`playable`), where the chosen animation has no length ("none").
  Timeline& requireTimeline(bool playable);
  void showScene(Scene scene, const std::string& name, const Camera& camera);
  // A frame's options at this size (the timeline's time, the scene camera, dynamic resolution's scale).
  FrameOptions frameOptions(int width, int height);
  // Makes the scene camera looked through (if any) the free camera, at its view.
  void takeOverSceneCamera();
  // Sets a numeric parameter to change(current value), clamped to the parameter's range.
  void adjustParameter(const std::string& name, const std::function<double(double)>& change);

  gl::GlCaps caps_;
  RendererOptions options_;
  std::unique_ptr<Renderer> renderer_;
  Scene scene_;
  std::string sceneName_;
  Bounds sceneBounds_;
  Camera sceneCamera_;  // the scene's own view, for resetCamera()
  ViewerState state_;
  DynamicResolution dynamic_;
  float renderScale_ = 1.0f;
  int lastWidth_ = 0, lastHeight_ = 0;  // the last frame's output size (a new one: dynamic_ measures afresh)
  double lastClock_ = -1.0;  // the clock of the last frame drawn (render's clockSeconds); -1: none yet
};

}  // namespace obscura
