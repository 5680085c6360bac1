#include "renderer/Renderer.h"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "base/Error.h"
#include "base/TimeSpent.h"
#include "effects/ao/AoEffect.h"
#include "effects/fog/FogEffect.h"
#include "frame/GBufferSettings.h"
#include "frame/Resolution.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

const gl::GlCaps& requireUsable(const gl::GlCaps& caps) {
  if (!caps.fragmentHighp)
    throw GlError("this GL context has no highp float in fragment shaders (GL_HIGH_FLOAT precision is 0); "
                  "Obscura's 16-bit depth packing needs it");
  return caps;
}

// The context's caps with the limits a test simulates (RendererOptions::simulateVertexLimits and
// simulateFragmentLimits) applied, so the scene's upload and every effect read the limits they must keep from one
// place.
gl::GlCaps withSimulatedLimits(gl::GlCaps caps, const RendererOptions& options) {
  if (const auto& vertex = options.simulateVertexLimits) {
    caps.maxVertexUniformVectors = std::min(caps.maxVertexUniformVectors, vertex->uniformVectors);
    caps.maxVertexAttribs = std::min(caps.maxVertexAttribs, vertex->attributes);
    caps.maxVertexTextureImageUnits = std::min(caps.maxVertexTextureImageUnits, vertex->textureUnits);
  }
  if (const auto& fragment = options.simulateFragmentLimits) {
    caps.maxFragmentUniformVectors = std::min(caps.maxFragmentUniformVectors, fragment->uniformVectors);
    caps.maxTextureImageUnits = std::min(caps.maxTextureImageUnits, fragment->textureUnits);
    caps.maxCombinedTextureImageUnits = std::min(caps.maxCombinedTextureImageUnits, fragment->combinedTextureUnits);
  }
  return caps;
}

// The view `name` shows, and how: {target, decoding}; empty target for "final" and "split".
std::pair<std::string, ViewDecoding> viewTarget(const View& view) {
  for (const TargetInfo& target : frameTargets())
    for (const TargetView& v : target.views)
      if (v.name == view.name) return {target.name, v.decoding};
  return {"", ViewDecoding::Color};
}

// The fog the fog pass applies with these settings, for the transparent layer (lib/fog.glsl's uniforms).
SurfaceFog surfaceFog(const FogSettings& settings, const glm::mat4& view) {
  SurfaceFog fog;
  fog.enabled = settings.enabled;
  if (!fog.enabled) return fog;
  const FogFactor factor = FogFactor::of(settings, view);
  fog.mode = static_cast<int>(factor.mode);
  fog.height = factor.falloff > 0.0f;
  fog.color = settings.color;
  fog.factor = glm::vec2(factor.offset, factor.scale);
  fog.falloff = factor.falloff;
  fog.heightScale = factor.heightScale;
  fog.upInView = factor.upInView;
  return fog;
}

}  // namespace

View parseView(const std::string& name) {
  const std::vector<std::string>& names = frameViewNames();
  for (const std::string& v : names)
    if (v == name) return View{name};
  throw InputError("view: expected " + parse::joinChoices(names, ", ") + ", got '" + name + "'");
}

const std::vector<std::string>& splitSwitches() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const ParameterInfo& p : RenderSettings::parameters())
      if (p.kind == ParameterKind::Switch && !p.effect.empty()) out.push_back(p.name);
    return out;
  }();
  return names;
}

std::string parseCompare(const std::string& name) {
  const ParameterInfo* p = RenderSettings::find(name);
  if (p && p->kind == ParameterKind::Switch && !p->effect.empty()) return p->name;
  throw InputError("compare: expected a switch, one of " + parse::joinChoices(splitSwitches(), ", ") + ", got '" +
                   name + "'");
}

Renderer::Renderer(const gl::GlCaps& caps, const RendererOptions& options)
    : caps_(withSimulatedLimits(requireUsable(caps), options)),
      options_(options),
      triangle_(caps_.vertexArrayObject && options.allowVertexArrays),
      programs_(options.checkGlErrors),
      resources_{caps_, options_, triangle_, programs_, surfaces_},
      pool_(caps_) {
  createdAtMs_ = TimeSpent::nowMs();
  for (size_t row = 0; row < effectTable().size(); ++row) {
    const EffectEntry& entry = effectTable()[row];
    effects_.push_back(entry.create(resources_));
    if (entry.info.name == "ao") ao_ = static_cast<AoEffect*>(effects_.back().get());
    for (const TargetInfo& target : entry.info.targets) targets_[target.name] = target;
    for (size_t p = 0; p < entry.parameters.size(); ++p)
      if (entry.parameters[p].info.shapesPlan) shapingParameters_.emplace_back(row, p);
  }
  // The table must add up before any frame: plan one with every effect on, at the defaults, for the final image
  // and for every view (PipelineError names the pass and the target that does not).
  FrameContext probe;
  probe.linesOrPoints = true;  // so that the points-and-lines pass is checked too
  probe.transparent = probe.transmission = true;  // and the transparent layer's
  const RenderSettings everyEffect = RenderSettings::everyEffectOn();
  for (bool forwardLighting : {false, true})  // a scene the deferred lighting can shade, and one it cannot
    for (int outputWidth : {1, 2}) {            // rendered at the output's size, and below it (upscaled)
      probe.forwardLighting = forwardLighting;
      probe.outputWidth = outputWidth;
      for (const std::string& name : frameViewNames())
        if (name != "split") plan(everyEffect, probe, View{name}, {});
    }
}

FramePlan Renderer::plan(const RenderSettings& settings, const FrameContext& frame, const View& view,
                         const std::vector<std::string>& retain, GLuint externalGBuffer) {
  const auto [target, decoding] = viewTarget(view);
  FramePlanner planner(settings, frame, targets_);
  planner.setViewTarget(target);
  planner.setFuseStages(options_.fuseStages);
  for (size_t row = 0; row < effects_.size(); ++row) {
    planner.beginEffect(effectTable()[row].info.name);
    if (externalGBuffer != 0 && effectTable()[row].info.name == "gbuffer") planner.add(importGBuffer(externalGBuffer));
    else effects_[row]->plan(planner);
  }
  planner.beginEffect("");
  if (!target.empty()) planner.add(DebugViewPass::pass("view", target, decoding));
  // A frame rendered below the output's size ends in the pass that upscales it into the output (the resolution
  // effect's, or FXAA's doing both).
  const bool finalImage = target.empty() && !frame.upscaled();
  return FramePlan::resolve(
      std::move(planner), finalImage ? kFinalImageTarget : kOutputTarget,
      [&] { return DebugViewPass::pass("present", kFinalImageTarget, ViewDecoding::Color); }, retain);
}

Renderer::~Renderer() = default;

PassDecl Renderer::importGBuffer(GLuint texture) {
  PassDecl pass;
  pass.name = "gbuffer";
  // Its own depth, cleared to the far plane: a pass that depth-tests against the G-buffer's sees nothing drawn.
  pass.writes = {{"gbuffer", TargetSize::full(), PassDecl::Write::Depth::Own, ""}};
  pass.run = [this, texture](PassContext& context) {
    // The texture the plan lent `gbuffer`: the colour attachment of the framebuffer bound for writing it.
    context.bindForWriting("gbuffer");
    glClearDepthf(1.0f);
    glClear(GL_DEPTH_BUFFER_BIT);
    GLint destination = 0;
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME,
                                          &destination);
    if (!externalGBufferSource_) externalGBufferSource_ = gl::FramebufferHandle::create();
    glBindFramebuffer(GL_FRAMEBUFFER, externalGBufferSource_.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("the caller's G-buffer texture " + std::to_string(texture) +
                    " cannot be read as an RGBA8 framebuffer attachment");
    // A byte-exact copy (no filtering, no blending), the same on GLES 2 and WebGL 1.
    const glm::ivec2 size = context.size("gbuffer");
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(destination));
    glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, size.x, size.y);
    glBindTexture(GL_TEXTURE_2D, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  };
  return pass;
}

HierarchyStorage Renderer::hierarchyStorage() const { return ao_->hierarchyStorage(); }

void Renderer::setScene(const Scene& scene) {
  GpuScene::Options options;
  options.allowUint32Indices = options_.allowUint32Indices;
  options.allowVertexArrays = options_.allowVertexArrays;
  options.batchStaticInstances = options_.batchStaticInstances;
  options.skinning = options_.skinning;
  scene_ = GpuScene(scene, caps_, options);
  // What posing needs (the hierarchy, skins, animations, and the instances and meshes they deform), not the images
  // nor the meshes' levels of detail, which the GPU holds now.
  sceneData_ = Scene();
  sceneData_.meshes = scene.meshes;
  for (Mesh& mesh : sceneData_.meshes) mesh.levels = {};
  sceneData_.instances = scene.instances;
  sceneData_.nodes = scene.nodes;
  sceneData_.skins = scene.skins;
  sceneData_.animations = scene.animations;
  sceneData_.cameras = scene.cameras;
  sceneBounds_ = scene.worldBounds();
  dropHistory();
  checkErrors("");
}

Camera Renderer::frameCamera(const Camera& camera, int width, int height, const FrameOptions& options) const {
  if (options.sceneCamera < 0) {
    Camera out = camera;
    out.width = width;
    out.height = height;
    return out;
  }
  if (static_cast<size_t>(options.sceneCamera) >= sceneData_.cameras.size())
    throw InputError("scene camera " + std::to_string(options.sceneCamera) + " is not in the scene (it has " +
                     std::to_string(sceneData_.cameras.size()) + ")");
  const ScenePose pose = evaluatePose(sceneData_, options.time, PoseOptions{options.animation, options.loop});
  return sceneCameraAt(sceneData_, options.sceneCamera, pose, sceneBounds_, width, height);
}

void Renderer::dropHistory() {
  if (hasPrevious_) ++historyDrops_;
  hasPrevious_ = false;
  historyFrames_ = 0;
  lastPose_ = ScenePose();
  pool_.dropHistory();
}

void Renderer::checkErrors(const std::string& after) const {
  if (!options_.checkGlErrors) return;
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", error);
    throw GlError(std::string("GL error ") + code + " " +
                  (after.empty() ? std::string("outside the passes (pending before the frame or from the scene "
                                               "upload)")
                                 : "after pass " + after));
  }
  if (!after.empty()) {
    const std::string leaked = gl::baselineStateDifferences();
    if (!leaked.empty()) throw GlError("pass " + after + " left GL state behind: " + leaked);
  }
}

bool Renderer::jitters(const RenderSettings& settings) {
  for (size_t row = 0; row < effectTable().size(); ++row)
    if (effectTable()[row].info.jitters && settings.enabled(row)) return true;
  return false;
}

const Renderer::OutputBuffers& Renderer::outputBuffers(const OutputTarget& output) {
  const glm::ivec2 size(output.width, output.height);
  OutputBuffers& known = outputBuffers_;
  // The default framebuffer's buffers never change. A framebuffer object's can, under the same name: its owner may
  // attach others, or delete it and make another, which GL may name alike (NVIDIA's driver reuses a name at once;
  // Mesa's does not): those are asked every frame (two queries; the page and the viewer draw into the default one).
  if (!known.known || known.framebuffer != output.framebuffer || known.size != size || output.framebuffer != 0) {
    GLint bound = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &bound);
    glBindFramebuffer(GL_FRAMEBUFFER, output.framebuffer);
    GLint depthBits = 0, stencilBits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depthBits);
    glGetIntegerv(GL_STENCIL_BITS, &stencilBits);
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(bound));
    known = {output.framebuffer, size, true, depthBits > 0, stencilBits > 0};
  }
  return known;
}

FrameContext Renderer::sceneFrame(const OutputTarget& output) {
  FrameContext frame;
  frame.linesOrPoints = !scene_.lines().empty();
  frame.transparent = scene_.hasTransparent();
  frame.transmission = scene_.hasTransmission();
  frame.forwardLighting = scene_.needsForwardLighting();
  frame.outputWidth = output.width;
  frame.outputHeight = output.height;
  const OutputBuffers& buffers = outputBuffers(output);
  frame.outputDepth = buffers.depth;
  frame.outputStencil = buffers.stencil;
  return frame;
}

void Renderer::beginFrame(const Camera& camera, const RenderSettings& settings, glm::ivec2 size,
                          const OutputTarget& output, const FrameOptions& options) {
  const double time = options.time;
  const glm::ivec2 outputSize(output.width, output.height);
  if (outputSize != lastOutputSize_) {
    dropHistory();
  } else if (size != lastSize_) {
    // A new render scale (dynamic resolution changes it often): the history targets go (the pool drops them with
    // the old size: TAA and the temporal AO start afresh, as after any drop), but the previous camera and pose stay,
    // since motion vectors are in uv units, the same at every size, and motion blur needs them this very frame.
    historyFrames_ = 0;
  }
  lastOutputSize_ = outputSize;
  lastSize_ = size;
  if (options.sceneCamera >= 0 && static_cast<size_t>(options.sceneCamera) >= sceneData_.cameras.size())
    throw InputError("scene camera " + std::to_string(options.sceneCamera) + " is not in the scene (it has " +
                     std::to_string(sceneData_.cameras.size()) + ")");
  // Another camera, or another projection: a cut, after which nothing of the previous frame applies.
  const int cameraKey = options.sceneCamera >= 0 ? options.sceneCamera : (camera.orthographic ? -2 : -1);
  if (hasPrevious_ && cameraKey != previousCameraKey_) dropHistory();
  previousCameraKey_ = cameraKey;
  pool_.beginFrame(size);
  // Sub-pixel jitter (Halton 2, 3, centred) while an effect that is on asks for it: 16 phases, the frames a still
  // image takes to converge under temporal antialiasing (TaaEffect.h).
  glm::vec2 jitter(0.0f);
  if (jitters(settings)) {
    const auto index = static_cast<std::uint32_t>(frameIndex_ % 16 + 1);
    jitter = glm::vec2(halton(index, 2), halton(index, 3)) - 0.5f;
  }
  FrameContext frame = sceneFrame(output);
  frame.hasPrevious = hasPrevious_;
  frame.index = frameIndex_;
  frame.historyFrames = historyFrames_;
  frame.time = time;
  frame.previousTime = options.previousTime.value_or(hasPrevious_ ? previousTime_ : time);
  frame.deltaTime = time - frame.previousTime;
  frame.frameInterval = options.frameInterval.value_or(frame.deltaTime > 0.0 ? frame.deltaTime : 1.0 / 60.0);
  frame_ = std::move(frame);

  // The scene's pose now and at the previous time (the last frame's pose when that is the one asked for).
  if (options.timer) options.timer->begin("pose");
  const PoseOptions poseOptions{options.animation, options.loop};
  ScenePose current = evaluatePose(sceneData_, time, poseOptions);
  const bool reuse = hasPrevious_ && !lastPose_.instanceWorld.empty() && frame_.previousTime == previousTime_ &&
                     poseOptions.animation == lastPoseOptions_.animation && poseOptions.loop == lastPoseOptions_.loop;
  // The last frame's pose by reference (not copied: it is kept until `current` replaces it at the end).
  ScenePose evaluatedPrevious;
  if (!reuse) evaluatedPrevious = evaluatePose(sceneData_, frame_.previousTime, poseOptions);
  const ScenePose& previous = reuse ? lastPose_ : evaluatedPrevious;
  scene_.setPose(current, previous);
  // The camera, where the pose puts a scene camera; the previous one is the previous frame's, or where the pose put
  // the scene camera at the previous time (the same when frames follow one another; the CLI's single frame has
  // no previous frame, but a previous time).
  if (options.sceneCamera >= 0) {
    frameSource_ = sceneCameraAt(sceneData_, options.sceneCamera, current, sceneBounds_, output.width, output.height);
  } else {
    frameSource_ = camera;
    frameSource_.width = output.width;
    frameSource_.height = output.height;
  }
  if (options.projectionShear != glm::vec2(0.0f) && !frameSource_.orthographic)
    throw InputError("a projection shear needs an orthographic camera");
  // At a render scale below 1 the frame is size.x x size.y but keeps the output's aspect (frame/Resolution.h); the
  // shear, in the output's pixels, shrinks with it.
  const float aspect = static_cast<float>(output.width) / static_cast<float>(output.height);
  const float scale = static_cast<float>(size.x) / static_cast<float>(output.width);
  frame_.camera = FrameCamera::from(frameSource_, size.x, size.y, jitter + options.projectionShift,
                                    options.projectionShear * scale, aspect);
  if (options.sceneCamera >= 0)
    frame_.previousCamera = FrameCamera::from(
        sceneCameraAt(sceneData_, options.sceneCamera, previous, sceneBounds_, output.width, output.height), size.x,
        size.y, glm::vec2(0.0f), glm::vec2(0.0f), aspect);
  else
    frame_.previousCamera = hasPrevious_ ? previousCamera_ : frame_.camera;
  lastPose_ = std::move(current);
  lastPoseOptions_ = poseOptions;
  if (options.timer) options.timer->end("pose");
  checkErrors("pose");
}

void Renderer::endFrame() {
  pool_.endFrame();
  previousCamera_ = frame_.camera;
  previousTime_ = frame_.time;
  hasPrevious_ = true;
  ++historyFrames_;
  ++frameIndex_;
  // Programs prepare() began for a frame that was not drawn (the state changed since) go.
  programs_.dropPending();
}

std::uint64_t Renderer::shapingId(const RenderSettings& settings) {
  const bool unchanged = keyedSettings_ && std::all_of(shapingParameters_.begin(), shapingParameters_.end(),
                                                       [&](const std::pair<size_t, size_t>& shaping) {
    const auto& [row, parameter] = shaping;
    return effectTable()[row].parameters[parameter].same(settings.rowAt(row), keyedSettings_->rowAt(row));
  });
  if (unchanged) return keyedId_;
  std::vector<std::string> values;
  values.reserve(shapingParameters_.size());
  for (const auto& [row, parameter] : shapingParameters_)
    values.push_back(effectTable()[row].parameters[parameter].get(settings.rowAt(row)));
  // Each combination seen keeps its id; a page whose user tries very many starts the table again (ids are never
  // reused, so a plan cached under a forgotten id is only made again).
  if (shapingIds_.size() >= kShapingIds) shapingIds_.clear();
  keyedId_ = shapingIds_.emplace(std::move(values), lastShapingId_ + 1).first->second;
  lastShapingId_ = std::max(lastShapingId_, keyedId_);
  keyedSettings_ = settings;
  return keyedId_;
}

Renderer::PlanKey Renderer::planKey(const RenderSettings& settings, const View& view,
                                    const FrameOptions& options) {
  PlanKey key;
  key.settings = shapingId(settings);
  key.view = view.name;
  key.size = {frame_.camera.width, frame_.camera.height};
  key.outputSize = {frame_.outputWidth, frame_.outputHeight};
  key.retain = options.retain;
  key.externalGBuffer = options.externalGBuffer;
  key.forwardLighting = frame_.forwardLighting;
  key.linesOrPoints = frame_.linesOrPoints;
  key.orthographic = frame_.camera.orthographic;
  key.outputDepth = frame_.outputDepth;
  return key;
}

const FramePlan& Renderer::cachedPlan(const RenderSettings& settings, const View& view,
                                      const FrameOptions& options) {
  PlanKey key = planKey(settings, view, options);
  if (!options_.cachePlans) plans_.clear();
  for (size_t i = 0; i < plans_.size(); ++i)
    if (plans_[i].key == key) {
      std::rotate(plans_.begin(), plans_.begin() + static_cast<long>(i), plans_.begin() + static_cast<long>(i) + 1);
      return *plans_.front().plan;
    }
  auto made = std::make_unique<FramePlan>(plan(settings, frame_, view, options.retain, options.externalGBuffer));
  ++plansMade_;
  if (plans_.size() == kCachedPlans) plans_.pop_back();
  plans_.insert(plans_.begin(), CachedPlan{std::move(key), std::move(made)});
  return *plans_.front().plan;
}

void Renderer::boundScene(bool externalGBuffer) {
  const glm::ivec2 size(frame_.camera.width, frame_.camera.height);
  frame_.sceneBounds = externalGBuffer || !options_.limitToScene
                           ? glm::ivec4(0, 0, size.x, size.y)
                           : scene_.coveredRect(frame_.camera.projection * frame_.camera.view, size);
}

void Renderer::run(const RenderSettings& settings, const View& view, const OutputTarget& output,
                   const FrameOptions& options) {
  for (const std::unique_ptr<Effect>& effect : effects_) effect->prepare(settings);
  scene_.chooseDetail(frame_.camera.view, frame_.camera.projection, frame_.camera.height,
                      settings.of<GBufferSettings>().lod);
  if (options_.cullToView)
    scene_.cullToView(frame_.camera.projection * frame_.camera.view);
  else
    scene_.drawWholeScene();
  boundScene(options.externalGBuffer != 0);
  // What surfaces drawn after the lighting need (frame/SurfaceShading.h): the fog these settings apply; the light
  // comes from the lighting pass as it runs.
  surfaces_.light.published = false;
  surfaces_.fog = surfaceFog(settings.of<FogSettings>(), frame_.camera.view);
  plan_ = &cachedPlan(settings, view, options);
  for (size_t i = 0; i < plan_->passes().size(); ++i)
    if (plan_->passes()[i].live) runPass(*plan_, i, pool_, settings, output, options.timer);
}

void Renderer::runPass(const FramePlan& plan, size_t index, RenderTargetPool& pool, const RenderSettings& settings,
                       const OutputTarget& output, PassTimer* timer) {
  const PlannedPass& pass = plan.passes()[index];
  PassContext context(plan, static_cast<int>(index), pool, frame_, settings, scene_, output, resources_);
  if (timer) timer->begin(pass.decl.name);
  pass.decl.run(context);
  context.finish();
  if (timer) timer->end(pass.decl.name);
  checkErrors(pass.decl.name);
}

std::optional<RenderSettings> Renderer::quickStartSettings(const RenderSettings& settings) {
  // The effects that add passes of their own over the frame (EffectInfo::waitsForFullFrame): each is a program, and
  // on SwiftShader a pipeline compiled at its first draw, that the first image can do without.
  RenderSettings cheap = settings;
  bool changed = false;
  for (const EffectEntry& row : effectTable())
    if (row.info.waitsForFullFrame && settings.enabled(row.info.name)) {
      cheap.set(row.info.name, "off");
      changed = true;
    }
  if (!changed) return std::nullopt;
  // Below scale 1 the cheap frame's own upscale pass (FXAA no longer does it) is the bilinear one, the cheapest.
  cheap.of<ResolutionSettings>().upscale = UpscaleFilter::Bilinear;
  return cheap;
}

Renderer::Warm& Renderer::smallTargets(bool outputDepth) {
  if (!warm_) {
    warm_ = std::make_unique<Warm>();
    warm_->pool = std::make_unique<RenderTargetPool>(caps_);
  }
  // The small output has a depth buffer where the frame's output has one (FrameContext::outputDepth: the forward
  // lighting may draw straight into it), so the small plan's passes draw with the state the frame's will.
  if (!warm_->output || warm_->outputDepth != outputDepth) {
    warm_->outputDepth = outputDepth;
    warm_->output = gl::RenderTarget(
        "quick-start warm output", kWarmSize, kWarmSize, GL_NEAREST,
        outputDepth ? gl::RenderTarget::Depth::Renderbuffer : gl::RenderTarget::Depth::None, caps_.depth24);
  }
  return *warm_;
}

FrameContext Renderer::smallFrame(FrameContext like, const Camera& source, bool upscaled) {
  // kWarmSize, half of it where the frame is upscaled (so that the plan has the same passes and programs), without
  // history. The AO's depth hierarchy needs 32 pixels for its 5 levels.
  const glm::ivec2 size = upscaled ? glm::ivec2(kWarmSize / 2) : glm::ivec2(kWarmSize);
  like.hasPrevious = false;
  like.historyFrames = 0;
  like.outputWidth = like.outputHeight = kWarmSize;
  like.camera = FrameCamera::from(source, size.x, size.y);
  like.previousCamera = like.camera;
  return like;
}

void Renderer::runSmall(const RenderSettings& settings, const FramePlan& plan, size_t& next, size_t passes,
                        bool reportWarmed) {
  for (const std::unique_ptr<Effect>& effect : effects_) effect->prepare(settings);
  surfaces_.light.published = false;
  surfaces_.fog = surfaceFog(settings.of<FogSettings>(), frame_.camera.view);
  OutputTarget output;
  output.framebuffer = warm_->output.framebuffer();
  output.width = output.height = kWarmSize;
  boundScene(false);
  warm_->pool->beginFrame({frame_.camera.width, frame_.camera.height});
  const std::vector<PlannedPass>& planned = plan.passes();
  for (size_t ran = 0; next < planned.size() && ran < passes; ++next) {
    if (!planned[next].live) continue;
    const double start = TimeSpent::nowMs();
    runPass(plan, next, *warm_->pool, settings, output, nullptr);
    const double end = TimeSpent::nowMs();
    if (reportWarmed)
      quickStart_.warmed.push_back({planned[next].decl.name, frameIndex_, start - createdAtMs_, end - start});
    ++ran;
  }
  warm_->pool->endFrame();
}

void Renderer::warmPasses(const RenderSettings& settings, bool upscaled) {
  Warm& warm = smallTargets(frame_.outputDepth);
  FrameContext warmFrame = smallFrame(frame_, frameSource_, upscaled);
  std::swap(frame_, warmFrame);  // frame_ is the warm frame's while it plans and runs, the cheap frame's after
  const PlanKey key = planKey(settings, View::Final, FrameOptions{});
  if (!warm.plan || !(key == warm.key)) {
    // A new plan (the first, or the settings changed since): its passes from the first (those warmed already cost
    // little the second time).
    warm.plan = std::make_unique<FramePlan>(plan(settings, frame_, View::Final, {}));
    warm.key = key;
    warm.next = 0;
  }
  runSmall(settings, *warm.plan, warm.next, kWarmPassesPerFrame, true);
  std::swap(frame_, warmFrame);
  if (warm.next >= warm.plan->passes().size()) quickStartOver_ = true;  // every pass warmed: the next frame is full
}

size_t Renderer::prepare(const Camera& camera, const RenderSettings& settings, const OutputTarget& output,
                         const FrameOptions& options) {
  settings.validate();
  const gl::DeferredBindings deferredBindings;
  const glm::ivec2 size = frameSize(settings, output, options);
  const std::optional<RenderSettings> cheap = cheapFrameSettings(settings, View::Final, options);
  const RenderSettings& drawn = cheap ? *cheap : settings;
  // The scene posed at the frame's time, as the frame will pose it (its draws bind what the pose uploads).
  const ScenePose pose = evaluatePose(sceneData_, options.time, PoseOptions{options.animation, options.loop});
  scene_.setPose(pose, pose);
  const FrameContext like = sceneFrame(output);
  smallTargets(like.outputDepth);
  const bool upscaled = size != glm::ivec2(output.width, output.height);
  FrameContext rehearsed = smallFrame(like, frameCamera(camera, output.width, output.height, options), upscaled);
  std::swap(frame_, rehearsed);
  const size_t pendingBefore = programs_.pending();
  {
    // The passes run for the programs they ask for; their draws, with stand-ins, are withheld (a stand-in does not
    // write what the real program would: the G-buffer's several draw buffers).
    struct Withheld {
      Renderer& renderer;
      explicit Withheld(Renderer& r) : renderer(r) { set(true); }
      ~Withheld() { set(false); }
      void set(bool withheld) {
        renderer.triangle_.withholdDraws(withheld);
        renderer.scene_.withholdDraws(withheld);
      }
    } withheld(*this);
    const ProgramCache::Rehearsal rehearsal(programs_);
    const FramePlan rehearsedPlan = plan(drawn, frame_, View::Final, {});
    size_t next = 0;
    runSmall(drawn, rehearsedPlan, next, rehearsedPlan.passes().size(), false);
  }
  std::swap(frame_, rehearsed);
  // Sent to the driver now: a browser's command buffer holds them until a flush.
  glFlush();
  return programs_.pending() - pendingBefore;
}

void Renderer::fullFrameDrawn() {
  lastFrameCheap_ = false;
  if (quickStart_.firstFullFrame >= 0) return;
  quickStart_.firstFullFrame = static_cast<std::int64_t>(frameIndex_);
  quickStart_.fullAtMs = TimeSpent::nowMs() - createdAtMs_;
  quickStartOver_ = true;
  warm_.reset();
}

glm::ivec2 Renderer::frameSize(const RenderSettings& settings, const OutputTarget& output,
                               const FrameOptions& options) const {
  const int limit = caps_.maxRenderSize();
  if (output.width < 1 || output.height < 1 || output.width > limit || output.height > limit)
    throw InputError("output size " + std::to_string(output.width) + "x" + std::to_string(output.height) +
                     " is outside what this context can render (1 .. " + std::to_string(limit) + " per side)");
  const float scale = options.renderScale.value_or(settings.of<ResolutionSettings>().scale);
  if (!(scale > 0.0f && scale <= 1.0f))
    throw InputError("render scale " + std::to_string(scale) + " is outside 0 .. 1");
  // A G-buffer the caller drew is at the output's size: such a frame renders at it.
  return options.externalGBuffer != 0 ? glm::ivec2(output.width, output.height)
                                      : renderSize({output.width, output.height}, scale);
}

std::optional<RenderSettings> Renderer::cheapFrameSettings(const RenderSettings& settings, const View& view,
                                                           const FrameOptions& options) const {
  if (quickStartOver_ || !options.allowCheapFrame || !settings.of<ResolutionSettings>().quickStart ||
      !(view == View::Final) || options.externalGBuffer != 0 || quickStart_.cheapFrames >= kMaxCheapFrames)
    return std::nullopt;
  return quickStartSettings(settings);
}

void Renderer::render(const Camera& camera, const RenderSettings& settings, const View& view,
                      const OutputTarget& output, const FrameOptions& options) {
  checkErrors("");  // an error the application left pending is reported as such, not blamed on a pass
  settings.validate();
  // The frame's bindings made only where a call needs them (gl/BindingCache.h); all of them made on return.
  const gl::DeferredBindings deferredBindings;
  const glm::ivec2 size = frameSize(settings, output, options);
  // Quick start: the cheap frame, and after the first the next passes of the full one warmed.
  if (const std::optional<RenderSettings> cheap = cheapFrameSettings(settings, view, options)) {
    beginFrame(camera, *cheap, size, output, options);
    run(*cheap, view, output, options);
    if (quickStart_.cheapFrames > 0) warmPasses(settings, size != glm::ivec2(output.width, output.height));
    ++quickStart_.cheapFrames;
    lastFrameCheap_ = true;
    endFrame();
    return;
  }
  if (view == View::Split) {
    // Two frames of one frame context into one output: the compared switch off, then on over the right half. The
    // frame starts as the right half's (its jitter, when that half has temporal antialiasing); the left half draws
    // without the jitter where it has none of its own, as it would alone.
    RenderSettings off = settings, on = settings;
    const std::string compared = parseCompare(view.compare);
    off.set(compared, "off");
    on.set(compared, "on");
    beginFrame(camera, on, size, output, options);
    const FrameContext right = frame_;
    if (!jitters(off))
      frame_.camera = FrameCamera::from(frameSource_, size.x, size.y, glm::vec2(0.0f), glm::vec2(0.0f),
                                        static_cast<float>(output.width) / static_cast<float>(output.height));
    run(off, View::Final, output, options);
    frame_ = right;
    OutputTarget rightHalf = output;
    rightHalf.region = {output.width / 2, 0, output.width - output.width / 2, output.height};
    run(on, View::Final, rightHalf, options);
  } else {
    beginFrame(camera, settings, size, output, options);
    parseView(view.name);
    run(settings, view, output, options);
  }
  fullFrameDrawn();
  endFrame();
}

const FramePlan& Renderer::lastPlan() const {
  static const FramePlan none;
  return plan_ ? *plan_ : none;
}

const gl::RenderTarget& Renderer::retained(const std::string& target) {
  const int version = plan_ ? plan_->retainedVersion(target) : -1;
  if (version < 0) throw InputError("target '" + target + "' was not retained by the last frame");
  const TargetVersion& v = plan_->versions()[static_cast<size_t>(version)];
  if (!v.slot) throw InputError("target '" + target + "' is not a pooled target");
  return pool_.slot(*v.slot);
}

}  // namespace obscura
