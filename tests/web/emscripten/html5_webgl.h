#pragma once
// Native stand-ins (tests/web/emscripten/emscripten.h says why).
#include "gl/GlApi.h"

// In the browser build the GL entry points are global prototypes; natively they are gl/GlApi.h's dispatch table, in
// namespace obscura::gles: code outside namespace obscura (obscura_web_geometry.cpp's exports) calls them unqualified.
using namespace obscura::gles;  // NOLINT
typedef int EM_BOOL;
#define EM_TRUE 1
#define EM_FALSE 0
#define EM_WEBGL_POWER_PREFERENCE_DEFAULT 0
#define EM_WEBGL_POWER_PREFERENCE_LOW_POWER 1
#define EM_WEBGL_POWER_PREFERENCE_HIGH_PERFORMANCE 2

typedef int EMSCRIPTEN_WEBGL_CONTEXT_HANDLE;
typedef EM_BOOL (*em_webgl_context_callback)(int eventType, const void* reserved, void* userData);

struct EmscriptenWebGLContextAttributes {
  EM_BOOL alpha, depth, stencil, antialias, premultipliedAlpha, preserveDrawingBuffer;
  int powerPreference;
  EM_BOOL failIfMajorPerformanceCaveat;
  int majorVersion, minorVersion;
  EM_BOOL enableExtensionsByDefault, explicitSwapControl;
  int proxyContextToMainThread;
  EM_BOOL renderViaOffscreenBackBuffer;
};

extern "C" {
void emscripten_webgl_init_context_attributes(EmscriptenWebGLContextAttributes* attributes);
EMSCRIPTEN_WEBGL_CONTEXT_HANDLE emscripten_webgl_create_context(const char* target,
                                                                const EmscriptenWebGLContextAttributes* attributes);
int emscripten_webgl_make_context_current(EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context);
int emscripten_webgl_destroy_context(EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context);
void* emscripten_webgl1_get_proc_address(const char* name);
int emscripten_set_webglcontextlost_callback(const char* target, void* userData, EM_BOOL useCapture,
                                             em_webgl_context_callback callback);
int emscripten_set_webglcontextrestored_callback(const char* target, void* userData, EM_BOOL useCapture,
                                                 em_webgl_context_callback callback);
}
