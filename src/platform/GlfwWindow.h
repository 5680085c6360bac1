#pragma once
// A desktop window with a real OpenGL ES 2.0 context (GLFW_OPENGL_ES_API), for obscura-view. The GLES 2 dispatch
// table is loaded from the window's context with glfwGetProcAddress, so the core runs exactly as on the web: no
// desktop-GL entry point is reachable. The back buffer is 4x multisampled with depth, like the web page's canvas.
#include <string>

#include "gl/GlCaps.h"

struct GLFWwindow;

namespace obscura {

class GlfwWindow {
 public:
  // Opens the window and makes its context current. Tries the platform's native context API first, then EGL.
  // Throws GlError with GLFW's reason if no OpenGL ES 2.0 context can be had.
  GlfwWindow(const std::string& title, int width, int height);
  ~GlfwWindow();
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  GLFWwindow* handle() const { return window_; }
  const gl::GlCaps& caps() const { return caps_; }
  // Resolves entry points of the current context (core and extensions), e.g. for GpuPassTimer.
  static void* procAddress(const char* name);

 private:
  GLFWwindow* window_ = nullptr;
  gl::GlCaps caps_;
};

}  // namespace obscura
