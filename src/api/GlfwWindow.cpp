// obscura/glfw.h over platform/GlfwWindow.
#include "obscura/glfw.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "platform/GlfwWindow.h"

namespace obscura::api {

struct GlfwWindow::Impl {
  Impl(const std::string& title, int width, int height) : window(title, width, height) {}
  obscura::GlfwWindow window;
};

GlfwWindow::GlfwWindow(const std::string& title, int width, int height) {
  try {
    impl_ = std::make_unique<Impl>(title, width, height);
  } catch (const std::exception& e) {
    throw Error(e.what());
  }
}
GlfwWindow::~GlfwWindow() = default;

GLFWwindow* GlfwWindow::handle() const { return impl_->window.handle(); }
void* GlfwWindow::getProcAddress(const char* name) { return obscura::GlfwWindow::procAddress(name); }
Framebuffer GlfwWindow::framebuffer() const {
  Framebuffer output;
  glfwGetFramebufferSize(handle(), &output.width, &output.height);
  return output;
}
bool GlfwWindow::shouldClose() const { return glfwWindowShouldClose(handle()) != 0; }
void GlfwWindow::swapBuffers() { glfwSwapBuffers(handle()); }
void GlfwWindow::pollEvents() { glfwPollEvents(); }

}  // namespace obscura::api
