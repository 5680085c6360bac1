// obscura-bench: the performance figures of the AO pipeline, measured in one run (docs/benchmarks.md).
//
//   obscura-bench [--out DIR] [--frames N] [--backend osmesa|egl] [--quick]
//
// Prints tables and writes DIR/bench.csv (every measurement), DIR/radius_sweep.csv and DIR/radius_sweep.png
// (gnuplot). Every pass is bounded by glFinish on both sides and reported as the median over N frames.
// Sections:
//   1. per-pass ms at 640x360, 1280x720 and 1920x1080 on the built-in scene and on 2CylinderEngine.glb
//   2. radius sweep 0.25 .. 4 m, depth hierarchy on and off
//   3. sample-count sweep 4 .. 32
//   4. the quality presets
//   5. ratios measured in this run: SAO / G-buffer, SAO(r = 4 m) / SAO(r = 0.5 m) with and without the hierarchy
//      (goal <= 1.15 with it), SAO / a floor pass making the same fetches with no arithmetic
#include <cstdio>
#include <cstdlib>
#include <array>
#include <cmath>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/AoSettings.h"
#include "core/Error.h"
#include "core/FetchFloorPass.h"
#include "core/Renderer.h"
#include "core/SaoKernel.h"
#include "gl/RenderTarget.h"
#include "platform/FinishPassTimer.h"
#include "platform/HeadlessContext.h"
#include "scene/BuiltinScene.h"
#include "scene/GltfLoader.h"

using namespace obscura;

namespace {

const char* kEnginePath = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
constexpr Pass kPasses[] = {Pass::GBuffer, Pass::Hierarchy, Pass::Sao, Pass::BlurHorizontal,
                            Pass::BlurVertical, Pass::Upsample, Pass::Composite};

struct Options {
  std::string outDir = "bench-results";
  int frames = 12;
  HeadlessBackend backend = HeadlessBackend::OSMesa;
  bool quick = false;
};

struct BenchScene {
  std::string name;
  Scene scene;
  Camera camera;
};

using PassTimes = std::array<double, static_cast<size_t>(Pass::Count)>;

class Bench {
 public:
  Bench(const Options& options, HeadlessContext& context)
      : options_(options), context_(context), renderer_(context.caps()), csv_(options.outDir + "/bench.csv") {
    if (!csv_) throw InputError(options.outDir + "/bench.csv: cannot write");
    csv_ << "section,scene,width,height,preset,samples,radius_m,hierarchy,half_res,pass,median_ms\n";
  }

  void useScene(const BenchScene& scene) {
    if (current_ == &scene) return;
    renderer_.setScene(scene.scene);
    current_ = &scene;
  }

  // Median per-pass times of `frames` frames of the final view (after one warm-up frame).
  PassTimes measure(const std::string& section, const BenchScene& scene, int width, int height,
                    const AoSettings& settings, const std::string& preset) {
    useScene(scene);
    Camera camera = scene.camera;
    camera.width = width;
    camera.height = height;
    const gl::RenderTarget output("bench output", width, height, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                  context_.caps().depth24);
    const OutputTarget target{output.framebuffer(), width, height, 0.0f};
    renderer_.render(camera, settings, View::Final, target);
    FinishPassTimer timer;
    for (int frame = 0; frame < options_.frames; ++frame) renderer_.render(camera, settings, View::Final, target, &timer);
    PassTimes times{};
    for (Pass pass : kPasses) {
      times[static_cast<size_t>(pass)] = timer.medianMs(pass);
      if (timer.samples(pass).empty()) continue;
      csv_ << section << "," << scene.name << "," << width << "," << height << "," << preset << ","
           << settings.samples << "," << settings.radius << "," << (settings.depthHierarchy ? 1 : 0) << ","
           << (settings.halfResolution ? 1 : 0) << "," << passName(pass) << "," << times[static_cast<size_t>(pass)]
           << "\n";
    }
    return times;
  }

  // The floor pass at the same size, sample count and a disk of `diskRadius` pixels.
  double measureFloor(const BenchScene& scene, int width, int height, const AoSettings& settings, float diskRadius) {
    measure("floor-setup", scene, width, height, settings, "medium");  // leaves the G-buffer of this view
    FetchFloorPass floor(triangle_);
    floor.render(renderer_.gbuffer().color(), settings.samples, settings.spiralTurns, diskRadius);  // warm-up
    FinishPassTimer timer;
    for (int frame = 0; frame < options_.frames; ++frame) {
      timer.begin(Pass::Sao);
      floor.render(renderer_.gbuffer().color(), settings.samples, settings.spiralTurns, diskRadius);
      timer.end(Pass::Sao);
    }
    const double ms = timer.medianMs(Pass::Sao);
    csv_ << "floor," << scene.name << "," << width << "," << height << ",medium," << settings.samples << ","
         << settings.radius << ",0,0,fetch-floor," << ms << "\n";
    return ms;
  }

  const Renderer& renderer() const { return renderer_; }

 private:
  const Options& options_;
  HeadlessContext& context_;
  Renderer renderer_;
  FullscreenTriangle triangle_;
  std::ofstream csv_;
  const BenchScene* current_ = nullptr;
};

double total(const PassTimes& t) {
  double sum = 0.0;
  for (double v : t) sum += v;
  return sum;
}

void printPassHeader() {
  std::printf("%-16s %-10s", "scene", "size");
  for (Pass pass : kPasses) std::printf(" %9s", passName(pass));
  std::printf(" %9s\n", "total");
}

void printPassRow(const std::string& scene, int width, int height, const PassTimes& t) {
  std::printf("%-16s %-10s", scene.c_str(), (std::to_string(width) + "x" + std::to_string(height)).c_str());
  for (Pass pass : kPasses) std::printf(" %9.2f", t[static_cast<size_t>(pass)]);
  std::printf(" %9.2f\n", total(t));
}

Options parseOptions(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw InputError(arg + ": missing value");
      return argv[++i];
    };
    if (arg == "--out") options.outDir = value();
    else if (arg == "--frames") {
      const std::string text = value();
      char* end = nullptr;
      const long frames = std::strtol(text.c_str(), &end, 10);
      if (*end != '\0' || frames < 1 || frames > 1000) throw InputError("--frames: expected 1 .. 1000, got '" + text + "'");
      options.frames = static_cast<int>(frames);
    } else if (arg == "--backend") options.backend = parseBackend(value());
    else if (arg == "--quick") options.quick = true;
    else throw InputError("unknown option '" + arg + "' (usage: obscura-bench [--out DIR] [--frames N] "
                          "[--backend osmesa|egl] [--quick])");
  }
  return options;
}

void writePlot(const std::string& dir) {
  const std::string script = dir + "/radius_sweep.gnuplot";
  std::ofstream(script) << "set terminal pngcairo size 900,480 font 'sans,11'\n"
                           "set output '" << dir << "/radius_sweep.png'\n"
                           "set datafile separator ','\n"
                           "set key top left\n"
                           "set logscale x 2\n"
                           "set xlabel 'AO radius (m)'\n"
                           "set ylabel 'SAO pass (ms, median)'\n"
                           "set yrange [0:*]\n"
                           "set grid\n"
                           "set title 'SAO cost vs radius, built-in scene 1280x720'\n"
                           "plot '" << dir << "/radius_sweep.csv' using 1:2 skip 1 with linespoints lw 2 "
                           "title 'depth hierarchy on', '' using 1:3 skip 1 with linespoints lw 2 "
                           "title 'depth hierarchy off'\n";
  if (std::system(("gnuplot '" + script + "'").c_str()) != 0)
    std::fprintf(stderr, "obscura-bench: gnuplot failed; %s/radius_sweep.csv has the data\n", dir.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options options = parseOptions(argc, argv);
    if (std::system(("mkdir -p '" + options.outDir + "'").c_str()) != 0)
      throw InputError(options.outDir + ": cannot create");
    HeadlessContext context(options.backend);
    std::printf("obscura-bench: %s (%s), %d frames per figure (median), passes bounded by glFinish\n",
                backendName(options.backend), context.caps().renderer.c_str(), options.frames);

    std::vector<BenchScene> scenes;
    scenes.push_back({"builtin", makeBuiltinScene(), builtinSceneCamera()});
    Scene engine = loadGltfFile(kEnginePath);
    const Camera engineCamera = Camera::fit(engine.worldBounds(), 1280, 720);
    scenes.push_back({"2CylinderEngine", std::move(engine), engineCamera});
    Bench bench(options, context);
    const AoSettings defaults;
    const BenchScene& builtin = scenes[0];

    std::printf("\n1. Per-pass ms, default settings (%d samples, r = %.2f m, hierarchy on)\n", defaults.samples,
                defaults.radius);
    printPassHeader();
    const std::vector<std::pair<int, int>> sizes =
        options.quick ? std::vector<std::pair<int, int>>{{640, 360}}
                      : std::vector<std::pair<int, int>>{{640, 360}, {1280, 720}, {1920, 1080}};
    for (const BenchScene& scene : scenes)
      for (auto [w, h] : sizes) printPassRow(scene.name, w, h, bench.measure("passes", scene, w, h, defaults, "medium"));

    const int w = options.quick ? 640 : 1280, h = options.quick ? 360 : 720;
    std::printf("\n2. Radius sweep, built-in scene %dx%d: SAO pass ms (hierarchy pass ms)\n", w, h);
    std::printf("%10s %18s %18s\n", "radius m", "hierarchy on", "hierarchy off");
    std::ofstream sweep(options.outDir + "/radius_sweep.csv");
    sweep << "radius_m,sao_ms_hierarchy,sao_ms_no_hierarchy\n";
    double saoAt[2][2] = {};  // [hierarchy][r=0.5, r=4]
    for (float radius : {0.25f, 0.5f, 1.0f, 2.0f, 3.0f, 4.0f}) {
      AoSettings settings = defaults;
      settings.radius = radius;
      settings.depthHierarchy = true;
      const PassTimes on = bench.measure("radius", builtin, w, h, settings, "medium");
      settings.depthHierarchy = false;
      const PassTimes off = bench.measure("radius", builtin, w, h, settings, "medium");
      const double saoOn = on[static_cast<size_t>(Pass::Sao)], saoOff = off[static_cast<size_t>(Pass::Sao)];
      std::printf("%10.2f %11.2f (%4.2f) %18.2f\n", radius, saoOn, on[static_cast<size_t>(Pass::Hierarchy)], saoOff);
      sweep << radius << "," << saoOn << "," << saoOff << "\n";
      if (radius == 0.5f) saoAt[1][0] = saoOn, saoAt[0][0] = saoOff;
      if (radius == 4.0f) saoAt[1][1] = saoOn, saoAt[0][1] = saoOff;
    }
    sweep.close();
    writePlot(options.outDir);

    std::printf("\n3. Sample-count sweep, built-in scene %dx%d: SAO pass ms\n", w, h);
    for (int samples : {4, 8, 11, 16, 24, 32}) {
      AoSettings settings = defaults;
      settings.samples = samples;
      settings.spiralTurns = SaoKernel::bestSpiralTurns(samples);
      const PassTimes t = bench.measure("samples", builtin, w, h, settings, "custom");
      std::printf("%10d samples %9.2f ms\n", samples, t[static_cast<size_t>(Pass::Sao)]);
    }

    std::printf("\n4. Quality presets, built-in scene %dx%d\n", w, h);
    printPassHeader();
    for (const PresetInfo& preset : qualityPresets()) {
      AoSettings settings = defaults;
      settings.applyPreset(preset.preset);
      printPassRow(preset.name, w, h, bench.measure("presets", builtin, w, h, settings, preset.name));
    }

    std::printf("\n5. Ratios (this run, built-in scene %dx%d)\n", w, h);
    const PassTimes base = bench.measure("ratios", builtin, w, h, defaults, "medium");
    const double sao = base[static_cast<size_t>(Pass::Sao)];
    const Camera& camera = builtin.camera;
    const float distance = glm::length(camera.target - camera.eye);
    const float disk = std::min(static_cast<float>(h) / (2.0f * std::tan(camera.fovyRadians() * 0.5f)) *
                                    defaults.radius / distance,
                                defaults.maxScreenRadius * static_cast<float>(h));
    const double floor = bench.measureFloor(builtin, w, h, defaults, disk);
    std::printf("  SAO / G-buffer                         %6.2f   (%.2f / %.2f ms)\n",
                sao / base[static_cast<size_t>(Pass::GBuffer)], sao, base[static_cast<size_t>(Pass::GBuffer)]);
    std::printf("  SAO(r=4 m) / SAO(r=0.5 m), hierarchy   %6.2f   (goal <= 1.15)\n", saoAt[1][1] / saoAt[1][0]);
    std::printf("  SAO(r=4 m) / SAO(r=0.5 m), no hierarchy%6.2f\n", saoAt[0][1] / saoAt[0][0]);
    std::printf("  SAO / fetch floor (%d fetches, disk %.0f px)  %6.2f   (%.2f / %.2f ms)\n", defaults.samples + 1,
                disk, sao / floor, sao, floor);
    std::printf("\nobscura-bench: wrote %s/bench.csv, radius_sweep.csv, radius_sweep.png\n", options.outDir.c_str());
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "obscura-bench: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "obscura-bench: %s\n", e.what());
    return 1;
  }
}
