// The public Renderer (include/obscura/obscura.h): a facade over the internal one (renderer/Renderer.h) that keeps the
// settings, the scene, the camera conventions and the caller's-G-buffer targets, and turns every internal error into
// obscura::api::Error.
#include <chrono>
#include <cmath>

#include "base/Error.h"
#include "base/Text.h"
#include "encoding/LinearDepthPacking.h"
#include "encoding/NormalEncoding.h"
#include "frame/FullscreenPass.h"
#include "frame/FullscreenTriangle.h"
#include "gl/EmbeddedShaders.h"
#include "gl/GlApi.h"
#include "gl/PipelineState.h"
#include "gl/Program.h"
#include "gl/RenderTarget.h"
#include "obscura/obscura.h"
#include "renderer/Renderer.h"
#include "scene/BuiltinScene.h"
#include "scene/Camera.h"
#include "scene/GltfLoader.h"
#include "scene/SceneScale.h"

namespace obscura::api {
namespace {

// Runs `body`, turning the internal errors (InputError, GlError, PipelineError, ...) into the public one.
template <typename F>
auto guarded(F&& body) -> decltype(body()) {
  try {
    return body();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(e.what());
  }
}

obscura::Camera internalCamera(const Camera& camera, int width, int height) {
  obscura::Camera c;
  c.eye = {camera.eye[0], camera.eye[1], camera.eye[2]};
  c.target = {camera.target[0], camera.target[1], camera.target[2]};
  c.up = {camera.up[0], camera.up[1], camera.up[2]};
  c.fovyDegrees = camera.fovyDegrees;
  c.near = camera.near;
  c.far = camera.far;
  c.orthographic = camera.orthographic;
  c.ymag = camera.ymag;
  c.width = width;
  c.height = height;
  c.validate("camera");
  return c;
}

Camera publicCamera(const obscura::Camera& c) {
  Camera camera;
  for (int i = 0; i < 3; ++i) {
    camera.eye[i] = c.eye[i];
    camera.target[i] = c.target[i];
    camera.up[i] = c.up[i];
  }
  camera.fovyDegrees = c.fovyDegrees;
  camera.near = c.near;
  camera.far = c.far;
  camera.orthographic = c.orthographic;
  camera.ymag = c.ymag;
  return camera;
}

std::size_t triangleCount(const Scene& scene) {
  std::size_t triangles = 0;
  for (const Instance& instance : scene.instances)
    triangles += scene.meshes[static_cast<std::size_t>(instance.mesh)].indices.size() / 3;
  return triangles;
}

// Multiplies the AO result into the caller's colour: blending dst * src (GL_ZERO, GL_SRC_COLOR) on RGB, alpha kept.
constexpr const char* kCompositeVertex = R"(#version 100
attribute vec2 a_position;
varying vec2 v_uv;
void main() {
  v_uv = a_position * 0.5 + 0.5;
  gl_Position = vec4(a_position, 0.0, 1.0);
}
)";
constexpr const char* kCompositeFragment = R"(#version 100
precision mediump float;
uniform sampler2D u_ao;
varying vec2 v_uv;
void main() { gl_FragColor = vec4(texture2D(u_ao, v_uv).rgb, 1.0); }
)";

}  // namespace

const char* version() { return OBSCURA_VERSION_STRING; }

const char* gbufferGlsl() {
  // Embedded from shaders_es2/lib/obscura_gbuffer.glsl.
  static const std::string text = [] {
    for (const EmbeddedShader& shader : embeddedShaders())
      if (shader.path == "lib/obscura_gbuffer.glsl") return std::string(shader.text);
    return std::string();
  }();
  return text.c_str();
}

struct Renderer::Impl {
  explicit Impl(const Options& options) : renderer(loadCaps(options), rendererOptions(options)) {}

  static gl::GlCaps loadCaps(const Options& options) {
#if !OBSCURA_GL_DIRECT
    if (!options.getProcAddress)
      throw Error("Renderer::Options::getProcAddress is required natively (eglGetProcAddress, glfwGetProcAddress, "
                  "...)");
    std::string missing;
    if (!gl::loadGles2(options.getProcAddress, &missing))
      throw Error("the current context lacks the GLES 2 entry point " + missing);
#else
    (void)options;
#endif
    return gl::GlCaps::query();
  }
  static RendererOptions rendererOptions(const Options& options) {
    RendererOptions o;
    o.checkGlErrors = options.checkGlErrors;
    return o;
  }

  void adoptScene(Scene scene, const std::vector<std::string>& warnings) {
    renderer.setScene(scene);
    info = SceneInfo();
    info.name = scene.name;
    info.triangles = triangleCount(scene);
    info.warnings = warnings;
    info.defaultRadius = defaultAoRadius(scene);
    for (const Animation& animation : scene.animations) info.animations.push_back(animation.name);
    bounds = scene.worldBounds();
    builtin = false;
    empty = scene.instances.empty();
    if (!radiusGiven) settings.set("ao.radius", formatShortest(info.defaultRadius));
  }

  // One frame of the internal renderer, timed, with the frame counter.
  void frame(const obscura::Camera& camera, const View& frameView, const OutputTarget& output,
             FrameOptions options) {
    options.time = time;
    const auto start = std::chrono::steady_clock::now();
    renderer.render(camera, settings, frameView, output, options);
    cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ++frames;
    lastWidth = output.width;
    lastHeight = output.height;
  }

  const gl::RenderTarget& resultTarget(int width, int height) {
    if (!aoResult || aoResult.width() != width || aoResult.height() != height)
      aoResult = gl::RenderTarget("obscura-ao-result", width, height, GL_NEAREST, gl::RenderTarget::Depth::None,
                                  renderer.caps().depth24);
    return aoResult;
  }

  obscura::Renderer renderer;
  RenderSettings settings;
  View currentView = View::Final;
  double time = 0.0;
  bool radiusGiven = false;
  SceneInfo info;
  Bounds bounds;
  bool builtin = true;
  bool empty = false;

  gl::RenderTarget callerGBuffer;  // beginGBuffer's
  gl::RenderTarget aoResult;       // ambientOcclusion's
  gl::Program composite;  // strict: its one uniform, u_ao, is set by name
  FullscreenTriangle triangle;

  std::uint64_t frames = 0;
  double cpuMs = 0.0;
  int lastWidth = 0, lastHeight = 0;
};

Renderer::Renderer(const Options& options) {
  guarded([&] {
    impl_ = std::make_unique<Impl>(options);
    setBuiltinScene();
  });
}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

void Renderer::setBuiltinScene() {
  guarded([&] {
    impl_->adoptScene(makeBuiltinScene(), {});
    impl_->builtin = true;
  });
}

void Renderer::setSceneFile(const std::string& path) {
  guarded([&] {
    GltfLoadReport report;
    impl_->adoptScene(loadGltfFile(path, &report), report.warnings);
  });
}

void Renderer::setSceneMemory(const void* bytes, std::size_t size, const std::string& name,
                              const std::map<std::string, std::vector<std::uint8_t>>& sideFiles) {
  guarded([&] {
    const auto* begin = static_cast<const std::uint8_t*>(bytes);
    GltfLoadReport report;
    impl_->adoptScene(loadGltfMemory(std::vector<std::uint8_t>(begin, begin + size), name, sideFiles, &report),
                      report.warnings);
  });
}

void Renderer::clearScene() {
  guarded([&] {
    Scene scene;
    scene.name = "(none)";
    scene.designedAoRadius = 1.0f;
    impl_->adoptScene(std::move(scene), {});
  });
}

SceneInfo Renderer::scene() const { return impl_->info; }

Camera Renderer::sceneCamera(int width, int height) const {
  return guarded([&] {
    if (impl_->builtin) return publicCamera(builtinSceneCamera(width, height));
    if (impl_->empty) return Camera();
    return publicCamera(obscura::Camera::fit(impl_->bounds, width, height));
  });
}

void Renderer::set(const std::string& name, const std::string& value) {
  guarded([&] {
    impl_->settings.set(name, value);
    if (RenderSettings::canonicalName(name) == "ao.radius") impl_->radiusGiven = true;
  });
}

void Renderer::set(const std::string& name, double value) { set(name, formatShortest(static_cast<float>(value))); }

std::string Renderer::get(const std::string& name) const {
  return guarded([&] { return impl_->settings.get(name); });
}

std::vector<ParameterInfo> Renderer::parameters() {
  const RenderSettings defaults;
  std::vector<ParameterInfo> out;
  for (const obscura::ParameterInfo& p : RenderSettings::parameters()) {
    ParameterInfo info;
    info.name = p.name;
    info.alias = p.alias;
    info.effect = p.effect;
    info.kind = parameterKindName(p.kind);
    info.range = p.range;
    info.help = p.help;
    info.defaultValue = defaults.get(p.name);
    info.min = p.min;
    info.max = p.max;
    info.choices = p.choices;
    out.push_back(std::move(info));
  }
  return out;
}

void Renderer::setView(const std::string& view) {
  guarded([&] {
    const std::string compared = impl_->currentView.compare;
    impl_->currentView = parseView(view);
    impl_->currentView.compare = compared;
  });
}
std::string Renderer::view() const { return impl_->currentView.name; }
std::vector<std::string> Renderer::views() { return frameViewNames(); }
void Renderer::setCompare(const std::string& switchName) {
  guarded([&] { impl_->currentView.compare = parseCompare(switchName); });
}
std::string Renderer::compare() const { return impl_->currentView.compare; }

void Renderer::setTime(double seconds) {
  if (!std::isfinite(seconds)) throw Error("time: expected a finite number of seconds");
  impl_->time = seconds;
}
double Renderer::time() const { return impl_->time; }

void Renderer::render(const Camera& camera, const Framebuffer& output) {
  guarded([&] {
    OutputTarget target;
    target.framebuffer = output.framebuffer;
    target.width = output.width;
    target.height = output.height;
    impl_->frame(internalCamera(camera, output.width, output.height), impl_->currentView, target, {});
  });
}

void Renderer::beginGBuffer(int width, int height) {
  guarded([&] {
    const int limit = impl_->renderer.caps().maxRenderSize();
    if (width < 1 || height < 1 || width > limit || height > limit)
      throw Error("beginGBuffer: " + std::to_string(width) + "x" + std::to_string(height) +
                  " is outside what this context can render (1 .. " + std::to_string(limit) + " per side)");
    gl::RenderTarget& target = impl_->callerGBuffer;
    if (!target || target.width() != width || target.height() != height)
      target = gl::RenderTarget("obscura-caller-gbuffer", width, height, GL_NEAREST,
                                gl::RenderTarget::Depth::Renderbuffer, impl_->renderer.caps().depth24);
    target.bindForDrawing();
    // The background, as the G-buffer pass clears it: normal (0, 0, 1), depth code 65535 (GBufferEffect.cpp).
    const auto normal = encodeNormal(glm::vec3(0.0f, 0.0f, 1.0f));
    glClearColor(LinearDepthPacking::channelFromByte(normal[0]), LinearDepthPacking::channelFromByte(normal[1]), 1.0f,
                 1.0f);
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  });
}

GBuffer Renderer::gbuffer() const {
  const gl::RenderTarget& target = impl_->callerGBuffer;
  if (!target) throw Error("gbuffer: no G-buffer yet (call beginGBuffer first)");
  return {target.color().id(), target.width(), target.height()};
}

unsigned int Renderer::ambientOcclusion(const Camera& camera) { return ambientOcclusion(camera, gbuffer()); }

unsigned int Renderer::ambientOcclusion(const Camera& camera, const GBuffer& gbuffer) {
  return guarded([&] {
    const gl::RenderTarget& result = impl_->resultTarget(gbuffer.width, gbuffer.height);
    renderView("ao", camera, gbuffer, {result.framebuffer(), result.width(), result.height()});
    // Obscura's own framebuffer is no business of the caller's: the default one is bound, as documented.
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return static_cast<unsigned int>(result.color().id());
  });
}

void Renderer::renderView(const std::string& view, const Camera& camera, const GBuffer& gbuffer,
                          const Framebuffer& output) {
  guarded([&] {
    if (gbuffer.texture == 0) throw Error("renderView: the G-buffer texture is 0");
    if (gbuffer.width != output.width || gbuffer.height != output.height)
      throw Error("renderView: the G-buffer is " + std::to_string(gbuffer.width) + "x" +
                  std::to_string(gbuffer.height) + ", the output " + std::to_string(output.width) + "x" +
                  std::to_string(output.height) + "; they must be the same size");
    const View frameView = parseView(view);
    if (frameView == View::Split) throw Error("renderView: the split view needs a scene (render())");
    OutputTarget target;
    target.framebuffer = output.framebuffer;
    target.width = output.width;
    target.height = output.height;
    FrameOptions options;
    options.externalGBuffer = gbuffer.texture;
    impl_->frame(internalCamera(camera, output.width, output.height), frameView, target, options);
  });
}

void Renderer::compositeAmbientOcclusion(const Framebuffer& target) {
  guarded([&] {
    Impl& impl = *impl_;
    if (!impl.aoResult) throw Error("compositeAmbientOcclusion: no AO yet (call ambientOcclusion first)");
    if (target.width != impl.aoResult.width() || target.height != impl.aoResult.height())
      throw Error("compositeAmbientOcclusion: the framebuffer is " + std::to_string(target.width) + "x" +
                  std::to_string(target.height) + ", the AO " + std::to_string(impl.aoResult.width()) + "x" +
                  std::to_string(impl.aoResult.height()));
    if (!impl.composite)
      impl.composite = gl::Program("obscura-composite-ao", kCompositeVertex, kCompositeFragment, /*strict=*/true);
    if (target.framebuffer != kBoundFramebuffer) glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
    glViewport(0, 0, target.width, target.height);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ZERO, GL_SRC_COLOR, GL_ZERO, GL_ONE);
    {
      FullscreenDraw draw(impl.composite, impl.triangle);
      draw.texture("u_ao", impl.aoResult.color());
      draw.draw();
    }
    gl::restoreBaselineState();  // the blending and the viewport
  });
}

Stats Renderer::stats() const {
  Stats stats;
  const Impl& impl = *impl_;
  stats.width = impl.lastWidth;
  stats.height = impl.lastHeight;
  stats.frames = impl.frames;
  stats.cpuMs = impl.cpuMs;
  for (const PlannedPass& pass : impl.renderer.lastPlan().passes()) {
    if (!pass.live) continue;
    stats.passesRun.push_back(pass.decl.name);
    for (const std::string& absorbed : pass.absorbed) stats.passesDoneBy.emplace_back(absorbed, pass.decl.name);
  }
  stats.pooledTargets = static_cast<int>(impl.renderer.pooledTargets());
  stats.historyDrops = impl.renderer.historyDrops();
  return stats;
}

}  // namespace obscura::api
