// Obscura in a GLFW window (OpenGL ES 2.0 context): the built-in scene, turning slowly; 'a' turns the AO on and off,
// Escape closes. --frames N closes after N frames (the test suite runs it under Xvfb that way).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <obscura/glfw.h>
#include <obscura/obscura.h>

int main(int argc, char** argv) {
  long frames = -1;
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--frames") == 0) frames = std::atol(argv[i + 1]);
  try {
    using namespace obscura::api;
    GlfwWindow window("Obscura: GLFW example", 800, 450);
    Renderer renderer({&GlfwWindow::getProcAddress, false});
    glfwSetKeyCallback(window.handle(), [](GLFWwindow* w, int key, int, int action, int) {
      if (action != GLFW_PRESS) return;
      if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, 1);
      auto* r = static_cast<Renderer*>(glfwGetWindowUserPointer(w));
      if (key == GLFW_KEY_A) r->set("ao", r->get("ao") == "on" ? "off" : "on");
    });
    glfwSetWindowUserPointer(window.handle(), &renderer);
    long drawn = 0;
    while (!window.shouldClose() && (frames < 0 || drawn < frames)) {
      const Framebuffer output = window.framebuffer();
      if (output.width > 0 && output.height > 0) {
        Camera camera = renderer.sceneCamera(output.width, output.height);
        // Orbit the eye around the target, a turn every 20 seconds.
        const double angle = glfwGetTime() * 2.0 * 3.14159265358979 / 20.0;
        const float dx = camera.eye[0] - camera.target[0], dz = camera.eye[2] - camera.target[2];
        camera.eye[0] = camera.target[0] + static_cast<float>(dx * std::cos(angle) - dz * std::sin(angle));
        camera.eye[2] = camera.target[2] + static_cast<float>(dx * std::sin(angle) + dz * std::cos(angle));
        renderer.render(camera, output);
        window.swapBuffers();
        ++drawn;
      }
      GlfwWindow::pollEvents();
    }
    const Stats stats = renderer.stats();
    std::printf("glfw_window: %ld frames at %dx%d, last %.1f ms (CPU), %zu passes\n", drawn, stats.width,
                stats.height, stats.cpuMs, stats.passesRun.size());
  } catch (const obscura::api::Error& e) {
    std::fprintf(stderr, "glfw_window: %s\n", e.what());
    return 1;
  }
  return 0;
}
