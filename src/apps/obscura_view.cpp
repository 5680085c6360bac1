// obscura-view: the desktop viewer. A GLFW window with an OpenGL ES 2.0 context running the same Viewer session as
// the web page: same defaults, same keys, same camera gestures; a glTF file dropped on the window is loaded (a bad
// one leaves the current scene and says why in the title bar and on stderr). Timings are shown in the title bar.
//
// usage: obscura-view [FILE.glb|FILE.gltf] [--size WxH] [--state QUERY] [--screenshot OUT.png [--frames N]]
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "base/Error.h"
#include "frame/Resolution.h"
#include "gl/RenderTarget.h"
#include "platform/GlfwWindow.h"
#include "platform/GpuPassTimer.h"
#include "platform/Viewer.h"
#include "scene/ImageIo.h"

using namespace obscura;

namespace {

constexpr double kTitleInterval = 0.25;  // seconds between title-bar updates
constexpr double kSmoothing = 0.1;       // weight of the newest frame in the displayed frame time
constexpr float kZoomPerWheelStep = 0.15f;  // exp(0.15) per step, as the web page's 100-pixel wheel step

struct Options {
  std::string scene;
  int width = 1280, height = 720;
  std::string state;
  std::string screenshot;
  int frames = 3;
};

const char* kUsage =
    "usage: obscura-view [FILE.glb|FILE.gltf] [--size WxH] [--state QUERY] [--screenshot OUT.png [--frames N]]\n"
    "\n"
    "Shows a glTF 2.0 scene (default: the built-in scene) with Scalable Ambient Obscurance in an OpenGL ES 2.0\n"
    "window. Drop a .glb or .gltf on the window to load it, a .cube to grade with it (grading.lut).\n"
    "Each scene loaded gets its default AO radius, 5 % of its bounding-sphere diameter to two significant figures\n"
    "(the built-in scene: 1 m), unless --state gives one, which is then kept for every scene.\n"
    "  --size WxH         window size (default 1280x720)\n"
    "  --state QUERY      view, parameters, timeline and camera as the web page's URL query, e.g. 'view=ao&radius=2'\n"
    "  --screenshot FILE  draw --frames frames (default 3), write the last one as PNG and exit\n"
    "\n"
    "The animation (if the scene has any) starts paused at 0 s: space plays it; --state chooses it, e.g.\n"
    "'animation=Walk&time=1.5&play=on'.\n"
    "Mouse: left drag orbits, right/middle or shift + left drag pans, the wheel zooms. Esc quits.\n"
    "Keys:\n";

Options parseOptions(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw InputError(arg + ": missing value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      for (const Viewer::KeyBinding& k : Viewer::keyBindings())
        std::cout << "  " << k.label << "  " << k.description << "\n";
      std::exit(0);
    } else if (arg == "--size") {
      const std::string text = value();
      char x = 0, extra = 0;
      if (std::sscanf(text.c_str(), "%d%c%d%c", &options.width, &x, &options.height, &extra) != 3 || x != 'x' ||
          options.width < 1 || options.height < 1 || options.width > Camera::kMaxSize ||
          options.height > Camera::kMaxSize)
        throw InputError("--size: expected WxH within 1 .. " + std::to_string(Camera::kMaxSize) + ", got '" + text +
                         "'");
    } else if (arg == "--state") {
      options.state = value();
    } else if (arg == "--screenshot") {
      options.screenshot = value();
    } else if (arg == "--frames") {
      const std::string text = value();
      options.frames = std::atoi(text.c_str());
      if (options.frames < 1) throw InputError("--frames: expected a count of at least 1, got '" + text + "'");
    } else if (!arg.empty() && arg[0] != '-' && options.scene.empty()) {
      options.scene = arg;
    } else {
      throw InputError("unknown option '" + arg + "' (see --help)");
    }
  }
  return options;
}

// Mouse and keyboard for one window, forwarded to the Viewer.
class Input {
 public:
  Input(GLFWwindow* window, Viewer& viewer) : viewer_(viewer) {
    glfwSetWindowUserPointer(window, this);
    glfwSetCharCallback(window, [](GLFWwindow* w, unsigned int codepoint) { self(w).character(codepoint); });
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
      if (key == GLFW_KEY_ESCAPE && action == GLFW_PRESS) glfwSetWindowShouldClose(w, GLFW_TRUE);
      // Keys that type no character reach the Viewer under their KeyboardEvent.key names, as on the page; held
      // down, they repeat (frame steps).
      if (action == GLFW_RELEASE) return;
      if (key == GLFW_KEY_LEFT) self(w).namedKey("ArrowLeft");
      else if (key == GLFW_KEY_RIGHT) self(w).namedKey("ArrowRight");
      else if (key == GLFW_KEY_HOME && action == GLFW_PRESS) self(w).namedKey("Home");
    });
    glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int mods) {
      self(w).button(w, button, action, mods);
    });
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) { self(w).move(w, x, y); });
    glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
      self(w).viewer_.zoom(std::exp(-kZoomPerWheelStep * static_cast<float>(dy)));
    });
    glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
      self(w).loadDropped(std::vector<std::string>(paths, paths + count));
    });
  }

  // A drop may hold a .gltf with its .bin and images, in any order: the scene file is the one to load (its side
  // files are found next to it). A .cube dropped alone is the colour grade's LUT (grading.lut, grading on; a
  // malformed one is refused with its line and the grade stays).
  void loadDropped(const std::vector<std::string>& paths) {
    for (const std::string& path : paths) {
      std::string extension = std::filesystem::path(path).extension().string();
      for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (extension == ".gltf" || extension == ".glb") {
        load(path);
        return;
      }
      if (extension == ".cube" && paths.size() == 1) {
        try {
          viewer_.state().settings.set("grading.lut", path);
          viewer_.state().settings.set("grading", "on");
          message_.clear();
        } catch (const std::exception& e) {
          std::cerr << "obscura-view: " << e.what() << "\n";
          message_ = e.what();
        }
        return;
      }
    }
    message_ = "none of the dropped files is a .gltf or .glb scene (or a .cube LUT)";
    std::fprintf(stderr, "obscura-view: %s\n", message_.c_str());
  }

  void load(const std::string& path) {
    try {
      const GltfLoadReport report = viewer_.loadGltfFile(path);
      for (const std::string& warning : report.warnings)
        std::cerr << "obscura-view: warning: " << path << ": " << warning << "\n";
      message_.clear();
    } catch (const std::exception& e) {
      // The previous scene stays on screen.
      std::cerr << "obscura-view: " << e.what() << "\n";
      message_ = e.what();
    }
  }

  const std::string& message() const { return message_; }

 private:
  enum class Drag { None, Orbit, Pan };

  static Input& self(GLFWwindow* window) { return *static_cast<Input*>(glfwGetWindowUserPointer(window)); }

  void character(unsigned int codepoint) {
    if (codepoint >= 128) return;  // every binding is ASCII
    namedKey(std::string(1, static_cast<char>(codepoint)));
  }

  void namedKey(const std::string& key) {
    try {
      viewer_.handleKey(key);
      message_.clear();
    } catch (const std::exception& e) {
      message_ = e.what();
    }
  }

  void button(GLFWwindow* window, int button, int action, int mods) {
    if (action == GLFW_RELEASE) {
      drag_ = Drag::None;
      return;
    }
    const bool pan = button == GLFW_MOUSE_BUTTON_RIGHT || button == GLFW_MOUSE_BUTTON_MIDDLE || (mods & GLFW_MOD_SHIFT);
    drag_ = pan ? Drag::Pan : Drag::Orbit;
    glfwGetCursorPos(window, &x_, &y_);
  }

  void move(GLFWwindow* window, double x, double y) {
    if (drag_ != Drag::None) {
      int width = 0, height = 0;
      glfwGetWindowSize(window, &width, &height);
      const float dx = static_cast<float>(x - x_), dy = static_cast<float>(y - y_);
      if (drag_ == Drag::Orbit) viewer_.orbit(dx, dy, height);
      else viewer_.pan(dx, dy, height);
    }
    x_ = x;
    y_ = y;
  }

  Viewer& viewer_;
  Drag drag_ = Drag::None;
  double x_ = 0.0, y_ = 0.0;
  std::string message_;
};

std::string title(const Viewer& viewer, double frameMs, const GpuPassTimer& timer, const std::string& message) {
  char text[512];
  const View& view = viewer.state().view;
  const std::string shown = view == View::Split ? "split: " + view.compare + " off | on" : view.name;
  std::snprintf(text, sizeof text, "Obscura - %s - %s - %.1f ms (%.0f fps) - scale %.2f%s", viewer.sceneName().c_str(),
                shown.c_str(), frameMs, frameMs > 0.0 ? 1000.0 / frameMs : 0.0, viewer.renderScale(),
                viewer.state().settings.get("resolution.dynamic") == "on" ? " (dynamic)" : "");
  std::string out = text;
  // What the keys change, as in use (bias, intensity and contrast on "auto" show their fitted values). The radius is
  // in the scene's units (metres only for the built-in scene), so it goes without a unit.
  const RenderSettings& s = viewer.state().settings;
  const std::string preset = s.get("ao.preset");
  const std::string presetShown = preset.empty() ? std::string(presetName(s.ao().preset)) + " (changed)" : preset;
  out += " - AO " + s.get("ao") + ", " + presetShown + ", r " + s.get("ao.radius") + ", " + s.get("ao.samples") +
         " samples, intensity " + s.effective("ao.intensity") + ", bias " + s.effective("ao.bias") + ", contrast " +
         s.effective("ao.contrast") + ", blur " + (s.ao().blur ? s.get("ao.blur-radius") : std::string("off")) +
         " - tone mapping " + (s.get("tonemap") == "on" ? s.get("tonemap.operator") + " " +
                                                             s.get("tonemap.exposure") + " EV"
                                                       : std::string("off")) +
         " - FXAA " + s.get("fxaa");
  // The timeline, where the scene has something to play.
  const Timeline& timeline = viewer.state().timeline;
  if (timeline.duration() > 0.0) {
    std::snprintf(text, sizeof text, " - %s %.2f / %.2f s, %s%s, x%g", timeline.playing() ? "playing" : "paused",
                  timeline.time(), timeline.duration(), timeline.animationName().c_str(),
                  timeline.loop() ? ", loop" : "", timeline.speed());
    out += text;
  }
  if (timer.hasResult()) {
    out += " - GPU";
    const std::vector<std::string>& passes = framePassNames();
    for (size_t p = 0; p < passes.size(); ++p) {
      const double ms = timer.lastResult()[p];
      if (ms < 0.0) continue;
      std::snprintf(text, sizeof text, " %s %.2f", passes[p].c_str(), ms);
      out += text;
    }
    out += " ms";
    if (const Renderer* renderer = viewer.renderer())
      for (const PlannedPass& pass : renderer->lastPlan().passes())
        for (const std::string& absorbed : pass.absorbed) out += " (" + absorbed + " done by " + pass.decl.name + ")";
  }
  if (!message.empty()) out += " - error: " + message;
  return out;
}

int run(const Options& options) {
  GlfwWindow window("Obscura", options.width, options.height);
  std::cout << "obscura-view: " << window.caps().version << " on " << window.caps().renderer << std::endl;
  RendererOptions rendererOptions;
  rendererOptions.checkGlErrors = !options.screenshot.empty();  // a screenshot run doubles as a check
  Viewer viewer(window.caps(), rendererOptions);
  Input input(window.handle(), viewer);
  if (!options.scene.empty()) {
    input.load(options.scene);
    if (!input.message().empty()) return 2;
  }
  if (!options.state.empty()) viewer.state().applyQuery(options.state);
  GpuPassTimer timer(window.caps(), &GlfwWindow::procAddress);

  double last = glfwGetTime(), lastTitle = 0.0, frameMs = 0.0;
  float lastScale = 1.0f;              // the render scale of the last frame drawn
  std::uint64_t timerResults = 0;      // the GPU timer's results given to dynamic resolution
  for (int frame = 1; !glfwWindowShouldClose(window.handle()); ++frame) {
    glfwPollEvents();
    int width = 0, height = 0;
    glfwGetFramebufferSize(window.handle(), &width, &height);
    if (width > 0 && height > 0) {  // 0 x 0 while minimised
      timer.beginFrame(viewer.dynamicResolution().scale(),
                       viewer.state().settings.of<ResolutionSettings>().dynamic);
      viewer.render(0, width, height, timer.available() ? &timer : nullptr, glfwGetTime());
      timer.endFrame();
      lastScale = viewer.renderScale();
    }
    // Dynamic resolution (resolution.dynamic) measures a frame by the GPU timer where there is one (the sum of its
    // passes), else by the interval between frames (below).
    if (timer.results() != timerResults) {
      timerResults = timer.results();
      double gpuMs = 0.0;
      for (double pass : timer.lastResult()) gpuMs += std::max(pass, 0.0);
      viewer.frameMeasured(gpuMs, static_cast<float>(timer.lastResultTag()));
    }
    if (!options.screenshot.empty() && frame >= options.frames) {
      Image image;
      image.width = width;
      image.height = height;
      image.rgba = gl::readPixelsTopDown(width, height);
      writePng(options.screenshot, image);
      return 0;
    }
    glfwSwapBuffers(window.handle());

    const double now = glfwGetTime();
    const double ms = (now - last) * 1000.0;
    frameMs = frameMs == 0.0 ? ms : frameMs + kSmoothing * (ms - frameMs);
    if (!timer.available()) viewer.frameMeasured(ms, lastScale);
    last = now;
    if (now - lastTitle >= kTitleInterval) {
      glfwSetWindowTitle(window.handle(), title(viewer, frameMs, timer, input.message()).c_str());
      lastTitle = now;
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parseOptions(argc, argv));
  } catch (const InputError& e) {
    std::cerr << "obscura-view: " << e.what() << "\n";
    return 2;
  } catch (const GlError& e) {
    std::cerr << "obscura-view: GL error: " << e.what() << "\n";
    return 1;
  } catch (const PipelineError& e) {
    std::cerr << "obscura-view: " << e.what() << "\n";
    return 1;
  }
}
