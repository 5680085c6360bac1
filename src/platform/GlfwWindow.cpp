#include "platform/GlfwWindow.h"

// GLFW must not include a desktop GL header: the GLES 2 declarations come from gl/GlApi.h.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "base/Error.h"
#include "gl/GlLoader.h"

namespace obscura {
namespace {

std::string lastGlfwError() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown GLFW error";
}

}  // namespace

GlfwWindow::GlfwWindow(const std::string& title, int width, int height) {
  if (!glfwInit()) throw GlError("GLFW: cannot initialise (" + lastGlfwError() + "); is a display available?");
  std::string reasons;
  for (int api : {GLFW_NATIVE_CONTEXT_API, GLFW_EGL_CONTEXT_API}) {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, api);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
    // Its depth lets the forward lighting draw straight into the window where nothing reads the lit image (`preset
    // low`: FrameContext::outputDepth); no multisampling (FXAA antialiases; effects/fxaa/FxaaEffect.h says why not
    // MSAA). Its stencil lets FXAA run its full shader on edge pixels only (FxaaEffect.h).
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    glfwWindowHint(GLFW_STENCIL_BITS, 8);
    glfwWindowHint(GLFW_SAMPLES, 0);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (window_) break;
    reasons += (reasons.empty() ? "" : "; ") + lastGlfwError();
  }
  if (!window_) {
    glfwTerminate();
    throw GlError("GLFW: no OpenGL ES 2.0 window (" + reasons + ")");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(1);
  std::string missing;
  if (!gl::loadGles2(&GlfwWindow::procAddress, &missing)) {
    glfwDestroyWindow(window_);
    glfwTerminate();
    throw GlError("GLFW: the OpenGL ES context lacks " + missing);
  }
  caps_ = gl::GlCaps::query();
}

GlfwWindow::~GlfwWindow() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void* GlfwWindow::procAddress(const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }

}  // namespace obscura
