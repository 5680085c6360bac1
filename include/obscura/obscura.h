#pragma once
// Obscura's public C++ API: image-space effects (ambient obscurance from one RGBA8 G-buffer, tone mapping, TAA,
// motion blur, FXAA, ...) on the caller's OpenGL ES 2.0 context (WebGL 1 under Emscripten).
//
// This header and the others in include/obscura/ are the whole public surface: they include no GL header and nothing
// of Obscura's internals, and keep source compatibility within a major version (CHANGELOG.md lists every change).
// docs/api.md walks through them. In short:
//
//   obscura::api::Renderer renderer({getProcAddress});   // on the caller's current GLES 2 context
//   renderer.setSceneFile("model.glb");                  // or setSceneMemory, or setBuiltinScene
//   renderer.set("ao.radius", "0.5");                    // the names of the CLI, the page's URL and the JS API
//   renderer.render(renderer.sceneCamera(w, h), {fbo, w, h});
//
// AO on the caller's own geometry: draw the meshes into beginGBuffer() with the GLSL ES 1.00 chunk
// obscura_gbuffer.glsl (in <prefix>/share/obscura/glsl; also gbufferGlsl()), or hand over an RGBA8 texture in the
// same layout; then ambientOcclusion() returns the AO texture and compositeAmbientOcclusion() multiplies it into a
// framebuffer.
//
// Threading and GL: every call needs the context the Renderer was made on to be current, on the thread using it.
// Calls expect the GL state at the baseline every pass of Obscura starts from, and leave it there: no program,
// buffers, textures or vertex attribute arrays bound, depth test, blending, culling, scissor, polygon offset and
// stencil off, texture unit 0 active. The framebuffer binding is the caller's business: bind yours again after a
// call. Errors throw obscura::api::Error.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "obscura/version.h"

namespace obscura::api {

// What Obscura refuses: an unknown parameter or a value out of its range, a file that is not valid glTF, a context
// that cannot run it (no highp float in fragment shaders), a GL error with checkGlErrors. what() is one line for a
// person, e.g. "ao.radius: 0 is out of range (0.0001 .. 1e+06 scene units)".
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The library's version at run time ("0.2.0"); OBSCURA_VERSION_STRING is the headers'.
const char* version();

// The text of the public GLSL ES 1.00 chunk obscura_gbuffer.glsl (also installed in <prefix>/share/obscura/glsl):
// obscuraGBuffer(viewNormal, viewDepth, near, far) packs a fragment's normal and depth as Obscura's G-buffer does.
const char* gbufferGlsl();

// Resolves GLES 2 entry points of the current context: eglGetProcAddress, glfwGetProcAddress, SDL_GL_GetProcAddress.
using ProcAddressLoader = void* (*)(const char* name);

// A symmetric perspective camera: right-handed, OpenGL conventions (looks down -z in view space). Units are the
// scene's (metres for the built-in scene).
struct Camera {
  float eye[3] = {0.0f, 1.6f, 6.0f};
  float target[3] = {0.0f, 1.0f, 0.0f};
  float up[3] = {0.0f, 1.0f, 0.0f};
  float fovyDegrees = 50.0f;  // vertical field of view
  float near = 0.1f;          // an orthographic camera's may be 0
  float far = 100.0f;
  bool orthographic = false;  // parallel projection, `ymag` scene units above and below the view's axis
  float ymag = 1.0f;          // orthographic: the half height of the view
};

// Framebuffer::framebuffer meaning "whichever framebuffer is bound when the call is made" (for callers whose
// framebuffers have no GL name Obscura can see: a WebGL page's own WebGLFramebuffer objects).
constexpr unsigned int kBoundFramebuffer = 0xFFFFFFFFu;

// A framebuffer of the caller's: its GL name (0: the window's or canvas's own) and size in pixels.
struct Framebuffer {
  unsigned int framebuffer = 0;  // a GLuint
  int width = 0, height = 0;
};

// One parameter of the frame, from the effect table (the same list as `obscura-render --help` and the page's
// controls). Names are stable (docs/api.md, "Stability").
struct ParameterInfo {
  std::string name;    // "ao.radius", "tonemap.operator", "fxaa"; "preset" for the frame's quality preset
  std::string alias;   // an older name also accepted ("radius"), or ""
  std::string effect;  // "ao", "tonemap", ...; "" for "preset"
  std::string kind;    // "switch" (on/off), "number", "integer", "choice"
  std::string range;   // for people: "0.0001 .. 1e+06 (scene units)"
  std::string help;
  std::string defaultValue;          // as text, as get() returns it
  double min = 0.0, max = 0.0;       // number and integer
  std::vector<std::string> choices;  // switch and choice; for a number, words it takes besides numbers ("auto")
};

// What a scene is, once set.
struct SceneInfo {
  std::string name;
  std::size_t triangles = 0;
  std::vector<std::string> warnings;  // what the glTF loader repaired or ignored
  // The AO radius the scene gets when nobody sets one: 5 % of its bounding sphere's diameter to two significant
  // figures (the built-in scene: 1). set("ao.radius", ...) overrides it, and a radius set stays across scenes.
  float defaultRadius = 1.0f;
  std::vector<std::string> animations;  // names ("" for an unnamed one), in the file's order
};

// The last frame, for people and tests.
struct Stats {
  int width = 0, height = 0;
  std::uint64_t frames = 0;      // frames rendered by this Renderer (render, ambientOcclusion, renderView)
  double cpuMs = 0.0;            // wall-clock time of the last frame's call: GL commands issued, not GPU completion
  // The passes the last frame ran, in order ("gbuffer", "hierarchy", "sao", "blur-h", "blur-v", "lighting", ...),
  // and passes another did the work of ({"tonemap", "lighting"}: the lighting applied the tone curve).
  std::vector<std::string> passesRun;
  std::vector<std::pair<std::string, std::string>> passesDoneBy;
  int pooledTargets = 0;         // render targets the frame keeps allocated
  int historyDrops = 0;          // how often the history (previous frame, TAA and motion histories) was dropped
};

// A G-buffer in Obscura's layout (docs/api.md, "The G-buffer layout"): an RGBA8 texture, sampled NEAREST, of the
// size of the frame. RG: the view-space normal, octahedral, 254 steps per axis; BA: 16-bit linear depth
// (-z_view - near) / (far - near), high byte in B; 65535 (B = A = 1) marks the background.
struct GBuffer {
  unsigned int texture = 0;  // a GLuint
  int width = 0, height = 0;
};

class Renderer {
 public:
  struct Options {
    // Natively required: how to load the GLES 2 entry points of the current context. Ignored under Emscripten.
    ProcAddressLoader getProcAddress = nullptr;
    // glGetError and the baseline GL state checked after every pass (a failure throws Error naming the pass), and
    // strict programs. For tests and debugging: each check waits for the GPU.
    bool checkGlErrors = false;
  };

  // Builds every program of the frame on the current context and starts with the built-in scene. Throws Error if the
  // context cannot run Obscura.
  explicit Renderer(const Options& options);
  ~Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // --- The scene. Each call replaces it (and drops the history of earlier frames); on Error the previous stays.
  void setBuiltinScene();
  // A .glb or .gltf file; a .gltf's external buffers and images are read beside it.
  void setSceneFile(const std::string& path);
  // A .glb or .gltf in memory. `name` appears in messages; a .gltf's external files come in `sideFiles`, keyed by
  // the URI the file uses.
  void setSceneMemory(const void* bytes, std::size_t size, const std::string& name,
                      const std::map<std::string, std::vector<std::uint8_t>>& sideFiles = {});
  // No scene at all: for frames whose G-buffer the caller draws (ambientOcclusion).
  void clearScene();
  SceneInfo scene() const;
  // A camera that frames the scene at rest for a width x height output (the built-in scene's own view for it).
  Camera sceneCamera(int width, int height) const;

  // --- Parameters, by the names used everywhere (ParameterInfo::name or its alias; docs/api.md lists them).
  // Sets one from text ("on", "0.5", "agx", "high"); throws Error naming the parameter, the value and the range, and
  // changes nothing, when refused.
  void set(const std::string& name, const std::string& value);
  void set(const std::string& name, double value);
  // The value as text that set() accepts; for "preset", the preset the values match or "".
  std::string get(const std::string& name) const;
  static std::vector<ParameterInfo> parameters();
  // What render() draws: "final" (the finished image), "split" (the final image with the switch compare() names
  // off left of the middle and on right of it), or a target's debug view ("ao", "normals", "depth", ...: views()).
  void setView(const std::string& view);
  std::string view() const;
  static std::vector<std::string> views();
  void setCompare(const std::string& switchName);  // the switch "split" compares: "ao" at first, or any switch
  std::string compare() const;

  // --- Time: the scene's animations are sampled at this time in seconds (the first animation plays; 0 at first).
  void setTime(double seconds);
  double time() const;

  // --- Rendering the scene into the caller's framebuffer (all of it; its size is the frame's).
  void render(const Camera& camera, const Framebuffer& output);

  // --- AO (and the other G-buffer views) on the caller's own geometry.
  // Binds an Obscura-owned framebuffer of width x height (an RGBA8 G-buffer texture with a depth renderbuffer),
  // cleared to the background, with its viewport set. The caller then draws its meshes (depth test on, GL_LESS)
  // with a fragment shader that writes obscuraGBuffer(...) from obscura/obscura_gbuffer.glsl, using the same
  // camera's near and far, and calls ambientOcclusion(camera).
  void beginGBuffer(int width, int height);
  // That G-buffer, valid after beginGBuffer (e.g. to run a view of it, or to read it).
  GBuffer gbuffer() const;
  // Runs the AO (its depth hierarchy, estimator, blur and upsampling, as the parameters say) on the G-buffer drawn
  // since beginGBuffer, or on the caller's own texture, and returns an RGBA8 texture of the same size that the
  // Renderer owns until the next call: RGB the ambient visibility (1 open, 0 fully occluded), A 1. The camera must
  // be the one the G-buffer was drawn with. Leaves the default framebuffer (0) bound.
  unsigned int ambientOcclusion(const Camera& camera);
  unsigned int ambientOcclusion(const Camera& camera, const GBuffer& gbuffer);
  // Multiplies the last ambientOcclusion() result into the caller's framebuffer (colour = colour x visibility;
  // its alpha untouched), over all of it. The framebuffer must have that result's size; kBoundFramebuffer: the one
  // bound now.
  void compositeAmbientOcclusion(const Framebuffer& target);
  // Any debug view of a frame whose G-buffer the caller gave ("ao", "ao-raw", "normals", "depth", "mask", ...)
  // into the caller's framebuffer of the G-buffer's size.
  void renderView(const std::string& view, const Camera& camera, const GBuffer& gbuffer, const Framebuffer& output);

  Stats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace obscura::api
