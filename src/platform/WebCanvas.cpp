#include "platform/WebCanvas.h"

#include <algorithm>
#include <cmath>

#include <emscripten/emscripten.h>
#include <emscripten/html5.h>

#include "base/Error.h"
#include "base/TimeSpent.h"
#include "gl/GlApi.h"

namespace obscura {
namespace {

constexpr const char* kCanvas = "!canvas";

// Emscripten looks DOM targets up by CSS selector, or in specialHTMLTargets: register the canvas the JS API gave
// the module so no id or selector is imposed on the embedding page.
EM_JS(void, obscura_register_canvas, (), { specialHTMLTargets["!canvas"] = Module["canvas"]; });

// A restored context has no extension enabled. Emscripten enables them (and keeps its own handles to the ones it
// drives, such as the timer-query object) once per context in GL.initExtensions; run that again.
EM_JS(void, obscura_enable_extensions_again, (int handle), {
  var context = GL.getContext(handle);
  context.initExtensionsDone = false;
  GL.initExtensions(context);
});

}  // namespace

WebCanvas::WebCanvas(std::function<void()> onLost, std::function<void()> onRestored)
    : onLost_(std::move(onLost)), onRestored_(std::move(onRestored)) {
  const TimedScope timed("context");
  obscura_register_canvas();
  EmscriptenWebGLContextAttributes attributes;
  emscripten_webgl_init_context_attributes(&attributes);
  attributes.majorVersion = 1;
  attributes.minorVersion = 0;
  attributes.alpha = EM_FALSE;
  // A depth buffer: where nothing reads the lit image (`preset low`: no FXAA), the forward lighting draws the scene
  // straight into the canvas, depth-tested there, and the frame saves a full-screen pass (FrameContext::outputDepth;
  // docs/benchmarks.md). No multisampling (FXAA antialiases: effects/fxaa/FxaaEffect.h says why not MSAA): measured
  // on SwiftShader, the multisampled back buffer alone cost a fifth of the old frame (docs/benchmarks.md). No stencil:
  // FXAA masked by a stencil (FxaaEffect.h), which more than halves its pass on llvmpipe, made the page's frame no
  // faster on SwiftShader (AO off, 1280x720: 236 against 219 ms, medians of 24 frames, within the noise).
  attributes.depth = EM_TRUE;
  attributes.stencil = EM_FALSE;
  attributes.antialias = EM_FALSE;
  attributes.premultipliedAlpha = EM_TRUE;
  attributes.preserveDrawingBuffer = EM_FALSE;
  attributes.powerPreference = EM_WEBGL_POWER_PREFERENCE_HIGH_PERFORMANCE;
  attributes.enableExtensionsByDefault = EM_TRUE;
  context_ = emscripten_webgl_create_context(kCanvas, &attributes);
  if (context_ <= 0) throw GlError("this browser cannot create a WebGL 1 context on the canvas");
  emscripten_webgl_make_context_current(context_);
  emscripten_set_webglcontextlost_callback(kCanvas, this, EM_FALSE, &WebCanvas::contextLost);
  emscripten_set_webglcontextrestored_callback(kCanvas, this, EM_FALSE, &WebCanvas::contextRestored);
}

WebCanvas::~WebCanvas() {
  emscripten_set_webglcontextlost_callback(kCanvas, nullptr, EM_FALSE, nullptr);
  emscripten_set_webglcontextrestored_callback(kCanvas, nullptr, EM_FALSE, nullptr);
  emscripten_webgl_destroy_context(context_);
}

EM_BOOL WebCanvas::contextLost(int, const void*, void* self) {
  auto* canvas = static_cast<WebCanvas*>(self);
  canvas->lost_ = true;
  canvas->onLost_();
  return EM_TRUE;  // preventDefault: we can restore
}

EM_BOOL WebCanvas::contextRestored(int, const void*, void* self) {
  auto* canvas = static_cast<WebCanvas*>(self);
  emscripten_webgl_make_context_current(canvas->context_);
  obscura_enable_extensions_again(canvas->context_);
  // Errors recorded before the restore belong to the lost context. The browser resets its own flags, but Emscripten
  // keeps one of its own (a glGet* that the lost context answered with null is recorded as GL_INVALID_ENUM) and
  // would report it on the new context's first glGetError. Found by the browser tests' GL error checks.
  for (int i = 0; i < 8 && glGetError() != GL_NO_ERROR; ++i) {
  }
  canvas->lost_ = false;
  canvas->onRestored_();
  return EM_TRUE;
}

double WebCanvas::devicePixelRatio() { return emscripten_get_device_pixel_ratio(); }

bool WebCanvas::fitToDisplay(int maxSize, double maxPixelRatio, int* width, int* height) {
  double cssWidth = 0.0, cssHeight = 0.0;
  emscripten_get_element_css_size(kCanvas, &cssWidth, &cssHeight);
  const double ratio = std::min(emscripten_get_device_pixel_ratio(), maxPixelRatio);
  pixelRatio_ = ratio;
  const int w = std::clamp(static_cast<int>(std::lround(cssWidth * ratio)), 1, std::max(maxSize, 1));
  const int h = std::clamp(static_cast<int>(std::lround(cssHeight * ratio)), 1, std::max(maxSize, 1));
  int current[2] = {0, 0};
  emscripten_get_canvas_element_size(kCanvas, &current[0], &current[1]);
  *width = w;
  *height = h;
  if (current[0] == w && current[1] == h) return false;
  emscripten_set_canvas_element_size(kCanvas, w, h);
  return true;
}

void* WebCanvas::procAddress(const char* name) { return emscripten_webgl1_get_proc_address(name); }

}  // namespace obscura
