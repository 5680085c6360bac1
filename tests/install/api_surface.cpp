// Obscura's public API surface (CHANGELOG.md), compiled against the installed headers only and linked with the flags
// pkg-config gives. Every public declaration is named here with its exact signature, so a change to one breaks this
// build until the CHANGELOG and this list say so; then it runs a few calls through a headless EGL context
// (OBSCURA_TEST_BACKEND=osmesa: OSMesa). tests/CMakeLists.txt also builds it in the tree (api.surface).
//   api_surface PREFIX
#include <obscura/glfw.h>
#include <obscura/headless.h>
#include <obscura/obscura.h>
#include <obscura/offscreen.h>
#include <obscura/version.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <type_traits>

using namespace obscura::api;

// --- The surface, by signature. ----------------------------------------------------------------------------------
static_assert(OBSCURA_VERSION == OBSCURA_VERSION_MAJOR * 10000 + OBSCURA_VERSION_MINOR * 100 + OBSCURA_VERSION_PATCH);
static_assert(std::is_base_of_v<std::runtime_error, Error>);
static_assert(std::is_same_v<ProcAddressLoader, void* (*)(const char*)>);
static_assert(kBoundFramebuffer == 0xFFFFFFFFu);
[[maybe_unused]] const char* (*const kVersion)() = &version;
[[maybe_unused]] const char* (*const kGBufferGlsl)() = &gbufferGlsl;
[[maybe_unused]] void (*const kWritePng)(const std::string&, int, int, const std::vector<std::uint8_t>&) = &writePng;

static_assert(!std::is_copy_constructible_v<Renderer> && std::is_nothrow_move_constructible_v<Renderer>);
static_assert(std::is_constructible_v<Renderer, const Renderer::Options&>);
[[maybe_unused]] void (Renderer::*const kSetBuiltinScene)() = &Renderer::setBuiltinScene;
[[maybe_unused]] void (Renderer::*const kSetSceneFile)(const std::string&) = &Renderer::setSceneFile;
[[maybe_unused]] void (Renderer::*const kSetSceneMemory)(const void*, std::size_t, const std::string&,
                                                         const std::map<std::string, std::vector<std::uint8_t>>&) =
    &Renderer::setSceneMemory;
[[maybe_unused]] void (Renderer::*const kClearScene)() = &Renderer::clearScene;
[[maybe_unused]] SceneInfo (Renderer::*const kScene)() const = &Renderer::scene;
[[maybe_unused]] Camera (Renderer::*const kSceneCamera)(int, int) const = &Renderer::sceneCamera;
[[maybe_unused]] bool Camera::*const kCameraOrthographic = &Camera::orthographic;
[[maybe_unused]] float Camera::*const kCameraYmag = &Camera::ymag;
[[maybe_unused]] void (Renderer::*const kSetText)(const std::string&, const std::string&) = &Renderer::set;
[[maybe_unused]] void (Renderer::*const kSetNumber)(const std::string&, double) = &Renderer::set;
[[maybe_unused]] std::string (Renderer::*const kGet)(const std::string&) const = &Renderer::get;
[[maybe_unused]] std::vector<ParameterInfo> (*const kParameters)() = &Renderer::parameters;
[[maybe_unused]] void (Renderer::*const kSetView)(const std::string&) = &Renderer::setView;
[[maybe_unused]] std::string (Renderer::*const kView)() const = &Renderer::view;
[[maybe_unused]] std::vector<std::string> (*const kViews)() = &Renderer::views;
[[maybe_unused]] void (Renderer::*const kSetCompare)(const std::string&) = &Renderer::setCompare;
[[maybe_unused]] std::string (Renderer::*const kCompare)() const = &Renderer::compare;
[[maybe_unused]] void (Renderer::*const kSetTime)(double) = &Renderer::setTime;
[[maybe_unused]] double (Renderer::*const kTime)() const = &Renderer::time;
[[maybe_unused]] void (Renderer::*const kRender)(const Camera&, const Framebuffer&) = &Renderer::render;
[[maybe_unused]] void (Renderer::*const kBeginGBuffer)(int, int) = &Renderer::beginGBuffer;
[[maybe_unused]] GBuffer (Renderer::*const kGBuffer)() const = &Renderer::gbuffer;
[[maybe_unused]] unsigned int (Renderer::*const kAo)(const Camera&) = &Renderer::ambientOcclusion;
[[maybe_unused]] unsigned int (Renderer::*const kAoOf)(const Camera&, const GBuffer&) = &Renderer::ambientOcclusion;
[[maybe_unused]] void (Renderer::*const kComposite)(const Framebuffer&) = &Renderer::compositeAmbientOcclusion;
[[maybe_unused]] void (Renderer::*const kRenderView)(const std::string&, const Camera&, const GBuffer&,
                                                     const Framebuffer&) = &Renderer::renderView;
[[maybe_unused]] Stats (Renderer::*const kStats)() const = &Renderer::stats;

static_assert(std::is_constructible_v<OffscreenFramebuffer, int, int>);
[[maybe_unused]] Framebuffer (OffscreenFramebuffer::*const kOffscreenFramebuffer)() const =
    &OffscreenFramebuffer::framebuffer;
[[maybe_unused]] unsigned int (OffscreenFramebuffer::*const kOffscreenTexture)() const = &OffscreenFramebuffer::texture;
[[maybe_unused]] std::vector<std::uint8_t> (OffscreenFramebuffer::*const kReadRgba)() const =
    &OffscreenFramebuffer::readRgba;

static_assert(std::is_constructible_v<HeadlessContext, HeadlessContext::Backend>);
[[maybe_unused]] ProcAddressLoader (HeadlessContext::*const kHeadlessLoader)() const = &HeadlessContext::getProcAddress;
[[maybe_unused]] HeadlessContext::Backend (*const kParseBackend)(const std::string&) = &HeadlessContext::parseBackend;
[[maybe_unused]] const char* (*const kBackendName)(HeadlessContext::Backend) = &HeadlessContext::backendName;

static_assert(std::is_constructible_v<GlfwWindow, const std::string&, int, int>);
[[maybe_unused]] GLFWwindow* (GlfwWindow::*const kHandle)() const = &GlfwWindow::handle;
[[maybe_unused]] void* (*const kGlfwLoader)(const char*) = &GlfwWindow::getProcAddress;
[[maybe_unused]] Framebuffer (GlfwWindow::*const kWindowFramebuffer)() const = &GlfwWindow::framebuffer;
[[maybe_unused]] bool (GlfwWindow::*const kShouldClose)() const = &GlfwWindow::shouldClose;
[[maybe_unused]] void (GlfwWindow::*const kSwapBuffers)() = &GlfwWindow::swapBuffers;
[[maybe_unused]] void (*const kPollEvents)() = &GlfwWindow::pollEvents;

// --- A few calls. ------------------------------------------------------------------------------------------------
static int failures = 0;
static void check(bool ok, const std::string& what) {
  if (!ok) {
    std::fprintf(stderr, "FAILED: %s\n", what.c_str());
    ++failures;
  }
}
template <typename F>
static std::string errorOf(F&& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const std::string prefix = argv[1];
  check(std::string(version()) == OBSCURA_VERSION_STRING, "the library's version is the headers'");
  std::ifstream glsl(prefix + "/share/obscura/glsl/obscura_gbuffer.glsl");
  std::stringstream text;
  text << glsl.rdbuf();
  check(text.str() == gbufferGlsl() && text.str().find("vec4 obscuraGBuffer(") != std::string::npos,
        "gbufferGlsl() is the installed chunk");

  const std::vector<ParameterInfo> parameters = Renderer::parameters();
  auto find = [&](const std::string& name) {
    return std::find_if(parameters.begin(), parameters.end(), [&](const ParameterInfo& p) { return p.name == name; });
  };
  check(find("preset") != parameters.end(), "preset is a parameter");
  check(find("ao.radius") != parameters.end() && find("ao.radius")->alias == "radius" &&
            find("ao.radius")->kind == "number",
        "ao.radius is a number with the alias radius");
  check(find("tonemap.operator") != parameters.end() && find("tonemap.operator")->kind == "choice",
        "tonemap.operator is a choice");
  const std::vector<std::string> views = Renderer::views();
  for (const char* view : {"final", "split", "ao", "ao-raw", "normals", "depth", "mask"})
    check(std::count(views.begin(), views.end(), view) == 1, std::string("view ") + view);

  // EGL, as a consumer would; the in-tree build of this file (api.surface) runs on OSMesa in the sanitized tree.
  const char* backend = std::getenv("OBSCURA_TEST_BACKEND");
  HeadlessContext context(HeadlessContext::parseBackend(backend ? backend : "egl"));
  Renderer renderer({context.getProcAddress(), true});
  check(renderer.scene().triangles > 1000 && renderer.scene().defaultRadius == 1.0f, "the built-in scene at start");
  renderer.set("radius", "0.75");
  check(renderer.get("ao.radius") == "0.75", "an alias sets the parameter");
  check(errorOf([&] { renderer.set("ao.radius", "0"); }).find("ao.radius") != std::string::npos &&
            renderer.get("ao.radius") == "0.75",
        "a value out of range throws Error naming the parameter and changes nothing");
  check(!errorOf([&] { renderer.set("no.such", "1"); }).empty(), "an unknown parameter throws Error");
  check(!errorOf([&] { renderer.setView("nope"); }).empty() && renderer.view() == "final", "an unknown view throws");
  check(!errorOf([&] { renderer.setSceneFile(prefix + "/no-such.glb"); }).empty(), "a missing file throws");
  const char garbage[] = "not a glTF file";
  check(!errorOf([&] { renderer.setSceneMemory(garbage, sizeof garbage, "garbage.glb"); }).empty() &&
            renderer.scene().triangles > 1000,
        "a bad file throws and the scene stays");

  OffscreenFramebuffer target(160, 90);
  renderer.render(renderer.sceneCamera(160, 90), target.framebuffer());
  const std::vector<std::uint8_t> pixels = target.readRgba();
  check(pixels.size() == 160u * 90u * 4u && std::count(pixels.begin(), pixels.end(), pixels[0]) < 160 * 90 * 2,
        "render() draws an image");
  const Stats stats = renderer.stats();
  check(stats.frames == 1 && stats.width == 160 && stats.height == 90 && !stats.passesRun.empty() &&
            stats.passesRun.front() == "gbuffer",
        "stats() describes the frame");
  renderer.setView("split");
  renderer.setCompare("fxaa");
  renderer.render(renderer.sceneCamera(160, 90), target.framebuffer());
  check(renderer.compare() == "fxaa" && renderer.stats().frames == 2, "the split view renders");
  std::printf("api_surface: obscura %s, %zu parameters, %zu views, %s\n", version(), parameters.size(), views.size(),
              failures ? "FAILED" : "ok");
  return failures ? 1 : 0;
}
