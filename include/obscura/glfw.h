#pragma once
// A desktop window with an OpenGL ES 2.0 context (component Obscura::glfw; pkg-config obscura-glfw): GLFW with
// GLFW_OPENGL_ES_API, the platform's native context API first, then EGL. Without depth or multisampling: every pass of
// Obscura's frame draws into textures and its last one covers the window (FXAA antialiases). The caller keeps using
// GLFW directly through handle() (input callbacks, the loop).
#include <memory>
#include <string>

#include "obscura/obscura.h"

struct GLFWwindow;

namespace obscura::api {

class GlfwWindow {
 public:
  // Initialises GLFW, opens the window and makes its context current. Throws Error with GLFW's reason if no
  // OpenGL ES 2.0 window can be had (no display, no GLES driver).
  GlfwWindow(const std::string& title, int width, int height);
  ~GlfwWindow();  // closes the window and terminates GLFW
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  GLFWwindow* handle() const;
  // glfwGetProcAddress: pass it to Renderer::Options::getProcAddress.
  static void* getProcAddress(const char* name);
  // The window's own framebuffer (0) at its current size in pixels (which a high-DPI screen makes larger than the
  // window's size in screen coordinates).
  Framebuffer framebuffer() const;
  bool shouldClose() const;
  void swapBuffers();
  static void pollEvents();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace obscura::api
