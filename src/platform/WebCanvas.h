#pragma once
// The page's <canvas> as a WebGL 1 context (Emscripten only). The canvas is the one the JS API hands to the module
// as Module.canvas, addressed as the "!canvas" target, so a page may use any element (and several pages' worth of
// modules may coexist).
//
// WebGL 1 only (the build links with MIN/MAX_WEBGL_VERSION=1): the back buffer is requested with depth (the forward
// lighting may draw the scene into it), without multisampling, opaque and not preserved. Context loss is reported
// through callbacks: on loss the event is accepted (preventDefault) so the browser may restore the context; on
// restore the extensions are enabled again, since a restored context starts with none.
#include <functional>

#include <emscripten/html5_webgl.h>

namespace obscura {

class WebCanvas {
 public:
  // Creates the context and makes it current. Throws GlError if the browser offers no WebGL 1.
  WebCanvas(std::function<void()> onLost, std::function<void()> onRestored);
  ~WebCanvas();
  WebCanvas(const WebCanvas&) = delete;
  WebCanvas& operator=(const WebCanvas&) = delete;

  bool lost() const { return lost_; }
  // Sizes the drawing buffer to the canvas's CSS size times the pixel ratio, devicePixelRatio but at most
  // `maxPixelRatio` (resolution.max-pixel-ratio: a phone at DPR 3 then draws 2 x 2 device pixels per CSS pixel, 4
  // where 3 x 3 would be 9, and the browser scales the canvas up), each side at most `maxSize`, and returns that
  // size; true if it changed.
  bool fitToDisplay(int maxSize, double maxPixelRatio, int* width, int* height);
  // The pixel ratio of the last fit, and the device's.
  double pixelRatio() const { return pixelRatio_; }
  static double devicePixelRatio();

  // Resolves WebGL 1 and extension entry points (GpuPassTimer's loader).
  static void* procAddress(const char* name);

 private:
  static EM_BOOL contextLost(int eventType, const void* reserved, void* self);
  static EM_BOOL contextRestored(int eventType, const void* reserved, void* self);

  EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context_ = 0;
  std::function<void()> onLost_, onRestored_;
  bool lost_ = false;
  double pixelRatio_ = 1.0;
};

}  // namespace obscura
