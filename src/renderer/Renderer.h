#pragma once
// The frame, the same on every platform: the effect table (renderer/EffectTable.h) planned and run for one camera, one
// set of settings and one view. The platform layer owns the context and the output framebuffer; the Renderer owns
// every GL object it creates (the effects, the pooled targets, the scene on the GPU).
//
// Each render():
//   1. starts the frame context (frame/FrameContext.h): this frame's camera and the previous one, time, jitter;
//   2. asks each effect in table order to plan its passes (Effect::plan), then adds the view's pass;
//   3. resolves the plan (frame/FramePlan.h): order, liveness, the result into the output, pooled targets;
//   4. runs the passes that are needed, timing each (PassTimer) and, with checkGlErrors, checking glGetError and the
//      baseline GL state after each one.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "frame/DebugViewPass.h"
#include "frame/FrameContext.h"
#include "frame/FramePlan.h"
#include "frame/FullscreenTriangle.h"
#include "frame/PassContext.h"
#include "frame/ProgramCache.h"
#include "frame/RendererOptions.h"
#include "frame/RenderTargetPool.h"
#include "gl/GlCaps.h"
#include "gpu/GpuScene.h"
#include "renderer/EffectTable.h"
#include "renderer/RenderSettings.h"
#include "scene/Animation.h"
#include "scene/Camera.h"
#include "scene/Scene.h"

namespace obscura {

class AoEffect;

// What a frame shows: "final" (the finished image), "split" (the final image with one switch, `compare`, off left of
// the middle and on right of it: the AO by default, or any effect's, or a switch within one, "ao.temporal"), or the
// name of a target's debug view ("ao", "normals", "scene-color", ...: frameViewNames()).
struct View {
  std::string name = "final";
  std::string compare = "ao";  // split: the switch parameter compared (splitSwitches())

  static const View Final, Split, Ao, AoRaw, Normals, Depth, Mask;
  bool operator==(const View& other) const { return name == other.name; }
  bool operator!=(const View& other) const { return name != other.name; }
};
inline const View View::Final{"final"};
inline const View View::Split{"split"};
inline const View View::Ao{"ao"};
inline const View View::AoRaw{"ao-raw"};
inline const View View::Normals{"normals"};
inline const View View::Depth{"depth"};
inline const View View::Mask{"mask"};

// One of frameViewNames(); throws InputError listing them.
View parseView(const std::string& name);
// The switches the split view can compare: every switch parameter of the frame ("ao", "ao.blur", ..., "fxaa"), full
// names, in table order.
const std::vector<std::string>& splitSwitches();
// The full name of a switch parameter (or its alias) the split view can compare; throws InputError listing them.
std::string parseCompare(const std::string& name);

// Receives the start and end of each pass that runs, by its name (framePassNames(); per-pass timings:
// glFinish-bounded natively, timer queries on the web).
class PassTimer {
 public:
  virtual ~PassTimer() = default;
  virtual void begin(const std::string& pass) = 0;
  virtual void end(const std::string& pass) = 0;
};

struct FrameOptions {
  PassTimer* timer = nullptr;
  // Seconds on the scene's timeline: the pose drawn (scene/Animation.h), and the frame context's time.
  double time = 0.0;
  // The time of the pose motion vectors measure from. Unset: the previous frame's time (this frame's own when there
  // is none, or the scene changed), so a paused timeline has no object motion. The CLI sets time - 1 / fps.
  std::optional<double> previousTime;
  // Seconds of real time since the previous frame, for what adapts over time whether or not the timeline moves (auto
  // exposure). Unset: time - previousTime where that is positive, else 1/60 (a paused timeline, a still frame).
  std::optional<double> frameInterval;
  AnimationChoice animation;  // which animations drive the pose (default: the first; none: the rest pose)
  bool loop = true;           // the timeline wraps at the chosen animations' duration
  // Quick start (resolution.quick-start): false draws this frame as asked even while the Renderer would draw a cheap
  // one (a snapshot, a reference); a full frame drawn ends the quick start.
  bool allowCheapFrame = true;
  // Targets whose contents stay readable after the frame (retained()): tests and tools read them back. Their
  // writers run and their pooled targets are not reused within the frame.
  std::vector<std::string> retain;
  // A G-buffer the caller drew (an RGBA8 texture of the output's size in the `gbuffer` target's layout:
  // docs/api.md, shaders_es2/lib/obscura_gbuffer.glsl): the frame's `gbuffer` pass copies it instead of drawing the
  // scene, and the effects read it as their own. The camera must be the one it was drawn with. 0: the scene's.
  GLuint externalGBuffer = 0;
  // A shift of the projection in pixels (x right, y up), added to the jitter: the sheared frustum of the aperture
  // reference (renderer/AccumulationReference.h: accumulateAperture), whose camera sits off the lens's centre and looks
  // through the same plane in focus. Reconstruction from depth ignores it, as it ignores the jitter.
  glm::vec2 projectionShift{0.0f};
  // The render scale of this frame (frame/Resolution.h), in place of resolution.scale: what dynamic resolution chose
  // (platform/DynamicResolution.h). Unset: resolution.scale.
  std::optional<float> renderScale;
  // A shift that grows with depth, in pixels per metre of view depth (x right, y up), added to projectionShift: the
  // orthographic aperture reference's tilted parallel rays (accumulateAperture). Orthographic cameras only.
  glm::vec2 projectionShear{0.0f};
  // The scene's camera to look through (an index into Scene::cameras, scene/Camera.h), or -1: the `camera`
  // argument's. The scene's pose places it at `time` (cameraOfScene, at the output's size; of the `camera` argument
  // only its size is then used), and at the previous pose's time for the motion vectors, so an animated camera's
  // motion is seen by the velocity pass, motion blur and TAA. Changing cameras (another index, the free camera, or
  // another projection) is a cut: the history is dropped.
  int sceneCamera = -1;
};

// What a Renderer's start-up did (resolution.quick-start, frame/Resolution.h): the cheap frames it drew, the passes
// of the full frame it warmed, and its first full frame. With quick start off the first frame is the full one.
struct QuickStartReport {
  // A pass of the full frame drawn once at a small size (Renderer::kWarmSize) into targets of its own, so that its
  // program is compiled and linked and the driver has made its code for the pass's state (SwiftShader compiles its
  // pipeline routines at a program's first draw) before the full frame first draws it.
  struct Warmed {
    std::string pass;
    std::uint64_t frame = 0;  // the frame (FrameContext::index) that warmed it
    double atMs = 0.0;        // when: ms since the Renderer was made
    double cpuMs = 0.0;       // its time in the calling thread (compiling the program, the GL calls)
  };
  std::vector<Warmed> warmed;
  int cheapFrames = 0;               // frames drawn cheap so far (quickStartSettings)
  std::int64_t firstFullFrame = -1;  // the index (FrameContext::index) of the first full frame; -1 before it
  double fullAtMs = -1.0;            // when it was drawn: ms since the Renderer was made
};

class Renderer {
 public:
  // Throws GlError if the context cannot run Obscura (no fragment highp) or a shader fails to build, and
  // PipelineError if the effect table does not add up (a pass reading what no earlier pass writes).
  explicit Renderer(const gl::GlCaps& caps, const RendererOptions& options = {});
  // The effects hold references to the renderer's resources: a Renderer stays where it is built.
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;
  ~Renderer();

  // Uploads the scene; drops the history (the previous frame showed another scene).
  void setScene(const Scene& scene);
  // The camera a frame of `options` at `width` x `height` looks through: options.sceneCamera's at options.time, or
  // `camera` as given (resized). Throws InputError for a scene camera the scene does not have.
  Camera frameCamera(const Camera& camera, int width, int height, const FrameOptions& options) const;
  void render(const Camera& camera, const RenderSettings& settings, const View& view, const OutputTarget& output,
              const FrameOptions& options = {});
  void render(const Camera& camera, const RenderSettings& settings, const View& view, const OutputTarget& output,
              PassTimer* timer) {
    FrameOptions options;
    options.timer = timer;
    render(camera, settings, view, output, options);
  }

  // Whether an effect that is on in `settings` asks for the sub-pixel jitter (EffectInfo::jitters).
  static bool jitters(const RenderSettings& settings);

  // Quick start (resolution.quick-start). Until a full frame has been drawn, a frame of the final view is drawn with
  // quickStartSettings (the lit scene: one geometry pass and the lighting) and, from the second frame on, warms up
  // to kWarmPassesPerFrame passes of the frame asked for, at kWarmSize, after it; once every pass is warmed the next
  // frame is the full one. A frame of another view, a split view, a caller's G-buffer or allowCheapFrame false is
  // drawn as asked, and ends the quick start.
  static constexpr int kWarmPassesPerFrame = 8;
  static constexpr int kWarmSize = 128;  // the warm frame's output, square (its render size: half of it, upscaled)
  static constexpr int kMaxCheapFrames = 12;  // then the full frame, warmed or not (settings changing meanwhile)
  // The settings of the cheap frame: `settings` with the effects that add passes of their own over the frame off
  // (EffectInfo::waitsForFullFrame: AO, TAA, bloom, lens flare, glare, depth of field, edges, motion blur,
  // chromatic aberration, FXAA) and the bilinear upscale; what shapes the image's light (lighting, fog, transparency,
  // tone mapping, auto exposure, the fused display stages) stays. Unset where that is `settings` already (nothing to
  // warm).
  static std::optional<RenderSettings> quickStartSettings(const RenderSettings& settings);
  // Begins compiling the programs of the frame that render() with these arguments would draw next (with quick start,
  // the cheap one) and returns without drawing it. That frame is rehearsed: its plan run at kWarmSize into the warm
  // targets, each program it asks for begun instead of built (ProgramCache::Rehearsal: compiled and linked without
  // waiting, a stand-in that draws nothing in its place), and the commands flushed. A driver that compiles elsewhere
  // (a browser's GPU process) compiles them while the caller does other work, and the frame finds them linked; where
  // GL compiles at once it changes nothing but the order. Returns how many programs it began.
  size_t prepare(const Camera& camera, const RenderSettings& settings, const OutputTarget& output,
                 const FrameOptions& options = {});
  // Whether the last frame was a cheap one (a front end drawing on change draws another: the full frame follows).
  bool lastFrameCheap() const { return lastFrameCheap_; }
  const QuickStartReport& quickStart() const { return quickStart_; }

  // The programs built so far (and begun: prepare), for tests and stats.
  const ProgramCache& programs() const { return programs_; }
  // Every program the frame may build, for the shader validation tools and tests.
  static std::vector<ProgramSpec> allProgramSpecs() { return frameProgramSpecs(); }

  const gl::GlCaps& caps() const { return caps_; }
  const GpuScene& gpuScene() const { return scene_; }
  // The last frame's context and plan (the second half's, for split screen).
  const FrameContext& lastFrame() const { return frame_; }
  const FramePlan& lastPlan() const;
  // How many times a frame's plan was made (not found among the cached plans), for tests and stats.
  std::uint64_t plansMade() const { return plansMade_; }
  // A target the last frame retained (FrameOptions::retain). Throws InputError if it was not retained or written.
  const gl::RenderTarget& retained(const std::string& target);
  // The depth hierarchy's storage in use (the AO effect's).
  HierarchyStorage hierarchyStorage() const;
  // How often the history was dropped (size changes, scene changes), and the pooled targets alive now.
  int historyDrops() const { return pool_.historyDrops() + historyDrops_; }
  size_t pooledTargets() const { return pool_.slotCount(); }

 private:
  // `size`: the size the frame renders at (the output's, or less: frame/Resolution.h).
  void beginFrame(const Camera& camera, const RenderSettings& settings, glm::ivec2 size, const OutputTarget& output,
                  const FrameOptions& options);
  // A frame context's fields that the scene and the output decide (what the scene draws, the output's size and
  // depth): beginFrame's, and prepare's rehearsal's.
  FrameContext sceneFrame(const OutputTarget& output);
  void endFrame();
  void dropHistory();

  // Every effect's passes for `view` (a target view, or the final image), resolved.
  FramePlan plan(const RenderSettings& settings, const FrameContext& frame, const View& view,
                 const std::vector<std::string>& retain, GLuint externalGBuffer = 0);
  // What a plan depends on: the values of the parameters that shape it (ParameterInfo::shapesPlan), the view, the
  // frame's size and the output's (below it, the frame ends in an upscale), the retained targets, the caller's
  // G-buffer, what the scene asks of the frame, the projection, and whether the output has a depth buffer.
  struct PlanKey {
    std::uint64_t settings = 0;  // the shaping parameters' values (shapingId)
    std::string view;
    glm::ivec2 size{0, 0}, outputSize{0, 0};
    std::vector<std::string> retain;
    GLuint externalGBuffer = 0;
    bool forwardLighting = false, linesOrPoints = false, orthographic = false, outputDepth = false;
    bool operator==(const PlanKey& o) const {
      return settings == o.settings && view == o.view && size == o.size && outputSize == o.outputSize &&
             retain == o.retain &&
             externalGBuffer == o.externalGBuffer && forwardLighting == o.forwardLighting &&
             linesOrPoints == o.linesOrPoints && orthographic == o.orthographic && outputDepth == o.outputDepth;
    }
  };
  PlanKey planKey(const RenderSettings& settings, const View& view, const FrameOptions& options);
  // The id of the shaping parameters' values in `settings`: the last settings' id while every shaping parameter
  // holds the same value (compared by value each frame: no text), else the id of their values as text, the same for
  // equal values whenever they come back (so that settings changed back find their cached plan).
  std::uint64_t shapingId(const RenderSettings& settings);
  // This frame's plan: a cached one with this key, or a new one (which replaces the least recently used).
  const FramePlan& cachedPlan(const RenderSettings& settings, const View& view, const FrameOptions& options);
  // The `gbuffer` pass of a frame whose G-buffer the caller drew (FrameOptions::externalGBuffer): a copy.
  PassDecl importGBuffer(GLuint texture);
  // frame_.sceneBounds for frame_'s camera and the scene's pose, before its passes run.
  void boundScene(bool externalGBuffer);
  // Plans and runs one frame's passes for `view` into `output`.
  void run(const RenderSettings& settings, const View& view, const OutputTarget& output, const FrameOptions& options);
  void checkErrors(const std::string& after) const;
  // Runs pass `index` of `plan` with targets from `pool` into `output`.
  void runPass(const FramePlan& plan, size_t index, RenderTargetPool& pool, const RenderSettings& settings,
               const OutputTarget& output, PassTimer* timer);
  // The size the frame renders at: the output's, or less (frame/Resolution.h); InputError for an output or a scale
  // out of range.
  glm::ivec2 frameSize(const RenderSettings& settings, const OutputTarget& output, const FrameOptions& options) const;
  // The settings of quick start's cheap frame where this frame is one (quickStartSettings), else none.
  std::optional<RenderSettings> cheapFrameSettings(const RenderSettings& settings, const View& view,
                                                   const FrameOptions& options) const;
  // Quick start: warms the next passes of the frame `settings` asks for (after this frame's cheap one, whose context
  // frame_ is), at kWarmSize into warm_'s targets; `upscaled`: whether the frame asked for is below its output's size.
  void warmPasses(const RenderSettings& settings, bool upscaled);
  // The small frames (the warm ones, prepare's rehearsal): their targets, made or remade for an output with depth
  // where `outputDepth`; their context, `like`'s at kWarmSize (half of it where upscaled) seen from `source`, without
  // history; and a run of up to `passes` live passes of `plan` from `next` (moved past them) with frame_ theirs,
  // each added to quickStart_.warmed where `reportWarmed`.
  struct Warm;
  Warm& smallTargets(bool outputDepth);
  static FrameContext smallFrame(FrameContext like, const Camera& source, bool upscaled);
  void runSmall(const RenderSettings& settings, const FramePlan& plan, size_t& next, size_t passes,
                bool reportWarmed);
  // The first full frame drawn: quick start is over and its warm targets go.
  void fullFrameDrawn();

  gl::GlCaps caps_;
  RendererOptions options_;
  FullscreenTriangle triangle_;
  ProgramCache programs_;  // every program of the frame, the effects' and the fused stages'
  SurfaceShading surfaces_;
  EffectResources resources_;
  std::vector<std::unique_ptr<Effect>> effects_;  // one per table row
  AoEffect* ao_ = nullptr;
  std::map<std::string, TargetInfo> targets_;     // every table target, by name
  GpuScene scene_;
  Scene sceneData_;  // what the GPU scene was made from, without its images: posed every frame
  Bounds sceneBounds_;  // its bounds at rest (where a scene camera's target and infinite far plane come from)
  RenderTargetPool pool_;
  // The plans made so far, the most recently used first: a frame whose key matches one reuses it (a split view's two
  // halves are two). The planning (and every std::function and map it builds) happens only when the key changes.
  static constexpr size_t kCachedPlans = 4;
  struct CachedPlan {
    PlanKey key;
    std::unique_ptr<FramePlan> plan;
  };
  std::vector<CachedPlan> plans_;
  const FramePlan* plan_ = nullptr;  // the last frame's
  std::uint64_t plansMade_ = 0;
  std::vector<std::pair<size_t, size_t>> shapingParameters_;  // (row, parameter) of each parameter in PlanKey
  std::optional<RenderSettings> keyedSettings_;  // the settings shapingId last read as text, and their id
  std::uint64_t keyedId_ = 0, lastShapingId_ = 0;
  static constexpr size_t kShapingIds = 1024;
  std::map<std::vector<std::string>, std::uint64_t> shapingIds_;
  gl::FramebufferHandle externalGBufferSource_;  // reads the caller's G-buffer texture (importGBuffer)
  // Whether the output framebuffer has a depth buffer and a stencil buffer (GL_DEPTH_BITS, GL_STENCIL_BITS): asked
  // once per size for the default framebuffer (a query makes the bindings the cache held back, gl/BindingCache.h,
  // and on the web may wait for the GPU process), every frame for a framebuffer object, whose buffers may change
  // under the same name.
  struct OutputBuffers {
    GLuint framebuffer = 0;
    glm::ivec2 size{0, 0};
    bool known = false, depth = false, stencil = false;
  } outputBuffers_;
  const OutputBuffers& outputBuffers(const OutputTarget& output);

  // History: what the next frame's context calls "previous".
  FrameContext frame_;
  std::uint64_t frameIndex_ = 0;
  bool hasPrevious_ = false;
  int historyFrames_ = 0;
  int historyDrops_ = 0;
  FrameCamera previousCamera_;
  int previousCameraKey_ = -1;  // the scene camera's index, or -1 (free perspective) or -2 (free orthographic)
  Camera frameSource_;          // this frame's camera, as beginFrame resolved it
  double previousTime_ = 0.0;
  // The last frame's pose, kept to be the next frame's previous one when it asks for that time.
  ScenePose lastPose_;
  PoseOptions lastPoseOptions_;
  // Quick start: what it did, whether the last frame was cheap, and the warm frame's own plan, targets and output.
  QuickStartReport quickStart_;
  double createdAtMs_ = 0.0;
  bool quickStartOver_ = false;  // a full frame was drawn, or every pass warmed (the next frame is the full one)
  bool lastFrameCheap_ = false;
  struct Warm {
    PlanKey key;
    std::unique_ptr<FramePlan> plan;
    std::unique_ptr<RenderTargetPool> pool;
    gl::RenderTarget output;
    bool outputDepth = false;  // whether `output` has a depth buffer (as the frame's output)
    size_t next = 0;           // the next pass of the plan to warm
  };
  std::unique_ptr<Warm> warm_;
  glm::ivec2 lastSize_{0, 0};        // the last frame's render size
  glm::ivec2 lastOutputSize_{0, 0};  // and its output's
};

}  // namespace obscura
