#include "apps/ReferenceCommandLine.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <thread>

#include "base/Error.h"
#include "effects/ao/AoSettings.h"
#include "scene/ImageIo.h"

namespace obscura {

std::string referenceUsage() {
  return "usage: obscura-reference [--scene FILE [--scene-scale S]] [--time T] [--animation A]\n"
         "                         [--camera CAM.json | --fit | --camera-node C] [--orthographic] [--size WxH]\n"
         "                         [--radius R] [--rays N] [--threads N]\n"
         "                         [--view ao|depth|mask] [--out FILE.png] [--depth-out FILE.png]\n"
         "                         [--mask-out FILE.png]\n"
         "\n"
         "Ray-traces (Embree) the ambient visibility A = (1/pi) * integral of V_R(w) cos(theta) dw of the scene\n"
         "obscura-render draws, with the same scene, moment of its animation, camera and view conventions\n"
         "(docs/accuracy.md).\n" +
         sceneInputUsage() +
         "  --radius R        AO radius in scene units, as obscura-render's --radius (1e-4 .. 1e6; default: below)\n"
         "  --rays N          cosine-weighted hemisphere rays per pixel, a power of two (default 256)\n"
         "  --threads N       worker threads (default: the number of cores); the image does not depend on it\n"
         "  --view V          ao (default) | depth | mask, encoded as obscura-render's views\n"
         "  --out FILE        the --view image (default reference.png)\n"
         "  --depth-out FILE  also write the depth view from the same trace\n"
         "  --mask-out FILE   also write the mask view (geometry 255, background 0)\n"
         "\n" + defaultAoRadiusUsage("--radius") +
         "obscura-render chooses the same for the same scene, so their images compare without a radius given.\n";
}

ReferenceOptions parseReferenceCommandLine(const std::vector<std::string>& args) {
  ReferenceOptions options;
  options.trace.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw InputError(arg + ": missing value");
      return args[++i];
    };
    auto file = [&]() {
      const std::string& path = value();
      if (path.empty()) throw InputError(arg + ": empty file name");
      return path;
    };
    if (arg == "--help" || arg == "-h") options.help = true;
    else if (options.input.parseOption(args, i)) continue;
    else if (arg == "--radius") {
      // The same parameter, range and message as obscura-render's --radius.
      AoSettings settings;
      try {
        settings.set("radius", value());
      } catch (const InputError& e) {
        throw InputError(std::string("--") + e.what());
      }
      options.trace.radius = settings.radius;
      options.radiusGiven = true;
    } else if (arg == "--rays") options.trace.rays = parseCount(arg, value(), 65536);
    else if (arg == "--threads") options.trace.threads = parseCount(arg, value(), 256);
    else if (arg == "--view") {
      const std::string& view = value();
      if (view == "ao") options.view = ReferenceView::Ao;
      else if (view == "depth") options.view = ReferenceView::Depth;
      else if (view == "mask") options.view = ReferenceView::Mask;
      else throw InputError("--view: expected ao, depth or mask, got '" + view + "'");
    } else if (arg == "--out") options.outPath = file();
    else if (arg == "--depth-out") options.depthOutPath = file();
    else if (arg == "--mask-out") options.maskOutPath = file();
    else throw InputError("unknown option '" + arg + "' (see --help)");
  }
  options.input.check();
  try {
    validateReferenceSettings(options.trace);  // e.g. rays not a power of two
  } catch (const InputError& e) {
    throw InputError(std::string("--") + e.what());
  }
  return options;
}

int runReference(const ReferenceOptions& options) {
  if (options.help) {
    std::cout << referenceUsage();
    return 0;
  }
  try {
    validateReferenceSettings(options.trace);
    const SceneInput::Loaded input = options.input.load();
    options.input.printWarnings("obscura-reference", input.warnings);
    const Camera& camera = input.camera;
    ReferenceSettings trace = options.trace;
    // The radius from the scene at rest, as obscura-render chooses it; the trace of the scene posed at --time with
    // --animation, as obscura-render draws it.
    if (!options.radiusGiven) trace.radius = chooseDefaultAoRadius("obscura-reference", "--radius", input.scene);
    const Scene scene = input.posedAt(options.input.time);

    const auto start = std::chrono::steady_clock::now();
    const AoReferenceTracer tracer(scene, trace.threads);
    const auto built = std::chrono::steady_clock::now();
    const ReferenceFrame frame = tracer.trace(camera, trace);
    const auto done = std::chrono::steady_clock::now();

    const Image views[] = {frame.aoImage(), frame.depthImage(), frame.maskImage()};
    writePng(options.outPath, views[static_cast<int>(options.view)]);
    if (!options.depthOutPath.empty()) writePng(options.depthOutPath, views[1]);
    if (!options.maskOutPath.empty()) writePng(options.maskOutPath, views[2]);

    size_t geometry = 0;
    for (std::uint8_t m : frame.mask) geometry += m;
    const double buildSeconds = std::chrono::duration<double>(built - start).count();
    const double traceSeconds = std::chrono::duration<double>(done - built).count();
    const double rays = static_cast<double>(geometry) * trace.rays + static_cast<double>(frame.mask.size());
    std::printf("obscura-reference: %dx%d, radius %g, %d rays per pixel, %zu triangles, %d threads: "
                "BVH %.2f s, trace %.2f s (%.1f M rays/s)\n",
                camera.width, camera.height, static_cast<double>(trace.radius), trace.rays,
                tracer.triangleCount(), trace.threads, buildSeconds, traceSeconds,
                rays / traceSeconds * 1e-6);
    return 0;
  } catch (const InputError& e) {
    std::cerr << "obscura-reference: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "obscura-reference: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace obscura
