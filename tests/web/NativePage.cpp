// Definitions of the native stand-ins for Emscripten (tests/web/emscripten/emscripten.h) and the test's side of the
// browser (NativePage.h).
#include "NativePage.h"

#include <chrono>
#include <cstdarg>
#include <cstdio>

#include <emscripten/emscripten.h>

#include "TestSupport.h"

namespace {

EM_BOOL (*g_frameCallback)(double, void*) = nullptr;
void* g_frameUser = nullptr;
em_webgl_context_callback g_lost = nullptr, g_restored = nullptr;
void* g_lostUser = nullptr;
void* g_restoredUser = nullptr;
int g_displayWidth = 160, g_displayHeight = 90;
int g_canvasWidth = 300, g_canvasHeight = 150;  // a canvas element's default size
int g_logged = 0;
int g_nextContext = 1;

}  // namespace

namespace obscura::test::page {

bool animationFrame(double milliseconds) {
  if (!g_frameCallback) return false;
  if (!g_frameCallback(milliseconds, g_frameUser)) g_frameCallback = nullptr;
  return true;
}

void setDisplaySize(int width, int height) {
  g_displayWidth = width;
  g_displayHeight = height;
}

void loseContext() {
  if (g_lost) g_lost(0, nullptr, g_lostUser);
}

void restoreContext() {
  if (g_restored) g_restored(0, nullptr, g_restoredUser);
}

int loggedErrors() {
  const int logged = g_logged;
  g_logged = 0;
  return logged;
}

}  // namespace obscura::test::page

extern "C" {

void emscripten_log(int, const char* format, ...) {
  va_list arguments;
  va_start(arguments, format);
  std::vfprintf(stderr, format, arguments);
  va_end(arguments);
  std::fputc('\n', stderr);
  ++g_logged;
}

double emscripten_get_now(void) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void emscripten_request_animation_frame_loop(EM_BOOL (*callback)(double, void*), void* userData) {
  g_frameCallback = callback;
  g_frameUser = userData;
}

EMSCRIPTEN_RESULT emscripten_get_element_css_size(const char*, double* width, double* height) {
  *width = g_displayWidth;
  *height = g_displayHeight;
  return EMSCRIPTEN_RESULT_SUCCESS;
}

double emscripten_get_device_pixel_ratio(void) { return 1.0; }

EMSCRIPTEN_RESULT emscripten_get_canvas_element_size(const char*, int* width, int* height) {
  *width = g_canvasWidth;
  *height = g_canvasHeight;
  return EMSCRIPTEN_RESULT_SUCCESS;
}

EMSCRIPTEN_RESULT emscripten_set_canvas_element_size(const char*, int width, int height) {
  g_canvasWidth = width;
  g_canvasHeight = height;
  return EMSCRIPTEN_RESULT_SUCCESS;
}

void emscripten_webgl_init_context_attributes(EmscriptenWebGLContextAttributes* attributes) {
  *attributes = EmscriptenWebGLContextAttributes{};
  attributes->alpha = attributes->depth = attributes->antialias = attributes->premultipliedAlpha = EM_TRUE;
  attributes->majorVersion = 1;
}

// Every canvas's context is the test's headless one (made current on first use).
EMSCRIPTEN_WEBGL_CONTEXT_HANDLE emscripten_webgl_create_context(const char*, const EmscriptenWebGLContextAttributes*) {
  obscura::test::context();
  return g_nextContext++;
}

int emscripten_webgl_make_context_current(EMSCRIPTEN_WEBGL_CONTEXT_HANDLE) { return EMSCRIPTEN_RESULT_SUCCESS; }
int emscripten_webgl_destroy_context(EMSCRIPTEN_WEBGL_CONTEXT_HANDLE) { return EMSCRIPTEN_RESULT_SUCCESS; }

// No extension entry points natively: the caps the module reads say which extensions there are, and the headless
// contexts offer no timer queries, so GpuPassTimer never asks.
void* emscripten_webgl1_get_proc_address(const char*) { return nullptr; }

int emscripten_set_webglcontextlost_callback(const char*, void* userData, EM_BOOL, em_webgl_context_callback callback) {
  g_lost = callback;
  g_lostUser = userData;
  return EMSCRIPTEN_RESULT_SUCCESS;
}

int emscripten_set_webglcontextrestored_callback(const char*, void* userData, EM_BOOL,
                                                 em_webgl_context_callback callback) {
  g_restored = callback;
  g_restoredUser = userData;
  return EMSCRIPTEN_RESULT_SUCCESS;
}

}  // extern "C"
