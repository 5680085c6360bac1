// The browser's "your own geometry" path (web/obscura.js: createAmbientOcclusion; docs/api.md): the public Renderer
// (include/obscura/obscura.h) on the page's own WebGL 1 context. The page creates the context on its canvas first
// (canvas.getContext('webgl')); the module asks the same canvas for one and is handed that very context, so the page
// and Obscura draw with one context, one set of bindings. No animation-frame loop and no scene of Obscura's: the page
// draws its meshes into the G-buffer framebuffer beginGBuffer binds, with the GLSL chunk gbufferGlsl(), then asks
// for the AO and composites it, on its own schedule.
#include <memory>
#include <string>

#include <emscripten/emscripten.h>
#include <emscripten/html5.h>

#include "gl/GlApi.h"
#include "obscura/obscura.h"

namespace {

using obscura::api::Renderer;

std::unique_ptr<Renderer> g_renderer;
EMSCRIPTEN_WEBGL_CONTEXT_HANDLE g_context = 0;
unsigned int g_ao = 0;  // the last AO texture
std::string g_geometryError, g_geometryText;

EM_JS(void, obscura_geometry_register_canvas, (), { specialHTMLTargets["!obscura-geometry"] = Module["canvas"]; });

template <typename Body>
int attempt(Body&& body) {
  try {
    g_geometryError.clear();
    body();
    return 1;
  } catch (const std::exception& e) {
    g_geometryError = e.what();
    return 0;
  }
}

const char* text(std::string value) {
  g_geometryText = std::move(value);
  return g_geometryText.c_str();
}

}  // namespace

extern "C" {

// Joins the canvas's WebGL 1 context (the page's, when it made one first) and builds the renderer on it.
EMSCRIPTEN_KEEPALIVE int obscura_geometry_create(int checkGlErrors) {
  return attempt([checkGlErrors] {
    obscura_geometry_register_canvas();
    EmscriptenWebGLContextAttributes attributes;
    emscripten_webgl_init_context_attributes(&attributes);
    attributes.majorVersion = 1;
    attributes.minorVersion = 0;
    attributes.antialias = EM_FALSE;
    attributes.enableExtensionsByDefault = EM_TRUE;
    g_context = emscripten_webgl_create_context("!obscura-geometry", &attributes);
    if (g_context <= 0) throw obscura::api::Error("this browser cannot create a WebGL 1 context on the canvas");
    emscripten_webgl_make_context_current(g_context);
    g_renderer = std::make_unique<Renderer>(Renderer::Options{nullptr, checkGlErrors != 0});
    g_renderer->clearScene();
  });
}

EMSCRIPTEN_KEEPALIVE const char* obscura_geometry_error() { return g_geometryError.c_str(); }
EMSCRIPTEN_KEEPALIVE const char* obscura_geometry_glsl() { return obscura::api::gbufferGlsl(); }
EMSCRIPTEN_KEEPALIVE const char* obscura_geometry_version() { return obscura::api::version(); }

EMSCRIPTEN_KEEPALIVE int obscura_geometry_set(const char* name, const char* value) {
  return attempt([&] { g_renderer->set(name, value); });
}

EMSCRIPTEN_KEEPALIVE const char* obscura_geometry_get(const char* name) {
  const char* out = nullptr;
  attempt([&] { out = text(g_renderer->get(name)); });
  return out;
}

// Binds the G-buffer framebuffer of width x height, cleared to the background, viewport set.
EMSCRIPTEN_KEEPALIVE int obscura_geometry_begin(int width, int height) {
  return attempt([&] { g_renderer->beginGBuffer(width, height); });
}

// The AO of the G-buffer drawn since obscura_geometry_begin, for the camera it was drawn with.
EMSCRIPTEN_KEEPALIVE int obscura_geometry_ambient_occlusion(float eyeX, float eyeY, float eyeZ, float targetX,
                                                            float targetY, float targetZ, float upX, float upY,
                                                            float upZ, float fovyDegrees, float near, float far) {
  return attempt([&] {
    obscura::api::Camera camera;
    const float eye[3] = {eyeX, eyeY, eyeZ}, target[3] = {targetX, targetY, targetZ}, up[3] = {upX, upY, upZ};
    for (int i = 0; i < 3; ++i) {
      camera.eye[i] = eye[i];
      camera.target[i] = target[i];
      camera.up[i] = up[i];
    }
    camera.fovyDegrees = fovyDegrees;
    camera.near = near;
    camera.far = far;
    g_ao = g_renderer->ambientOcclusion(camera);
  });
}

// Binds the last AO texture to TEXTURE_2D on the active unit, so the page reads it back as a WebGLTexture
// (gl.getParameter(gl.TEXTURE_BINDING_2D)): the page's WebGL objects and the module's numbered ones are two worlds.
EMSCRIPTEN_KEEPALIVE int obscura_geometry_bind_ao() {
  return attempt([] {
    if (g_ao == 0) throw obscura::api::Error("no AO yet (call ambientOcclusion first)");
    glBindTexture(GL_TEXTURE_2D, g_ao);
  });
}

// Multiplies the AO into the framebuffer the page has bound now (its own, or the canvas's).
EMSCRIPTEN_KEEPALIVE int obscura_geometry_composite(int width, int height) {
  return attempt([&] {
    g_renderer->compositeAmbientOcclusion({obscura::api::kBoundFramebuffer, width, height});
  });
}

EMSCRIPTEN_KEEPALIVE const char* obscura_geometry_stats() {
  const obscura::api::Stats s = g_renderer->stats();
  std::string passes;
  for (const std::string& pass : s.passesRun) passes += (passes.empty() ? "\"" : ",\"") + pass + "\"";
  return text("{\"width\":" + std::to_string(s.width) + ",\"height\":" + std::to_string(s.height) +
              ",\"frames\":" + std::to_string(s.frames) + ",\"cpuMs\":" + std::to_string(s.cpuMs) +
              ",\"passesRun\":[" + passes + "],\"pooledTargets\":" + std::to_string(s.pooledTargets) + "}");
}

}  // extern "C"
