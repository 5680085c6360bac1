#include "apps/RenderCommandLine.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "core/Error.h"
#include "gl/RenderTarget.h"
#include "platform/FinishPassTimer.h"
#include "scene/ImageIo.h"

namespace obscura {

std::string renderUsage() {
  std::string usage =
      "usage: obscura-render [--scene FILE [--scene-scale S]] [--camera CAM.json | --fit] [--size WxH] [--view V]\n"
      "                      [--out FILE.png]\n"
      "                      [--radius R --bias B --intensity I --contrast K --samples N --blur-radius R --no-blur]\n"
      "                      [--preset P] [--no-ao] [--bench N] [--backend osmesa|egl]\n"
      "\n"
      "Renders a glTF 2.0 scene (default: the built-in scene) headless with Scalable Ambient Obscurance.\n"
      + sceneInputUsage() +
      "  --view V          final | ao | ao-raw | normals | depth | mask   (default final)\n"
      "  --out FILE        output PNG (default obscura.png)\n"
      "  --bench N         render N frames and print per-pass milliseconds (glFinish-bounded)\n"
      "  --backend B       osmesa (default) or egl (Mesa EGL surfaceless, a true GLES 2 context)\n"
      "  --no-ao, --no-blur  shorthands for --ao off, --blur off\n"
      "\nAO parameters (--NAME VALUE):\n";
  for (const ParameterInfo& p : aoParameters()) {
    char line[200];
    std::snprintf(line, sizeof line, "  --%-18s %-32s %s\n", p.name, p.range.c_str(), p.help);
    usage += line;
  }
  return usage;
}

RenderOptions parseRenderCommandLine(const std::vector<std::string>& args) {
  RenderOptions options;
  auto isParameter = [](const std::string& name) {
    const auto& params = aoParameters();
    return std::any_of(params.begin(), params.end(), [&](const ParameterInfo& p) { return name == p.name; });
  };
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw InputError(arg + ": missing value");
      return args[++i];
    };
    if (arg == "--help" || arg == "-h") options.help = true;
    else if (options.input.parseOption(args, i)) continue;
    else if (arg == "--view") {
      try {
        options.view = parseView(value());
      } catch (const InputError& e) {
        throw InputError(std::string("--") + e.what());
      }
    } else if (arg == "--out") {
      options.outPath = value();
      if (options.outPath.empty()) throw InputError("--out: empty file name");
    } else if (arg == "--bench") options.benchFrames = parseCount(arg, value(), 100000);
    else if (arg == "--backend") {
      try {
        options.backend = parseBackend(value());
      } catch (const InputError& e) {
        throw InputError(std::string("--") + e.what());
      }
    } else if (arg == "--no-blur") options.ao.blur = false;
    else if (arg == "--no-ao") options.ao.enabled = false;
    else if (arg.rfind("--", 0) == 0 && isParameter(arg.substr(2))) {
      const std::string name = arg.substr(2);
      try {
        options.ao.set(name, value());
      } catch (const InputError& e) {
        throw InputError(std::string("--") + e.what());
      }
    } else {
      throw InputError("unknown option '" + arg + "' (see --help)");
    }
  }
  options.input.check();
  return options;
}

int runRender(const RenderOptions& options) {
  if (options.help) {
    std::cout << renderUsage();
    return 0;
  }
  try {
    // Input first, so a bad file is reported before any GL work.
    const SceneInput::Loaded input = options.input.load();
    const Scene& scene = input.scene;
    const Camera& camera = input.camera;

    HeadlessContext context(options.backend);
    if (std::max(camera.width, camera.height) > context.caps().maxRenderSize())
      throw InputError("--size: " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                       " exceeds this context's limit of " + std::to_string(context.caps().maxRenderSize()) +
                       " per side");
    options.input.printWarnings("obscura-render", input.warnings);  // every input checked: a refusal stays one line
    RendererOptions rendererOptions;
    rendererOptions.checkGlErrors = true;
    Renderer renderer(context.caps(), rendererOptions);
    renderer.setScene(scene);
    const gl::RenderTarget output("output", camera.width, camera.height, GL_NEAREST,
                                  gl::RenderTarget::Depth::Renderbuffer, context.caps().depth24);
    const OutputTarget target{output.framebuffer(), camera.width, camera.height, 0.0f};

    renderer.render(camera, options.ao, options.view, target);  // also warms up shader compilation
    if (options.benchFrames > 0) {
      FinishPassTimer timer;
      const auto start = std::chrono::steady_clock::now();
      for (int frame = 0; frame < options.benchFrames; ++frame)
        renderer.render(camera, options.ao, options.view, target, &timer);
      glFinish();
      const double total = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      std::printf("obscura-render --bench: %dx%d, %d frames, view %s, %d samples, backend %s (%s)\n", camera.width,
                  camera.height, options.benchFrames, viewName(options.view), options.ao.samples,
                  backendName(options.backend), context.caps().renderer.c_str());
      std::printf("%-10s %10s %10s %10s\n", "pass", "mean ms", "min ms", "max ms");
      double sumOfMeans = 0.0;
      for (int p = 0; p < static_cast<int>(Pass::Count); ++p) {
        const std::vector<double>& s = timer.samples(static_cast<Pass>(p));
        if (s.empty()) continue;
        double sum = 0.0;
        for (double v : s) sum += v;
        const double mean = sum / static_cast<double>(s.size());
        sumOfMeans += mean;
        std::printf("%-10s %10.3f %10.3f %10.3f\n", passName(static_cast<Pass>(p)), mean,
                    *std::min_element(s.begin(), s.end()), *std::max_element(s.begin(), s.end()));
      }
      std::printf("%-10s %10.3f   (sum of pass means; wall clock per frame %.3f ms)\n", "total", sumOfMeans,
                  total / options.benchFrames);
    }

    Image image;
    image.width = camera.width;
    image.height = camera.height;
    image.rgba = output.readRgba();
    writePng(options.outPath, image);
    return 0;
  } catch (const InputError& e) {
    std::cerr << "obscura-render: " << e.what() << "\n";
    return 2;
  } catch (const GlError& e) {
    std::cerr << "obscura-render: GL error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace obscura
