// obscura-bench: the performance figures of the AO pipeline, measured in one run (docs/benchmarks.md).
//
//   obscura-bench [--out DIR] [--frames N] [--backend osmesa|egl] [--quick] [--NAME-only]
//   (--NAME-only: one section alone, NAME one in sections() at the end; without it the full run, start-up first)
//
// Prints tables and writes DIR/bench.csv (every measurement), DIR/ratios.csv, DIR/radius_sweep.csv,
// DIR/radius_sweep.png (gnuplot) and DIR/estimators.csv. Every pass is bounded by glFinish on both sides and
// reported as the median over N frames. The passes and effects are the effect table's (renderer/EffectTable.h): a new
// effect shows up by itself. --quick (the suite's smoke run) measures every section at 320x180 alone (the host time
// at 160x90): it checks that the benchmark runs, not its figures.
// Sections:
//   1. per-pass and per-effect ms at 640x360, 1280x720 and 1920x1080 on the built-in scene and on
//      2CylinderEngine.glb, at the defaults (every effect on; each scene at its default AO radius, scene/SceneScale.h)
//   2. radius sweep 0.25 .. 4 m, depth hierarchy on and off (SAO)
//   3. sample-count sweep 4 .. 32 (SAO)
//   4. the quality presets (the default estimator)
//   5. ratios measured in this run: SAO / G-buffer, SAO(r = 4 m) / SAO(r = 0.5 m) with and without the hierarchy
//      (goal <= 1.15 with it), SAO / a floor pass making the same fetches with no arithmetic
//   6. every estimator (ao.estimator) at every preset, taking turns frame by frame (--estimators-only: this alone)
//   7. scenes that move (--motion-only: this alone): a skinned crowd drawn by every skinning path, the same pose
//      baked into still meshes, and the velocity pass drawing only what moves or everything, all taking turns (the
//      AO off); ms of the pose and of each geometry pass (G-buffer, lighting, velocity), written to DIR/motion.csv
//   8. every effect at 640x360 and 1280x720 (--effects-only: this alone): the moving built-in scene playing at 60
//      frames per second, the defaults against every switch on (motion blur and TAA included), and the AO's
//      temporal accumulation at 4 taps against the single frame, and bloom and fog on over the defaults; ms per
//      effect, written to DIR/effects.csv, and the target beside it: bloom's ms against the G-buffer pass's
//      in the same frames; and depth of field on over the defaults, its ms against the SAO pass's
//   8c. the camera's finish (--finish-only: this alone): auto exposure (average and percentile metering), lens flare
//      and glare on bloom, hatching against the lines, at 640x360 and 1280x720, all taking turns frame by frame;
//      each configuration's passes, and what the tone mapping pays for reading the exposure and adding the lens's
//      light (DIR/finish.csv)
//   8e. the display colour's stages (--stages-only: this alone): grading (its balance, its LUT, both), the vignette,
//      the grain and the dithering, fused into the lighting (and with TAA into the tone curve's pass), at 640x360
//      and 1280x720 taking turns frame by frame; what each adds to the pass it joins (DIR/stages.csv)
//   8d. the transparent pass, transmission and clear coat on the glass sample and its variants
//      (assets/scenes/glass-samples.glb), with section 8 (--transparency-only: this alone; DIR/transparency.csv)
//   9. temporal AO (--temporal-ao-only: this alone): the default AO in one frame against 4 taps accumulated by
//      ao.temporal (default blur, a 5-tap and a 3-tap one), and 4 taps alone, taking turns frame by frame at 640x360
//      and 1280x720 on the still room (DIR/temporal_ao.csv)
//   0. start-up (run first, in a process that has made nothing yet; --startup-only: this alone): the first Renderer
//      (its programs, the built-in sky made and prefiltered, ...), the built-in scene uploaded, the first frame and
//      a steady frame at 1280x720, each part as base/TimeSpent.h counts it (DIR/startup.csv)
//  10. the lighting (--lighting-only: this alone), on 2CylinderEngine.glb and the metallic-roughness sample at
//      640x360 and 1280x720, all configurations of a scene and size taking turns frame by frame: the AO on against
//      the AO off with each lighting.depth, at the medium and low tiers; each tier's lighting pass, and its error
//      against the high tier's image; the environment's levels as half floats (the default where the context filters
//      them) against the fallbacks: RGB9E5 filtered by hand, and the rough levels as RGBM (DIR/lighting.csv)
//  11. the render scale (--resolution-only: this alone): the default frame at full size against scale 0.75 and 0.5
//      with the edge upscale and 0.5 with the bilinear one, taking turns, at 640x360 and 1280x720, beside the issue's
//      target (scale 0.5 + edge <= 0.35 x the full frame); and each upscale's error against the full-size frame
//      (metrics/UpscaleMetrics.h: MAE, edge MAE; target: edge <= 0.8 x bilinear's) (DIR/resolution.csv)
//  12. the AO's depth layers and normals (--ao-layers-only: this alone): the default AO against ao.layers 2 and
//      gbuffer.normals reconstructed, without the depth hierarchy (ao.hierarchy auto: the estimator reads the second
//      layer's target beside the G-buffer), and each layer count with the hierarchy's atlas (ao.hierarchy on; with
//      two layers both in one texel), taking turns frame by frame at 640x360 and 1280x720 on the still room and the
//      engine (DIR/ao_layers.csv)
//  13. host time per frame (--host-only: this alone): the renderer's own CPU time in Renderer::render (the calling
//      thread's CPU clock: planning, GL calls and what the driver does on that thread; llvmpipe rasterises on threads
//      of its own), median of 4 x N frames of the moving built-in scene, the defaults and every effect on, at
//      1280x720 and at 160x90 (where the driver's work is least); DIR/host.csv
//  14. the scene's bounds (--scene-bounds-only: this alone): the frame with the passes limited to the scene's bounds
//      on screen (PassContext::sceneRect) against the same passes over the whole frame (RendererOptions::limitToScene
//      off), the defaults, `preset low` and the AO off, taking turns frame by frame on the engine and the still room
//      at 640x360 and 1280x720 (DIR/scene_bounds.csv)
//  15. frustum culling (--culling-only; alone only): the frame with the instances outside the view left out
//      (GpuScene::cullToView) against every instance drawn (RendererOptions::cullToView off), the same configurations
//      taking turns, on the built-in room's columns view, the engine's detail view and the millimetre room's table
//      view (tools/tuning-views.json) at 640x360 and 1280x720 (DIR/culling.csv)
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <tuple>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "FetchFloorPass.h"
#include "apps/SceneInput.h"
#include "base/Error.h"
#include "base/Text.h"
#include "base/TimeSpent.h"
#include "effects/ao/AoSettings.h"
#include "effects/ao/DepthHierarchyPass.h"
#include "effects/ao/SaoKernel.h"
#include "encoding/ColorLut.h"
#include "frame/Resolution.h"
#include "gl/RenderTarget.h"
#include "metrics/UpscaleMetrics.h"
#include "platform/FinishPassTimer.h"
#include "platform/HeadlessContext.h"
#include "renderer/Renderer.h"
#include "scene/Animation.h"
#include "scene/BuiltinScene.h"
#include "scene/GltfLoader.h"
#include "scene/Primitives.h"
#include "scene/SceneScale.h"
#include "scene/SkinnedTube.h"

using namespace obscura;

namespace {

const char* kEnginePath = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
constexpr float kEngineScale = 0.01f;

// The passes a frame of the final image may run (the table's, without the debug views' own).
const std::vector<std::string>& benchPasses() {
  static const std::vector<std::string> passes = [] {
    std::vector<std::string> out;
    for (const std::string& pass : framePassNames())
      if (pass != "view" && pass != "present" && pass != "shading-count") out.push_back(pass);
    return out;
  }();
  return passes;
}

struct Options {
  std::string outDir = "bench-results";
  int frames = 15;
  HeadlessBackend backend = HeadlessBackend::OSMesa;
  bool quick = false;
  // The section --NAME-only runs alone (a name in sections(), below main's helpers), or empty: every section.
  std::string only;
  bool alone(const char* section) const { return only == section; }
  using Sizes = std::vector<std::pair<int, int>>;
  // The sizes a section measures: the given ones, or with --quick (the smoke run, tools.bench_smoke) the smallest
  // size the smoke run takes, 320x180, whatever the section measures at full.
  Sizes sizes(Sizes full) const { return quick ? Sizes{{320, 180}} : full; }
  std::pair<int, int> size(int w, int h) const { return sizes({{w, h}}).front(); }
};

struct BenchScene {
  std::string name;
  Scene scene;
  Camera camera;
};

// Median ms per pass name (0: did not run).
using PassTimes = std::map<std::string, double>;

class Bench {
 public:
  Bench(const Options& options, HeadlessContext& context)
      : options_(options), context_(context), renderer_(context.caps()), csv_(options.outDir + "/bench.csv") {
    for (DepthHierarchyPass::Storage storage :
         {DepthHierarchyPass::Storage::SeparateTextures, DepthHierarchyPass::Storage::Atlas}) {
      RendererOptions forced;
      forced.hierarchyStorage = storage;
      storageRenderers_.push_back(std::make_unique<Renderer>(context.caps(), forced));
    }
    if (!csv_) throw InputError(options.outDir + "/bench.csv: cannot write");
    csv_ << "section,scene,width,height,preset,samples,radius_m,hierarchy,half_res,pass,median_ms\n";
  }

  // The scene set on every renderer, its camera at the given size, and an offscreen target to draw into.
  struct BenchView {
    BenchView(Bench& bench, const BenchScene& scene, int width, int height)
        : camera(sized(scene.camera, width, height)),
          output("bench output", width, height, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                 bench.context_.caps().depth24, bench.context_.caps().packedDepthStencil),  // like a window's
          target{output.framebuffer(), width, height, {}} {
      bench.useScene(scene);
    }
    static Camera sized(Camera camera, int width, int height) {
      camera.width = width;
      camera.height = height;
      return camera;
    }
    Camera camera;
    gl::RenderTarget output;
    OutputTarget target;
  };

  void useScene(const BenchScene& scene) {
    if (current_ == &scene) return;
    renderer_.setScene(scene.scene);
    for (auto& r : storageRenderers_) r->setScene(scene.scene);
    current_ = &scene;
  }

  // SAO pass medians for the same settings with the hierarchy stored as separate textures and as an atlas, taking
  // turns frame by frame: {separate, atlas}.
  std::pair<double, double> measureStorages(const BenchScene& scene, int width, int height,
                                            const RenderSettings& settings) {
    const BenchView view(*this, scene, width, height);
    const Camera& camera = view.camera;
    const OutputTarget& target = view.target;
    std::vector<FinishPassTimer> timers(storageRenderers_.size());
    for (auto& r : storageRenderers_) r->render(camera, settings, View::Final, target);
    for (int frame = 0; frame < options_.frames; ++frame)
      for (size_t i = 0; i < storageRenderers_.size(); ++i)
        storageRenderers_[i]->render(camera, settings, View::Final, target, &timers[i]);
    for (size_t i = 0; i < storageRenderers_.size(); ++i)
      csv_ << "storage," << scene.name << "," << width << "," << height << ","
           << DepthHierarchyPass::storageName(storageRenderers_[i]->hierarchyStorage()) << ","
           << settings.ao().samples << "," << settings.ao().radius << ",1,0,sao," << timers[i].medianMs("sao") << "\n";
    return {timers[0].medianMs("sao"), timers[1].medianMs("sao")};
  }

  // Median per-pass times of `frames` frames of the final view for each of `configurations`, after one warm-up
  // frame each. The configurations take turns frame by frame, so a slow spell of the machine (other processes,
  // frequency changes) falls on all of them alike and the ratios between them stay sound.
  std::vector<PassTimes> measure(const std::string& section, const BenchScene& scene, int width, int height,
                                 const std::vector<RenderSettings>& configurations) {
    const BenchView view(*this, scene, width, height);
    const Camera& camera = view.camera;
    const OutputTarget& target = view.target;
    for (const RenderSettings& settings : configurations) renderer_.render(camera, settings, View::Final, target);
    std::vector<FinishPassTimer> timers(configurations.size());
    for (int frame = 0; frame < options_.frames; ++frame)
      for (size_t c = 0; c < configurations.size(); ++c)
        renderer_.render(camera, configurations[c], View::Final, target, &timers[c]);
    for (const PlannedPass& pass : renderer_.lastPlan().passes())
      for (const std::string& absorbed : pass.absorbed) doneBy_[absorbed] = pass.decl.name;
    std::vector<PassTimes> results;
    for (size_t c = 0; c < configurations.size(); ++c) {
      const AoSettings& settings = configurations[c].ao();
      PassTimes times;
      for (const std::string& pass : benchPasses()) {
        times[pass] = timers[c].medianMs(pass);
        if (timers[c].samples(pass).empty()) continue;
        const std::string presetName = configurations[c].get("preset");
        csv_ << section << "," << scene.name << "," << width << "," << height << ","
             << (presetName.empty() ? "custom" : presetName) << ","
             << settings.samples << "," << settings.radius << "," << (settings.usesDepthHierarchy() ? 1 : 0) << ","
             << (settings.halfResolution ? 1 : 0) << "," << pass << "," << times[pass] << "\n";
      }
      results.push_back(times);
    }
    return results;
  }

  PassTimes measure(const std::string& section, const BenchScene& scene, int width, int height,
                    const RenderSettings& settings) {
    return measure(section, scene, width, height, std::vector<RenderSettings>{settings}).front();
  }

  // Passes whose work another pass did in the frames measured (the tone curve in the lighting): absorbed -> doer.
  const std::map<std::string, std::string>& doneBy() const { return doneBy_; }

  // The SAO pass and the floor pass at the same size and sample count (a disk of `diskRadius` pixels), taking turns
  // frame by frame. Returns {SAO median ms, floor median ms}.
  std::pair<double, double> measureAgainstFloor(const BenchScene& scene, int width, int height,
                                                const AoSettings& settings, float diskRadius) {
    FrameOptions keepGbuffer;
    keepGbuffer.retain = {"gbuffer"};
    const BenchView view(*this, scene, width, height);
    const Camera& camera = view.camera;
    const OutputTarget& target = view.target;
    FetchFloorPass floor(triangle_);
    renderer_.render(camera, settings, View::Final, target, keepGbuffer);
    floor.render(renderer_.retained("gbuffer").color(), settings.samples, settings.spiralTurns, diskRadius);  // warm-up
    FinishPassTimer saoTimer, floorTimer;
    for (int frame = 0; frame < options_.frames; ++frame) {
      keepGbuffer.timer = &saoTimer;
      renderer_.render(camera, settings, View::Final, target, keepGbuffer);
      floorTimer.begin("sao");
      floor.render(renderer_.retained("gbuffer").color(), settings.samples, settings.spiralTurns, diskRadius);
      floorTimer.end("sao");
    }
    const double sao = saoTimer.medianMs("sao"), floorMs = floorTimer.medianMs("sao");
    csv_ << "floor," << scene.name << "," << width << "," << height << ",medium," << settings.samples << ","
         << settings.radius << "," << (settings.usesDepthHierarchy() ? 1 : 0) << ",0,sao," << sao << "\n";
    csv_ << "floor," << scene.name << "," << width << "," << height << ",medium," << settings.samples << ","
         << settings.radius << ",0,0,fetch-floor," << floorMs << "\n";
    return {sao, floorMs};
  }

  const Renderer& renderer() const { return renderer_; }

 private:
  const Options& options_;
  HeadlessContext& context_;
  Renderer renderer_;  // the default storage (the atlas here: the headless contexts lack the mip-chain extensions)
  std::vector<std::unique_ptr<Renderer>> storageRenderers_;  // forced: separate textures, atlas
  FullscreenTriangle triangle_;
  std::ofstream csv_;
  const BenchScene* current_ = nullptr;
  std::map<std::string, std::string> doneBy_;
};

double total(const PassTimes& t) {
  double sum = 0.0;
  for (const auto& [pass, ms] : t) sum += ms;
  return sum;
}

double at(const PassTimes& t, const std::string& pass) {
  const auto it = t.find(pass);
  return it == t.end() ? 0.0 : it->second;
}

// One effect's milliseconds: the sum of its passes.
double effectMs(const PassTimes& t, const EffectEntry& effect) {
  double sum = 0.0;
  for (const std::string& pass : effect.info.passes) sum += at(t, pass);
  return sum;
}

void printPassHeader() {
  std::printf("%-16s %-10s", "scene", "size");
  for (const std::string& pass : benchPasses()) std::printf(" %9s", pass.c_str());
  std::printf(" %9s\n", "total");
}

void printPassRow(const std::string& scene, int width, int height, const PassTimes& t) {
  std::printf("%-16s %-10s", scene.c_str(), (std::to_string(width) + "x" + std::to_string(height)).c_str());
  for (const std::string& pass : benchPasses()) std::printf(" %9.2f", at(t, pass));
  std::printf(" %9.2f\n", total(t));
}

void printEffectHeader() {
  std::printf("%-16s %-10s", "scene", "size");
  for (const EffectEntry& effect : effectTable()) std::printf(" %9s", effect.info.name.c_str());
  std::printf(" %9s\n", "total");
}

void printEffectRow(const std::string& scene, int width, int height, const PassTimes& t) {
  std::printf("%-16s %-10s", scene.c_str(), (std::to_string(width) + "x" + std::to_string(height)).c_str());
  for (const EffectEntry& effect : effectTable()) std::printf(" %9.2f", effectMs(t, effect));
  std::printf(" %9.2f\n", total(t));
}

// `alone`: the sections' names, each an option --NAME-only.
Options parseOptions(int argc, char** argv, const std::vector<std::string>& alone) {
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
    else if (std::find_if(alone.begin(), alone.end(), [&](const std::string& section) {
               return arg == "--" + section + "-only";
             }) != alone.end())
      options.only = arg.substr(2, arg.size() - 7);
    else {
      std::string usage = "obscura-bench [--out DIR] [--frames N] [--backend osmesa|egl] [--quick]";
      for (const std::string& section : alone) usage += " [--" + section + "-only]";
      throw InputError("unknown option '" + arg + "' (usage: " + usage + ")");
    }
  }
  return options;
}

// Section 6: every estimator at every preset on the built-in scene, all taking turns frame by frame: the AO effect's
// passes (hierarchy, estimator, blur, upsample) and the estimator pass alone; written to DIR/estimators.csv. With
// docs/accuracy.md's error per estimator and preset, this is the cost side of "beats SAO at the same cost".
void estimatorSection(Bench& bench, const BenchScene& scene, int w, int h, const std::string& outDir) {
  const std::vector<AoEstimator>& estimators = allAoEstimators();
  const EffectEntry& aoEffect = effectEntry("ao");
  // The column every other is divided by.
  const size_t sao = static_cast<size_t>(
      std::find(estimators.begin(), estimators.end(), AoEstimator::Sao) - estimators.begin());
  std::vector<RenderSettings> configurations;
  for (QualityPreset preset : allQualityPresets()) {
    for (AoEstimator estimator : estimators) {
      RenderSettings settings;
      settings.applyPreset(preset);
      settings.ao().estimator = estimator;
      configurations.push_back(settings);
    }
  }
  const AoSettings defaults;
  std::printf("\n6. Estimators, built-in scene %dx%d, r = %s: AO effect ms (its passes: hierarchy, estimator, blur, "
              "upsample) / the estimator pass alone; all %zu configurations take turns frame by frame\n",
              w, h, formatShortest(defaults.radius).c_str(), configurations.size());
  const std::vector<PassTimes> times = bench.measure("estimators", scene, w, h, configurations);
  std::printf("%-8s", "preset");
  for (AoEstimator estimator : estimators) std::printf(" %17s", estimatorName(estimator));
  std::printf("   %s\n", "each / sao (AO effect)");
  std::ofstream csv(outDir + "/estimators.csv");
  csv << "preset,estimator,width,height,ao_effect_ms,estimator_pass_ms,ao_effect_over_sao\n";
  for (size_t p = 0; p < allQualityPresets().size(); ++p) {
    const char* preset = presetName(allQualityPresets()[p]);
    std::printf("%-8s", preset);
    const double saoEffect = effectMs(times[p * estimators.size() + sao], aoEffect);
    std::string relative;  // each estimator's AO effect over SAO's, at this preset
    for (size_t e = 0; e < estimators.size(); ++e) {
      const PassTimes& t = times[p * estimators.size() + e];
      const double effect = effectMs(t, aoEffect);
      std::printf(" %8.2f / %6.2f", effect, at(t, "sao"));
      char ratio[16];
      std::snprintf(ratio, sizeof ratio, " %.2f", effect / saoEffect);
      relative += ratio;
      csv << preset << "," << estimatorName(estimators[e]) << "," << w << "," << h << "," << effect << ","
          << at(t, "sao") << "," << effect / saoEffect << "\n";
    }
    std::printf("  %s\n", relative.c_str());
  }
}

// Section 12: what the AO's second depth layer and its normals from depth cost (docs/accuracy.md has what they buy).
// GTAO at the medium preset, every configuration taking turns frame by frame: one layer and two, stored normals and
// reconstructed ones, with ao.hierarchy auto (no hierarchy: every tap reads the G-buffer, and with two layers the
// second layer's target beside it), then each layer count with the hierarchy's atlas (ao.hierarchy on; with two
// layers both in one texel per tap). Per configuration, the G-buffer pass, the peel, the hierarchy, the estimator,
// the blur and the AO effect in all, and that over the default's.
void aoLayersSection(Bench& bench, const std::vector<BenchScene>& scenes,
                     const std::vector<std::pair<int, int>>& sizes, const std::string& outDir) {
  struct Configuration {
    const char* name;
    int layers;
    const char* normals;
    DepthHierarchy hierarchy;
  };
  const Configuration configurations[] = {{"default", 1, "stored", DepthHierarchy::Auto},
                                          {"layers 2", 2, "stored", DepthHierarchy::Auto},
                                          {"normals from depth", 1, "reconstructed", DepthHierarchy::Auto},
                                          {"layers 2, normals from depth", 2, "reconstructed", DepthHierarchy::Auto},
                                          {"hierarchy on", 1, "stored", DepthHierarchy::On},
                                          {"layers 2, hierarchy on", 2, "stored", DepthHierarchy::On}};
  std::vector<RenderSettings> settings;
  for (const Configuration& c : configurations) {
    RenderSettings s;
    s.ao().layers = c.layers;
    s.ao().depthHierarchy = c.hierarchy;
    s.set("gbuffer.normals", c.normals);
    settings.push_back(s);
  }
  const EffectEntry& aoEffect = effectEntry("ao");
  std::ofstream csv(outDir + "/ao_layers.csv");
  csv << "scene,width,height,configuration,gbuffer_ms,peel_ms,hierarchy_ms,estimator_ms,blur_ms,ao_effect_ms,"
         "ao_effect_over_default\n";
  std::printf("\n12. The AO's depth layers and normals from depth (GTAO, medium), all configurations taking turns "
              "frame by frame: ms of the G-buffer pass, the peel, the hierarchy, the estimator, the blur, the AO "
              "effect (peel to blur), and the AO effect over the default's\n");
  for (const BenchScene& scene : scenes) {
    for (const auto& [w, h] : sizes) {
      const std::vector<PassTimes> times = bench.measure("ao-layers", scene, w, h, settings);
      const double reference = effectMs(times[0], aoEffect);
      std::printf("%s %dx%d\n", scene.name.c_str(), w, h);
      for (size_t c = 0; c < times.size(); ++c) {
        const PassTimes& t = times[c];
        const double blur = at(t, "blur-h") + at(t, "blur-v"), effect = effectMs(t, aoEffect);
        std::printf("  %-30s gbuffer %7.2f  peel %7.2f  hierarchy %6.2f  estimator %7.2f  blur %6.2f  AO %7.2f  "
                    "x%.2f\n",
                    configurations[c].name, at(t, "gbuffer"), at(t, "peel"), at(t, "hierarchy"), at(t, "sao"), blur,
                    effect, effect / reference);
        csv << scene.name << "," << w << "," << h << ",\"" << configurations[c].name << "\"," << at(t, "gbuffer") << ","
            << at(t, "peel") << "," << at(t, "hierarchy") << "," << at(t, "sao") << "," << blur << "," << effect
            << "," << effect / reference << "\n";
      }
    }
  }
}

// Settings with each (parameter, value) of `set` applied over the defaults.
RenderSettings settingsFrom(const std::vector<std::pair<std::string, std::string>>& set) {
  RenderSettings settings;
  for (const auto& [name, value] : set) settings.set(name, value);
  return settings;
}

// Section 9: what ao.temporal saves, on the still room. The default AO (GTAO, medium: 2 slices x 2 sides x 3 steps, a
// 9-tap blur each way) in one frame; 4 taps a pixel (one side x 4 steps) accumulated by ao.temporal with the default
// blur, a 5-tap and a 3-tap one (blur-radius 2 and 1: the accumulated AO needs less); and the same 4 taps in one
// frame; all taking turns frame by frame, each with its own Renderer (its own history). The accuracy side is
// tests/test_temporal_ao.cpp's (docs/temporal-effects.md, "Temporal AO"). The temporal frames also run the velocity
// pass, which only they read here (TAA and motion blur read it too when they are on).
// Per-pass times of `frames` frames of the final view at w x h for each of `configurations`, after 8 warm-up frames
// (shaders built, histories filled), each configuration with a Renderer of its own (its own history), all taking
// turns frame by frame. `play`: the scene's time advances at 60 frames per second from 1 s (each frame's previous
// one 1/60 s earlier); otherwise it stays at 0.
// Configuration c draws scenes[c].
std::vector<FinishPassTimer> timeTakingTurns(const Options& options, HeadlessContext& context,
                                             const std::vector<const Scene*>& scenes, const Camera& camera,
                                             const std::vector<RenderSettings>& configurations, bool play) {
  const int w = camera.width, h = camera.height;
  const gl::RenderTarget output("bench output", w, h, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                context.caps().depth24, context.caps().packedDepthStencil);
  const OutputTarget target{output.framebuffer(), w, h, {}};
  std::vector<std::unique_ptr<Renderer>> renderers;
  for (size_t c = 0; c < configurations.size(); ++c) {
    renderers.push_back(std::make_unique<Renderer>(context.caps()));
    renderers.back()->setScene(*scenes[c]);
  }
  std::vector<FinishPassTimer> timers(configurations.size());
  const int warmUp = 8;
  FrameOptions frame;
  for (int f = -warmUp; f < options.frames; ++f) {
    if (play) {
      frame.time = 1.0 + (f + warmUp) / 60.0;
      frame.previousTime = frame.time - 1.0 / 60.0;
    }
    for (size_t c = 0; c < configurations.size(); ++c) {
      frame.timer = f < 0 ? nullptr : &timers[c];
      renderers[c]->render(camera, configurations[c], View::Final, target, frame);
    }
  }
  return timers;
}

std::vector<FinishPassTimer> timeTakingTurns(const Options& options, HeadlessContext& context, const Scene& scene,
                                             const Camera& camera, const std::vector<RenderSettings>& configurations,
                                             bool play) {
  return timeTakingTurns(options, context, std::vector<const Scene*>(configurations.size(), &scene), camera,
                         configurations, play);
}

void temporalAoSection(const Options& options, HeadlessContext& context, const BenchScene& scene) {
  const EffectEntry& aoEffect = effectEntry("ao");
  struct Configuration {
    const char* name;
    RenderSettings settings;
  };
  std::vector<Configuration> configurations(5);
  configurations[0].name = "default, one frame";
  configurations[1].name = "4 taps, temporal";
  configurations[1].settings.ao().samples = 4;
  configurations[1].settings.ao().temporal = true;
  configurations[2].name = "4 taps, temporal, blur 2";
  configurations[2].settings = configurations[1].settings;
  configurations[2].settings.ao().blurRadius = 2;
  configurations[3].name = "4 taps, temporal, blur 1";
  configurations[3].settings = configurations[1].settings;
  configurations[3].settings.ao().blurRadius = 1;
  configurations[4].name = "4 taps, one frame";
  configurations[4].settings.ao().samples = 4;
  std::printf("\n9. Temporal AO, the still built-in room, %s: AO effect ms (estimator + ao-temporal + blur), each "
              "pass, and the velocity pass; median of %d frames, all taking turns\n",
              context.caps().renderer.c_str(), options.frames);
  std::printf("%-10s %-25s %9s %8s %11s %7s %7s %9s %10s\n", "size", "configuration", "AO effect", "sao",
              "ao-temporal", "blur-h", "blur-v", "velocity", "/ default");
  std::ofstream csv(options.outDir + "/temporal_ao.csv");
  csv << "width,height,configuration,ao_effect_ms,sao_ms,ao_temporal_ms,blur_ms,velocity_ms\n";
  for (auto [w, h] : options.sizes({{640, 360}, {1280, 720}})) {
    Camera camera = scene.camera;
    camera.width = w;
    camera.height = h;
    std::vector<RenderSettings> settings;
    for (const auto& c : configurations) settings.push_back(c.settings);
    const std::vector<FinishPassTimer> timers = timeTakingTurns(options, context, scene.scene, camera, settings, false);
    double reference = 0.0;
    for (size_t c = 0; c < configurations.size(); ++c) {
      double effect = 0.0;
      for (const std::string& pass : aoEffect.info.passes) effect += timers[c].medianMs(pass);
      if (c == 0) reference = effect;
      const double blur = timers[c].medianMs("blur-h") + timers[c].medianMs("blur-v");
      std::printf("%4dx%-5d %-25s %9.2f %8.2f %11.2f %7.2f %7.2f %9.2f %10.2f\n", w, h, configurations[c].name, effect,
                  timers[c].medianMs("sao"), timers[c].medianMs("ao-temporal"), timers[c].medianMs("blur-h"),
                  timers[c].medianMs("blur-v"), timers[c].medianMs("velocity"), effect / reference);
      csv << w << "," << h << ",\"" << configurations[c].name << "\"," << effect << "," << timers[c].medianMs("sao")
          << "," << timers[c].medianMs("ao-temporal") << "," << blur << "," << timers[c].medianMs("velocity") << "\n";
    }
  }
}

// Section 0: where start-up goes natively, in a process that has made nothing yet (what the page's stats and
// tools/browser-bench/startup.mjs show in the browser): the first Renderer, the built-in scene (with what moves, as
// the viewers show it) uploaded, the first frame and steady frames of the default frame at 1280x720, each bounded by
// glFinish; and the parts base/TimeSpent.h counted in each. The start-up target for the page, the first frame
// at most 1.3 x a steady one, is printed beside their ratio.
void startupSection(const Options& options, HeadlessContext& context) {
  const auto [w, h] = options.size(1280, 720);
  const gl::RenderTarget output("bench output", w, h, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                context.caps().depth24, context.caps().packedDepthStencil);
  const OutputTarget target{output.framebuffer(), w, h, {}};
  std::ofstream csv(options.outDir + "/startup.csv");
  csv << "step,ms,part,part_ms\n";
  auto parts = [&](const char* step, double ms) {
    std::string text;
    csv << step << "," << ms << ",,\n";
    for (const auto& [name, total] : TimeSpent::take()) {
      csv << step << "," << ms << "," << name << "," << total.ms << "\n";
      if (total.ms >= 0.5) {
        char part[96];
        std::snprintf(part, sizeof part, "%s%s %.0f", text.empty() ? "" : ", ", name.c_str(), total.ms);
        if (total.count > 1)
          std::snprintf(part + std::strlen(part), sizeof part - std::strlen(part), " (%d)", total.count);
        text += part;
      }
    }
    std::printf("  %-22s %9.1f ms%s%s%s\n", step, ms, text.empty() ? "" : "   (", text.c_str(),
                text.empty() ? "" : ")");
  };
  std::printf("\n0. Start-up, %s, %dx%d, the built-in scene: ms of each step, of which what base/TimeSpent counts\n",
              context.caps().renderer.c_str(), w, h);
  TimeSpent::take();
  glFinish();
  double start = TimeSpent::nowMs();
  Renderer renderer(context.caps());
  glFinish();
  parts("renderer", TimeSpent::nowMs() - start);
  start = TimeSpent::nowMs();
  renderer.setScene(makeBuiltinScene());
  glFinish();
  parts("scene", TimeSpent::nowMs() - start);
  const Camera camera = builtinSceneCamera(w, h);
  start = TimeSpent::nowMs();
  renderer.render(camera, RenderSettings(), View::Final, target);
  glFinish();
  const double first = TimeSpent::nowMs() - start;
  parts("first frame", first);
  std::vector<double> steady;
  for (int frame = 0; frame < std::max(3, options.frames / 3); ++frame) {
    start = TimeSpent::nowMs();
    renderer.render(camera, RenderSettings(), View::Final, target);
    glFinish();
    steady.push_back(TimeSpent::nowMs() - start);
  }
  std::sort(steady.begin(), steady.end());
  const double median = steady[steady.size() / 2];
  parts("steady frame (median)", median);
  std::printf("  first frame / steady frame: %.2f   (the page's target: <= 1.3)\n", first / median);
}

// Section 11: the render scale. The default frame of the still room at full size, at scale 0.75 and 0.5 with the
// edge upscale (FXAA's pass doing it) and at 0.5 with the bilinear one, each a Renderer of its own, taking turns;
// frame ms as the sum of the passes' medians. Then one frame of each upscale read back against the full-size frame
// (metrics/UpscaleMetrics.h).
void resolutionSection(const Options& options, HeadlessContext& context, const BenchScene& scene) {
  struct Configuration {
    const char* name;
    float scale;
    UpscaleFilter filter;
  };
  const std::vector<Configuration> configurations = {{"full size", 1.0f, UpscaleFilter::Edge},
                                                     {"scale 0.75, edge", 0.75f, UpscaleFilter::Edge},
                                                     {"scale 0.5, edge", 0.5f, UpscaleFilter::Edge},
                                                     {"scale 0.5, bilinear", 0.5f, UpscaleFilter::Bilinear}};
  std::vector<RenderSettings> settings;
  for (const Configuration& c : configurations) {
    RenderSettings s;
    s.of<ResolutionSettings>().scale = c.scale;
    s.of<ResolutionSettings>().upscale = c.filter;
    settings.push_back(s);
  }
  std::printf("\n11. Render scale, the still built-in room, %s: frame ms (the sum of the passes' medians over %d "
              "frames, all taking turns), the pass writing the output, and the error against the full-size frame\n",
              context.caps().renderer.c_str(), options.frames);
  std::printf("%-10s %-20s %9s %8s %14s %8s %9s %9s\n", "size", "configuration", "frame ms", "/ full",
              "output pass ms", "MAE", "edge MAE", "/ bilinear");
  std::ofstream csv(options.outDir + "/resolution.csv");
  csv << "width,height,configuration,frame_ms,ratio_to_full,output_pass_ms,mae,edge_mae\n";
  std::vector<std::string> targets;
  for (auto [w, h] : options.sizes({{640, 360}, {1280, 720}})) {
    Camera camera = scene.camera;
    camera.width = w;
    camera.height = h;
    const std::vector<FinishPassTimer> timers = timeTakingTurns(options, context, scene.scene, camera, settings, false);
    // The images: one frame of each, read back.
    const gl::RenderTarget output("bench output", w, h, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                  context.caps().depth24, context.caps().packedDepthStencil);
    Renderer renderer(context.caps());
    renderer.setScene(scene.scene);
    std::vector<Image> images;
    for (const RenderSettings& s : settings) {
      renderer.render(camera, s, View::Final, OutputTarget{output.framebuffer(), w, h, {}});
      images.push_back(Image{w, h, output.readRgba()});
    }
    double full = 0.0, bilinearMae = 0.0;
    std::vector<double> ms;
    for (size_t c = 0; c < configurations.size(); ++c) {
      double sum = 0.0;
      for (const std::string& pass : framePassNames()) sum += timers[c].medianMs(pass);
      ms.push_back(sum);
      if (c == 0) full = sum;
    }
    bilinearMae = upscaleError(images[0], images[3]).mae;
    for (size_t c = 0; c < configurations.size(); ++c) {
      const UpscaleError error = upscaleError(images[0], images[c]);
      // The pass writing the output: FXAA's (upscaling where the scale is below 1).
      const double outputPass = timers[c].medianMs("fxaa") + timers[c].medianMs("upscale");
      std::printf("%4dx%-5d %-20s %9.1f %8.3f %14.2f %8.3f %9.2f %9.3f\n", w, h, configurations[c].name, ms[c],
                  ms[c] / full, outputPass, error.mae, error.edgeMae, c == 0 ? 0.0 : error.mae / bilinearMae);
      csv << w << "," << h << ",\"" << configurations[c].name << "\"," << ms[c] << "," << ms[c] / full << ","
          << outputPass << "," << error.mae << "," << error.edgeMae << "\n";
    }
    char line[200];
    std::snprintf(line, sizeof line,
                  "%dx%d: scale 0.5 + edge upscale %.3f x the full frame (target <= 0.35); its MAE %.3f x "
                  "bilinear's (target <= 0.8)",
                  w, h, ms[2] / full, upscaleError(images[0], images[2]).mae / bilinearMae);
    targets.push_back(line);
  }
  std::printf("Targets:\n");
  for (const std::string& line : targets) std::printf("  %s\n", line.c_str());
}

// Section 10: what the lighting's choices cost, and the tiers' error. One Renderer per configuration (its own
// RendererOptions: the environment's storage), all taking turns frame by frame after a warm-up; the frame's ms is the
// sum of its passes' medians.
void lightingSection(const Options& options, HeadlessContext& context) {
  struct Configuration {
    std::string name;
    std::string state;  // parameters as NAME=VALUE&...
    // Measured: the context's best storage (half floats where it filters them); the others force the RGB9E5 atlas.
    EnvironmentFiltering filtering = EnvironmentFiltering::Measured;
  };
  auto settingsOf = [](const std::string& state) {
    RenderSettings settings;
    for (size_t begin = 0; begin < state.size();) {
      const size_t end = std::min(state.find('&', begin), state.size());
      const std::string pair = state.substr(begin, end - begin);
      const size_t eq = pair.find('=');
      settings.set(pair.substr(0, eq), pair.substr(eq + 1));
      begin = end + 1;
    }
    return settings;
  };
  const std::vector<Configuration> configurations = {
      {"AO on", ""},
      {"AO off, depth gbuffer", "ao=off&lighting.depth=gbuffer"},
      {"AO off, depth prepass", "ao=off&lighting.depth=prepass"},
      {"AO off, depth overdraw", "ao=off&lighting.depth=overdraw"},
      {"low: AO on", "preset=low"},
      {"low: AO off, gbuffer", "preset=low&ao=off&lighting.depth=gbuffer"},
      {"low: AO off, prepass", "preset=low&ao=off&lighting.depth=prepass"},
      {"low: AO off, overdraw", "preset=low&ao=off&lighting.depth=overdraw"},
      {"tier low", "lighting.quality=low"},
      {"tier high", "lighting.quality=high"},
      {"levels by hand", "", EnvironmentFiltering::ByHand},
      {"levels filtered", "", EnvironmentFiltering::Hardware},
  };
  struct Subject {
    std::string name;
    Scene scene;
    float scale;
  };
  std::vector<Subject> subjects;
  subjects.push_back({"2CylinderEngine", loadGltfFile(kEnginePath), kEngineScale});
  subjects.push_back({"pbr-samples", loadGltfFile(std::string(OBSCURA_SOURCE_DIR) + "/assets/scenes/pbr-samples.glb"),
                      1.0f});
  std::ofstream csv(options.outDir + "/lighting.csv");
  csv << "scene,width,height,configuration,frame_ms,gbuffer_ms,lighting_ms,display_mae_vs_high,display_p99_vs_high\n";
  std::printf("\n10. The lighting, %s; median ms of %d frames, all configurations taking turns; frame = the sum of its "
              "passes\n", context.caps().renderer.c_str(), options.frames);
  std::printf("%-16s %-10s %-24s %9s %9s %9s\n", "scene", "size", "configuration", "frame", "G-buffer", "lighting");
  const Options::Sizes sizes = options.sizes({{640, 360}, {1280, 720}});
  for (Subject& subject : subjects) {
    scaleScene(subject.scene, subject.scale);
    for (auto [w, h] : sizes) {
      const Camera camera = Camera::fit(subject.scene.worldBounds(), w, h);
      const gl::RenderTarget output("bench output", w, h, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                    context.caps().depth24, context.caps().packedDepthStencil);
      const OutputTarget target{output.framebuffer(), w, h, {}};
      std::vector<std::unique_ptr<Renderer>> renderers;
      std::vector<RenderSettings> settings;
      for (const Configuration& c : configurations) {
        RendererOptions rendererOptions;
        rendererOptions.environmentFiltering = c.filtering;
        if (c.filtering != EnvironmentFiltering::Measured) rendererOptions.environmentLayout = EnvironmentLayout::Atlas;
        renderers.push_back(std::make_unique<Renderer>(context.caps(), rendererOptions));
        renderers.back()->setScene(subject.scene);
        settings.push_back(settingsOf(c.state));
      }
      std::vector<FinishPassTimer> timers(configurations.size());
      FrameOptions frame;
      for (int f = -3; f < options.frames; ++f)
        for (size_t c = 0; c < configurations.size(); ++c) {
          frame.timer = f < 0 ? nullptr : &timers[c];
          renderers[c]->render(camera, settings[c], View::Final, target, frame);
        }
      // The tiers' images against the high tier's: the display colour (FXAA off, so the lighting writes it) over the
      // pixels the scene covers, in 8-bit steps.
      std::map<std::string, std::vector<std::uint8_t>> images;
      std::vector<std::uint8_t> gbuffer;
      for (const char* tier : {"low", "medium", "high"}) {
        RenderSettings still = settingsOf(std::string("fxaa=off&lighting.quality=") + tier);
        FrameOptions keep;
        keep.retain = {"display-color", "gbuffer"};
        renderers[0]->render(camera, still, View::Final, target, keep);
        images[tier] = renderers[0]->retained("display-color").readRgba();
        gbuffer = renderers[0]->retained("gbuffer").readRgba();
      }
      auto errorAgainstHigh = [&](const std::string& tier) {
        std::vector<int> errors;
        for (size_t i = 0; i < gbuffer.size(); i += 4) {
          if (gbuffer[i + 2] == 255 && gbuffer[i + 3] == 255) continue;  // background
          int worst = 0;
          for (size_t k = 0; k < 3; ++k) worst = std::max(worst, std::abs(images[tier][i + k] - images["high"][i + k]));
          errors.push_back(worst);
        }
        double mean = 0.0;
        for (int e : errors) mean += e;
        std::sort(errors.begin(), errors.end());
        return std::make_pair(errors.empty() ? 0.0 : mean / static_cast<double>(errors.size()),
                              errors.empty() ? 0 : errors[errors.size() * 99 / 100]);
      };
      for (size_t c = 0; c < configurations.size(); ++c) {
        double frameMs = 0.0;
        for (const std::string& pass : benchPasses()) frameMs += timers[c].medianMs(pass);
        const std::string size = std::to_string(w) + "x" + std::to_string(h);
        std::string error;
        double mae = 0.0;
        int p99 = 0;
        const std::string tier = c == 0 ? "medium" : c == 8 ? "low" : c == 9 ? "high" : "";
        if (!tier.empty()) {
          std::tie(mae, p99) = errorAgainstHigh(tier);
          char text[80];
          std::snprintf(text, sizeof text, "  %s tier against high: mean %.2f, p99 %d (8-bit steps)", tier.c_str(),
                        mae, p99);
          error = text;
        }
        std::printf("%-16s %-10s %-24s %9.2f %9.2f %9.2f%s\n", subject.name.c_str(), size.c_str(),
                    configurations[c].name.c_str(), frameMs, timers[c].medianMs("gbuffer"),
                    timers[c].medianMs("lighting"), error.c_str());
        csv << subject.name << "," << w << "," << h << ",\"" << configurations[c].name << "\"," << frameMs << ","
            << timers[c].medianMs("gbuffer") << "," << timers[c].medianMs("lighting") << "," << mae << "," << p99
            << "\n";
      }
    }
  }
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

// Section 7: the cost of skinning in each geometry pass and of the velocity pass. A crowd of skinned tubes (each
// 64 x 16 quads on a chain of 40 joints, more than GLES 2's minimum palette of 16) on a floor, playing its bend; each
// configuration is a Renderer of its own, all taking turns frame by frame at the same times:
//   - still: the same pose baked into still meshes (posedScene), no skinning: the floor of the comparison;
//   - texture, uniforms, uniforms at GLES 2's minimum limits (16-joint pieces), cpu: the skinning paths;
//   - velocity drawing every instance instead of only those that moved (RendererOptions::velocityDrawsEverything);
//   - the still scene's velocity: the full-screen camera motion alone.
void motionSection(const Options& options, HeadlessContext& context, int w, int h) {
  Scene crowd;
  crowd.meshes.push_back(makeBox({-8.0f, -0.1f, -8.0f}, {8.0f, 0.0f, 8.0f}));
  crowd.instances.push_back(Instance{0, glm::mat4(1.0f), -1, -1});
  SkinnedTubeShape shape;
  shape.joints = 40;
  const int side = options.quick ? 3 : 5;
  for (int i = 0; i < side; ++i)
    for (int k = 0; k < side; ++k)
      addSkinnedTube(crowd, shape, glm::vec3(2.0f * static_cast<float>(i - side / 2), 0.0f,
                                             2.0f * static_cast<float>(k - side / 2)));
  Camera camera = Camera::fit(crowd.worldBounds(), w, h);
  struct Configuration {
    std::string name;
    RendererOptions renderer;
    bool baked = false;
  };
  std::vector<Configuration> configurations(7);
  configurations[0].name = "still (baked pose)";
  configurations[0].baked = true;
  configurations[1].name = "texture";
  configurations[1].renderer.skinning = SkinningPath::Texture;
  configurations[2].name = "uniforms";
  configurations[2].renderer.skinning = SkinningPath::Uniforms;
  configurations[3].name = "uniforms, GLES 2 minimum";
  configurations[3].renderer.skinning = SkinningPath::Uniforms;
  configurations[3].renderer.simulateVertexLimits = VertexLimits::gles2Minimum();
  configurations[4].name = "cpu";
  configurations[4].renderer.skinning = SkinningPath::Cpu;
  configurations[5].name = "texture, velocity draws all";
  configurations[5].renderer.skinning = SkinningPath::Texture;
  configurations[5].renderer.velocityDrawsEverything = true;
  configurations[6].name = "still, velocity draws all";
  configurations[6].baked = true;
  configurations[6].renderer.velocityDrawsEverything = true;

  const Scene baked = posedScene(crowd, evaluatePose(crowd, 0.5));
  std::vector<std::unique_ptr<Renderer>> renderers;
  for (const Configuration& c : configurations) {
    renderers.push_back(std::make_unique<Renderer>(context.caps(), c.renderer));
    renderers.back()->setScene(c.baked ? baked : crowd);
  }
  const gl::RenderTarget output("bench output", w, h, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                context.caps().depth24, context.caps().packedDepthStencil);
  const OutputTarget target{output.framebuffer(), w, h, {}};
  camera.width = w;
  camera.height = h;
  std::vector<FinishPassTimer> timers(configurations.size());
  FrameOptions frame;
  frame.retain = {"velocity"};  // the velocity pass runs (motion blur and TAA will read it)
  // The AO off: its cost does not depend on what moves, and at a quarter of a second per frame on llvmpipe its noise
  // would drown the geometry passes'.
  RenderSettings settings;
  settings.ao().enabled = false;
  for (int f = -1; f < options.frames; ++f) {  // frame -1: the warm-up
    frame.time = 0.25 + 0.5 * static_cast<double>(std::max(f, 0)) / options.frames;
    for (size_t c = 0; c < configurations.size(); ++c) {
      frame.timer = f < 0 ? nullptr : &timers[c];
      renderers[c]->render(camera, settings, View::Final, target, frame);
    }
  }
  std::printf("\n7. Motion, %dx%d: %d skinned tubes (%zu triangles, 40 joints each) on a floor, %s; ms per pass "
              "(median of %d frames, all configurations taking turns)\n",
              w, h, side * side, crowd.triangleCount(), context.caps().renderer.c_str(), options.frames);
  const std::vector<std::string> passes = {"pose", "gbuffer", "lighting", "velocity"};
  std::printf("%-30s %9s %9s %9s %9s %9s   %s\n", "configuration", "pose", "gbuffer", "lighting", "velocity", "frame",
              "draws (cpu-deformed) in the last pass");
  std::ofstream csv(options.outDir + "/motion.csv");
  csv << "configuration,width,height,pass,median_ms\n";
  for (size_t c = 0; c < configurations.size(); ++c) {
    double frameMs = 0.0;
    for (const std::string& pass : framePassNames()) frameMs += timers[c].medianMs(pass);
    const GpuScene::Counts counts = renderers[c]->gpuScene().lastDrawCounts();
    std::printf("%-30s %9.2f %9.2f %9.2f %9.2f %9.2f   %d (%d)\n", configurations[c].name.c_str(),
                timers[c].medianMs("pose"), timers[c].medianMs("gbuffer"), timers[c].medianMs("lighting"),
                timers[c].medianMs("velocity"), frameMs,
                counts.draws, counts.cpuDeformed);
    for (const std::string& pass : passes)
      csv << '"' << configurations[c].name << "\"," << w << "," << h << "," << pass << ","
          << timers[c].medianMs(pass) << "\n";
    csv << '"' << configurations[c].name << "\"," << w << "," << h << ",frame," << frameMs << "\n";
  }
}

// effects.csv's columns, which transparency.csv shares (section 8 writes both sets of rows into effects.csv).
constexpr const char* kEffectCostsHeader = "configuration,width,height,effect,median_ms\n";

// Section 8d (issue 31): the transparent layer and the material layers, on the glass sample
// (assets/scenes/glass-samples.glb: glass spheres with transmission, two blended panes, clear-coated spheres, an
// unlit box) as made, and on variants whose materials put each over most of the frame, so that its cost per pixel
// shows: every opaque material blended (alpha 0.5), or transmissive (roughness 0.3); and every opaque material
// clear-coated against none with the material layers (the lighting's difference is the clear coat's). The browser
// benchmark (tools/browser-bench/effect-costs.mjs) edits the file the same way. The five scenes take turns.
void transparencySection(const Options& options, HeadlessContext& context,
                         const std::vector<std::pair<int, int>>& sizes, std::ofstream& csv) {
  const std::string path = std::string(OBSCURA_SOURCE_DIR) + "/assets/scenes/glass-samples.glb";
  const Scene glass = loadGltfFile(path);
  const glm::vec3 eye(0.0f, 1.5f, 3.6f), target(0.0f, 0.5f, 0.0f);
  auto variant = [&](const std::function<void(Material&)>& edit) {
    Scene scene = glass;
    for (Material& m : scene.materials)
      if (!m.transparent() && !m.unlit) edit(m);
    return scene;
  };
  const Scene blendedFrame = variant([](Material& m) {
    m.alphaMode = AlphaMode::Blend;
    m.baseColorFactor.a = 0.5f;
  });
  const Scene transmissiveFrame = variant([](Material& m) {
    m.transmissionFactor = 1.0f;
    m.roughnessFactor = 0.3f;
  });
  const Scene uncoated = variant([](Material& m) {
    m.clearcoatFactor = 0.0f;
    m.ior = 1.5f;
    m.specularFactor = 1.0f;
    m.specularColorFactor = glm::vec3(1.0f);
  });
  const Scene coated = variant([](Material& m) {
    m.clearcoatFactor = 1.0f;
    m.clearcoatRoughnessFactor = 0.1f;
    m.ior = 1.5f;
    m.specularFactor = 1.0f;
    m.specularColorFactor = glm::vec3(1.0f);
  });
  std::printf("\n8d. The transparent layer and the material layers, glass sample (%s) and its variants over most of "
              "the frame; median ms of %d frames, the five scenes taking turns\n",
              path.c_str(), options.frames);
  for (auto [w, h] : sizes) {
    Camera camera = builtinSceneCamera(w, h);
    camera.eye = {0.0f, 1.5f, 3.6f};
    camera.target = {0.0f, 0.5f, 0.0f};
    const std::vector<FinishPassTimer> t =
        timeTakingTurns(options, context, {&glass, &blendedFrame, &transmissiveFrame, &uncoated, &coated}, camera,
                        std::vector<RenderSettings>(5), false);
    const double clearcoat = t[4].medianMs("lighting") - t[3].medianMs("lighting");
    std::printf("  %dx%d, the sample: transparency %.2f ms, transmission-levels %.2f ms, lighting %.2f ms, G-buffer "
                "%.2f ms\n",
                w, h, t[0].medianMs("transparency"), t[0].medianMs("transmission-levels"), t[0].medianMs("lighting"),
                t[0].medianMs("gbuffer"));
    std::printf("  %dx%d, every opaque material blended: transparency %.2f ms; transmissive: transparency %.2f ms + "
                "transmission-levels %.2f ms; clear-coated: lighting %.2f ms against %.2f ms without: clear coat "
                "%.2f ms\n",
                w, h, t[1].medianMs("transparency"), t[2].medianMs("transparency"),
                t[2].medianMs("transmission-levels"), t[4].medianMs("lighting"), t[3].medianMs("lighting"),
                clearcoat);
    const auto row = [&](const char* configuration, const char* what, double ms) {
      csv << '"' << configuration << "\"," << w << "," << h << "," << what << "," << ms << "\n";
    };
    row("glass sample", "transparency", t[0].medianMs("transparency"));
    row("glass sample", "transmission-levels", t[0].medianMs("transmission-levels"));
    row("glass sample", "lighting", t[0].medianMs("lighting"));
    row("every material blended", "transparency", t[1].medianMs("transparency"));
    row("every material transmissive", "transparency", t[2].medianMs("transparency"));
    row("every material transmissive", "transmission-levels", t[2].medianMs("transmission-levels"));
    row("clear coat everywhere", "lighting", t[4].medianMs("lighting"));
    row("no material layers", "lighting", t[3].medianMs("lighting"));
    row("clear coat everywhere", "clearcoat", clearcoat);
  }
}

// Section 8: what each effect costs, the temporal ones included, on the moving built-in scene played at 60 frames per
// second (each frame's previous one 1/60 s earlier, so that motion blur and TAA have motion to work on and their
// history carries). One Renderer per configuration (each keeps its own history), all taking turns frame by frame.
void effectsSection(const Options& options, HeadlessContext& context, const std::vector<std::pair<int, int>>& sizes) {
  const Scene scene = makeBuiltinScene();
  struct Configuration {
    std::string name;
    RenderSettings settings;
  };
  std::vector<Configuration> configurations = {{"defaults", RenderSettings()},
                                               {"every effect on", RenderSettings::everyEffectOn()}};
  // The AO's temporal accumulation (where the table has it) at 4 taps a frame, beside 4 taps in a single frame.
  if (RenderSettings::find("ao.temporal")) {
    RenderSettings four;
    four.set("ao.samples", "4");
    configurations.push_back({"ao 4 taps", four});
    four.set("ao.temporal", "on");
    configurations.push_back({"ao temporal, 4 taps", four});
  }
  // Edges over the defaults, where the table has them: the lines, and the toon style (issue 16). Before "bloom, fog",
  // which the target lines below read as the last configuration.
  if (RenderSettings::find("edges.style")) {
    RenderSettings edges;
    edges.set("edges", "on");
    configurations.push_back({"edges", edges});
    edges.set("edges.style", "toon");
    configurations.push_back({"edges, toon", edges});
  }
  // Bloom and fog over the defaults, where the table has them: their cost beside the G-buffer pass's, in one frame.
  const bool bloomAndFog = RenderSettings::find("bloom") && RenderSettings::find("fog");
  const size_t bloomConfiguration = configurations.size();
  if (bloomAndFog) {
    RenderSettings both;
    both.set("bloom", "on");
    both.set("fog", "on");
    configurations.push_back({"bloom, fog", both});
  }
  // Depth of field over the defaults (the AO on at its default preset), where the table has it: its cost beside the
  // SAO pass's, in one frame.
  const bool dof = RenderSettings::find("dof") != nullptr;
  const size_t dofConfiguration = configurations.size();
  if (dof) {
    RenderSettings lens;
    lens.set("dof", "on");
    configurations.push_back({"dof", lens});
  }
  std::vector<std::string> dofLines;
  std::ofstream csv(options.outDir + "/effects.csv");
  csv << kEffectCostsHeader;
  std::vector<std::string> targetLines;
  std::printf("\n8. Every effect, the moving built-in scene playing at 60 fps, %s; ms per effect (the sum of its "
              "passes; median of %d frames, all configurations taking turns)\n",
              context.caps().renderer.c_str(), options.frames);
  std::printf("%-22s %-10s", "configuration", "size");
  for (const EffectEntry& effect : effectTable()) std::printf(" %11s", effect.info.name.c_str());
  std::printf(" %9s\n", "frame");
  for (auto [w, h] : sizes) {
    std::vector<RenderSettings> settings;
    for (const Configuration& c : configurations) settings.push_back(c.settings);
    const std::vector<FinishPassTimer> timers =
        timeTakingTurns(options, context, scene, builtinSceneCamera(w, h), settings, true);
    for (size_t c = 0; c < configurations.size(); ++c) {
      std::printf("%-22s %-10s", configurations[c].name.c_str(), (std::to_string(w) + "x" + std::to_string(h)).c_str());
      double frameMs = 0.0;
      for (const EffectEntry& effect : effectTable()) {
        double ms = 0.0;
        for (const std::string& pass : effect.info.passes) ms += timers[c].medianMs(pass);
        frameMs += ms;
        std::printf(" %11.2f", ms);
        csv << '"' << configurations[c].name << "\"," << w << "," << h << "," << effect.info.name << "," << ms << "\n";
      }
      frameMs += timers[c].medianMs("pose");
      std::printf(" %9.2f\n", frameMs);
      csv << '"' << configurations[c].name << "\"," << w << "," << h << ",frame," << frameMs << "\n";
    }
    if (bloomAndFog) {
      // Issue 15's target: bloom at 1280x720 under the cost of the G-buffer pass, the two timed in the same frames.
      const FinishPassTimer& t = timers[bloomConfiguration];
      double bloomMs = 0.0;  // its chain's passes
      for (const std::string& pass : effectEntry("bloom").info.passes) bloomMs += t.medianMs(pass);
      char line[200];
      std::snprintf(line, sizeof line, "%dx%d: bloom %.2f ms, fog %.2f ms, G-buffer %.2f ms; bloom / G-buffer %.2f", w,
                    h, bloomMs, t.medianMs("fog"), t.medianMs("gbuffer"),
                    bloomMs / std::max(t.medianMs("gbuffer"), 1e-9));
      targetLines.push_back(line);
    }
    if (dof) {
      // Issue 16's target: depth of field at 1280x720 costs no more than the SAO pass at its default preset.
      const FinishPassTimer& t = timers[dofConfiguration];
      double dofMs = 0.0;
      for (const std::string& pass : effectEntry("dof").info.passes) dofMs += t.medianMs(pass);
      char line[200];
      std::snprintf(line, sizeof line, "%dx%d: depth of field %.2f ms (near %.2f, far %.2f), SAO pass %.2f ms; "
                    "dof / SAO %.2f", w, h, dofMs, t.medianMs("dof-near"), t.medianMs("dof-far"), t.medianMs("sao"),
                    dofMs / std::max(t.medianMs("sao"), 1e-9));
      dofLines.push_back(line);
    }
  }
  // The metallic-roughness lighting (issue 15): the lighting pass on the PBR sample (assets/scenes/pbr-samples.glb:
  // forward, PBR_TEXTURES, two punctual lights) beside the built-in scene's rough dielectrics (deferred where the
  // context has several render targets), default settings, taking turns with nothing else.
  const std::string samples = std::string(OBSCURA_SOURCE_DIR) + "/assets/scenes/pbr-samples.glb";
  std::printf("\n8b. The lighting pass, metallic-roughness sample (%s) against the built-in scene; median ms of %d "
              "frames\n",
              samples.c_str(), options.frames);
  const Scene pbrScene = loadGltfFile(samples);
  for (auto [w, h] : sizes) {
    Camera camera = builtinSceneCamera(w, h);
    camera.eye = {0.0f, 1.7f, 4.0f};
    camera.target = {0.0f, 0.55f, 0.0f};
    const std::vector<FinishPassTimer> pbrTimes =
        timeTakingTurns(options, context, pbrScene, camera, {RenderSettings()}, false);
    const std::vector<FinishPassTimer> builtinTimes =
        timeTakingTurns(options, context, scene, builtinSceneCamera(w, h), {RenderSettings()}, false);
    const FinishPassTimer &pbr = pbrTimes[0], &builtin = builtinTimes[0];
    std::printf("  %dx%d: lighting %.2f ms on the PBR sample (G-buffer %.2f ms), %.2f ms on the built-in scene "
                "(G-buffer %.2f ms)\n",
                w, h, pbr.medianMs("lighting"), pbr.medianMs("gbuffer"), builtin.medianMs("lighting"),
                builtin.medianMs("gbuffer"));
    csv << "\"pbr sample\"," << w << "," << h << ",lighting," << pbr.medianMs("lighting") << "\n";
    csv << "\"built-in, defaults (lighting alone)\"," << w << "," << h << ",lighting," << builtin.medianMs("lighting")
        << "\n";
  }
  transparencySection(options, context, sizes, csv);
  if (!targetLines.empty()) {
    std::printf("Bloom and fog against the G-buffer pass (configuration \"bloom, fog\"; target: bloom at 1280x720 "
                "under the G-buffer pass):\n");
    for (const std::string& line : targetLines) std::printf("  %s\n", line.c_str());
  }
  if (!dofLines.empty()) {
    std::printf("Depth of field against the SAO pass (configuration \"dof\", the AO at its default preset; target: "
                "depth of field at 1280x720 no dearer than the SAO pass):\n");
    for (const std::string& line : dofLines) std::printf("  %s\n", line.c_str());
  }
}

// Section 13: the renderer's host time per frame. Each frame is drawn after a glFinish, so no earlier frame's work
// is waited for inside it, and timed by the calling thread's CPU clock (time the thread waits for the rasteriser's
// threads is not counted) and by the wall clock. The moving built-in scene plays at 60 frames per second, as on the
// page; the defaults and every effect on; 1280x720 and 160x90 (where the rasteriser's share on this thread is least).
double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

double wallMs() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

void hostSection(const Options& options, HeadlessContext& context) {
  const Scene scene = makeBuiltinScene();
  struct Configuration {
    std::string name;
    RenderSettings settings;
    bool cachePlans = true;
  };
  const RenderSettings everything = RenderSettings::everyEffectOn();
  // Each also with its plan made every frame (RendererOptions::cachePlans off), in the same frames: what the cache
  // saves.
  const std::vector<Configuration> configurations = {{"defaults", RenderSettings()},
                                                     {"defaults, plan each frame", RenderSettings(), false},
                                                     {"every effect on", everything},
                                                     {"every effect, plan each", everything, false}};
  // --quick: the smallest alone (Options::sizes' 320x180 is not where this section's driver share is least).
  const Options::Sizes sizes = options.quick ? Options::Sizes{{160, 90}} : Options::Sizes{{1280, 720}, {160, 90}};
  const int frames = 4 * options.frames;
  std::ofstream csv(options.outDir + "/host.csv");
  csv << "configuration,width,height,host_cpu_ms,host_wall_ms\n";
  std::printf("\n13. Host time per frame, the moving built-in scene playing at 60 fps, %s: the renderer's CPU time in "
              "render() on the calling thread (and its wall time), median of %d frames, each drawn after glFinish\n",
              context.caps().renderer.c_str(), frames);
  std::printf("%-27s %-10s %12s %12s\n", "configuration", "size", "host cpu ms", "host wall ms");
  for (auto [w, h] : sizes) {
    const gl::RenderTarget output("bench output", w, h, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                  context.caps().depth24, context.caps().packedDepthStencil);
    const OutputTarget target{output.framebuffer(), w, h, {}};
    const Camera camera = builtinSceneCamera(w, h);
    std::vector<std::unique_ptr<Renderer>> renderers;
    for (size_t c = 0; c < configurations.size(); ++c) {
      RendererOptions rendererOptions;
      rendererOptions.cachePlans = configurations[c].cachePlans;
      renderers.push_back(std::make_unique<Renderer>(context.caps(), rendererOptions));
      renderers.back()->setScene(scene);
    }
    std::vector<std::vector<double>> cpu(configurations.size()), wall(configurations.size());
    const int warmUp = 8;
    FrameOptions frame;
    for (int f = -warmUp; f < frames; ++f) {
      frame.time = 1.0 + (f + warmUp) / 60.0;
      frame.previousTime = frame.time - 1.0 / 60.0;
      for (size_t c = 0; c < configurations.size(); ++c) {
        glFinish();
        const double cpu0 = threadCpuMs(), wall0 = wallMs();
        renderers[c]->render(camera, configurations[c].settings, View::Final, target, frame);
        const double cpu1 = threadCpuMs(), wall1 = wallMs();
        if (f >= 0) {
          cpu[c].push_back(cpu1 - cpu0);
          wall[c].push_back(wall1 - wall0);
        }
      }
    }
    glFinish();
    for (size_t c = 0; c < configurations.size(); ++c) {
      const double cpuMs = median(cpu[c]), wallMsMedian = median(wall[c]);
      std::printf("%-27s %-10s %12.3f %12.3f\n", configurations[c].name.c_str(),
                  (std::to_string(w) + "x" + std::to_string(h)).c_str(), cpuMs, wallMsMedian);
      csv << '"' << configurations[c].name << "\"," << w << "," << h << "," << cpuMs << "," << wallMsMedian << "\n";
    }
  }
}

// A renderer option turned on against off (sections 14 and 15): each configuration's frame with the option and
// without it taking turns frame by frame, per scene and size; `quickScene` alone with --quick.
struct OptionComparison {
  const char* title;  // "14. The scene's bounds"
  const char* what;   // what the option does, for the heading
  const char* csv;    // the file in DIR
  const char* onColumn;
  const char* offColumn;
  std::function<void(RendererOptions&, bool)> set;
};

void optionSection(const Options& options, HeadlessContext& context, const std::vector<BenchScene>& scenes,
                   const OptionComparison& compared, const BenchScene* quickScene) {
  struct Configuration {
    std::string name;
    std::vector<std::pair<std::string, std::string>> set;
  };
  const std::vector<Configuration> configurations = {
      {"defaults", {}}, {"preset low", {{"preset", "low"}}}, {"AO off", {{"ao", "off"}}}};
  const Options::Sizes sizes = options.sizes({{640, 360}, {1280, 720}});
  std::ofstream csv(options.outDir + "/" + compared.csv);
  csv << "scene,configuration,width,height," << compared.onColumn << "_ms," << compared.offColumn << "_ms,ratio,"
      << compared.onColumn << "_triangles," << compared.offColumn << "_triangles\n";
  std::printf("\n%s, %s: frame ms (glFinish-bounded, median of %d frames) %s, taking turns\n", compared.title,
              context.caps().renderer.c_str(), options.frames, compared.what);
  std::printf("%-16s %-12s %-10s %12s %12s %8s  %s\n", "scene", "frame", "size",
              (std::string(compared.onColumn) + " ms").c_str(), (std::string(compared.offColumn) + " ms").c_str(),
              "ratio", "triangles (the last geometry pass's)");
  for (const BenchScene& scene : scenes) {
    if (options.quick && &scene != quickScene) continue;
    for (auto [w, h] : sizes) {
      const gl::RenderTarget output("bench output", w, h, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                    context.caps().depth24, context.caps().packedDepthStencil);
      const OutputTarget target{output.framebuffer(), w, h, {}};
      Camera camera = scene.camera;
      camera.width = w;
      camera.height = h;
      for (const Configuration& c : configurations) {
        const RenderSettings settings = settingsFrom(c.set);
        std::vector<std::unique_ptr<Renderer>> renderers;
        for (const bool on : {true, false}) {
          RendererOptions rendererOptions;
          compared.set(rendererOptions, on);
          renderers.push_back(std::make_unique<Renderer>(context.caps(), rendererOptions));
          renderers.back()->setScene(scene.scene);
        }
        std::vector<std::vector<double>> ms(2);
        for (int f = -2; f < options.frames; ++f)
          for (size_t r = 0; r < 2; ++r) {
            glFinish();
            const double start = wallMs();
            renderers[r]->render(camera, settings, View::Final, target);
            glFinish();
            if (f >= 0) ms[r].push_back(wallMs() - start);
          }
        const double on = median(ms[0]), off = median(ms[1]);
        const long onTriangles = renderers[0]->gpuScene().lastDrawCounts().triangles;
        const long offTriangles = renderers[1]->gpuScene().lastDrawCounts().triangles;
        std::printf("%-16s %-12s %-10s %12.2f %12.2f %8.3f  %ld / %ld\n", scene.name.c_str(), c.name.c_str(),
                    (std::to_string(w) + "x" + std::to_string(h)).c_str(), on, off, on / off, onTriangles,
                    offTriangles);
        csv << scene.name << ",\"" << c.name << "\"," << w << "," << h << "," << on << "," << off << "," << on / off
            << "," << onTriangles << "," << offTriangles << "\n";
      }
    }
  }
}

// Section 14: what limiting the passes to the scene's bounds on screen saves (--quick: the engine alone; the room
// fills its frame).
void sceneBoundsSection(const Options& options, HeadlessContext& context, const std::vector<BenchScene>& scenes) {
  optionSection(options, context, scenes,
                {"14. The scene's bounds", "with the passes limited to the scene's bounds on screen and over the "
                 "whole frame", "scene_bounds.csv", "limited", "whole",
                 [](RendererOptions& o, bool on) { o.limitToScene = on; }},
                &scenes.back());
}

// Section 15: what frustum culling saves (GpuScene::cullToView), on views of three tuning scenes that leave much of
// their scene outside the frame (tools/tuning-views.json, at their files' units): the built-in room's columns, the
// engine's detail and the millimetre room's table. --quick: the engine's detail alone.
void cullingSection(const Options& options, HeadlessContext& context) {
  const std::string assets = std::string(OBSCURA_SOURCE_DIR) + "/assets/";
  std::vector<BenchScene> scenes;
  scenes.push_back({"builtin-columns", makeBuiltinScene(BuiltinSceneOptions::still()),
                    Camera::fromJsonFile(assets + "cameras/builtin-columns.json")});
  scenes.push_back(
      {"engine-detail", loadGltfFile(kEnginePath), Camera::fromJsonFile(assets + "cameras/engine-detail.json")});
  scenes.push_back({"room-table", loadGltfFile(assets + "scenes/room-mm.glb"),
                    Camera::fromJsonFile(assets + "cameras/room-mm-table.json")});
  optionSection(options, context, scenes,
                {"15. Frustum culling", "with the instances outside the view left out and with every instance drawn",
                 "culling.csv", "culled", "whole", [](RendererOptions& o, bool on) { o.cullToView = on; }},
                &scenes[1]);
}

// Section 8c: the camera's finish (issue 29), every configuration in the same frames.
void finishSection(const Options& options, HeadlessContext& context, const std::vector<std::pair<int, int>>& sizes) {
  const Scene scene = makeBuiltinScene(BuiltinSceneOptions::still());
  struct Configuration {
    std::string name;
    std::vector<std::pair<std::string, std::string>> set;
  };
  const std::vector<Configuration> configurations = {
      {"defaults", {}},
      {"auto exposure", {{"auto-exposure", "on"}}},
      {"auto exposure, percentile", {{"auto-exposure", "on"}, {"auto-exposure.metering", "percentile"}}},
      {"bloom", {{"bloom", "on"}}},
      {"bloom, lens flare", {{"bloom", "on"}, {"lens-flare", "on"}}},
      {"bloom, glare 4", {{"bloom", "on"}, {"glare", "on"}}},
      {"bloom, glare 6", {{"bloom", "on"}, {"glare", "on"}, {"glare.streaks", "6"}}},
      {"bloom, flare, glare 4", {{"bloom", "on"}, {"lens-flare", "on"}, {"glare", "on"}}},
      {"lens flare, bloom off", {{"lens-flare", "on"}}},
      {"edges", {{"edges", "on"}}},
      {"edges, hatching", {{"edges", "on"}, {"edges.style", "hatching"}}}};
  std::vector<RenderSettings> settings;
  for (const Configuration& c : configurations) settings.push_back(settingsFrom(c.set));
  const std::vector<std::string> columns = {"lighting", "bloom", "bloom-bright", "lens-flare", "glare", "exposure",
                                            "tonemap", "edges"};
  // exposure and bloom: their passes together; bloom-bright: bloom's first three passes where they ran alone (bloom
  // off, read by the lens flare or the glare).
  auto ms = [](const FinishPassTimer& t, const std::string& column) {
    double sum = 0.0;
    if (column == "bloom-bright")
      return t.medianMs("bloom") > 0.0 ? 0.0
                                       : t.medianMs("bloom-prefilter-blocks") + t.medianMs("bloom-prefilter") +
                                             t.medianMs("bloom-down-2");
    if (column != "exposure" && column != "bloom") return t.medianMs(column);
    for (const std::string& pass : effectEntry(column == "bloom" ? "bloom" : "auto-exposure").info.passes)
      sum += t.medianMs(pass);
    return sum;
  };
  std::ofstream csv(options.outDir + "/finish.csv");
  csv << "configuration,width,height,pass,median_ms\n";
  std::printf("\n8c. The camera's finish, the still built-in scene, %s; median ms of %d frames, all configurations "
              "taking turns (exposure, bloom: their passes together; edges: its last pass, where hatching draws)\n",
              context.caps().renderer.c_str(), options.frames);
  std::printf("%-27s %-9s", "configuration", "size");
  for (const std::string& c : columns) std::printf(" %12s", c.c_str());
  std::printf(" %9s\n", "frame");
  std::vector<std::string> summary;
  for (auto [w, h] : sizes) {
    const std::vector<FinishPassTimer> timers =
        timeTakingTurns(options, context, scene, builtinSceneCamera(w, h), settings, false);
    for (size_t c = 0; c < configurations.size(); ++c) {
      std::printf("%-27s %-9s", configurations[c].name.c_str(), (std::to_string(w) + "x" + std::to_string(h)).c_str());
      double frameMs = 0.0;
      for (const std::string& pass : framePassNames()) frameMs += timers[c].medianMs(pass);
      for (const std::string& column : columns) {
        std::printf(" %12.2f", ms(timers[c], column));
        csv << '"' << configurations[c].name << "\"," << w << "," << h << "," << column << "," << ms(timers[c], column)
            << "\n";
      }
      std::printf(" %9.2f\n", frameMs);
      csv << '"' << configurations[c].name << "\"," << w << "," << h << ",frame," << frameMs << "\n";
    }
    // What the tone mapping pays for the exposure texel and for the lens light's upsample: its ms against the tone
    // mapping of bloom alone (the lighting does not absorb it there either).
    const double tonemapBloom = timers[3].medianMs("tonemap");
    char line[400];
    std::snprintf(line, sizeof line,
                  "%dx%d: auto exposure %.2f ms (percentile %.2f), tone mapping %.2f ms with it against %.2f with "
                  "bloom alone; lens flare %.2f ms, glare %.2f (4 streaks) / %.2f (6), tone mapping with the lens "
                  "light %.2f ms; the bright pass alone (bloom off) %.2f ms; hatching: edges' last pass %.2f ms "
                  "against %.2f for the lines",
                  w, h, ms(timers[1], "exposure"), ms(timers[2], "exposure"), timers[1].medianMs("tonemap"),
                  tonemapBloom, timers[4].medianMs("lens-flare"), timers[5].medianMs("glare"),
                  timers[6].medianMs("glare"), timers[7].medianMs("tonemap"), ms(timers[8], "bloom-bright"),
                  timers[10].medianMs("edges"), timers[9].medianMs("edges"));
    summary.push_back(line);
  }
  for (const std::string& line : summary) std::printf("  %s\n", line.c_str());

}

// Section 8e: the display colour's per-pixel stages (issue 29: grading, vignette, grain, dithering). They add no pass:
// what each costs is what it adds to the pass it is fused into, the lighting's (the default frame) or, with TAA, the
// tone curve's stage pass; measured against the same frame without it (without dithering for the dithering itself),
// every configuration taking turns frame by frame.
void stagesSection(const Options& options, HeadlessContext& context, const std::vector<std::pair<int, int>>& sizes) {
  const Scene scene = makeBuiltinScene(BuiltinSceneOptions::still());
  // A 33-point LUT (a warm grade), written where the results go: what a .cube from a grading tool is.
  const std::string lut = options.outDir + "/warm.cube";
  std::ofstream(lut) << writeCubeLut(ColorLut::of(33, [](const glm::vec3& c) {
    return glm::vec3(std::min(1.0f, 1.05f * c.r + 0.02f), c.g, 0.85f * c.b);
  }));
  const std::vector<std::pair<std::string, std::string>> balance = {
      {"grading", "on"}, {"grading.temperature", "5000"}, {"grading.saturation", "1.2"}, {"grading.contrast", "1.1"}};
  struct Configuration {
    std::string name;
    std::vector<std::pair<std::string, std::string>> set;
  };
  auto with = [](std::vector<std::pair<std::string, std::string>> a,
                 const std::vector<std::pair<std::string, std::string>>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };
  const std::vector<std::pair<std::string, std::string>> lutOn = {{"grading", "on"}, {"grading.lut", lut}};
  const std::vector<std::pair<std::string, std::string>> every =
      with(with(balance, {{"grading.lut", lut}}), {{"vignette", "on"}, {"grain", "on"}});
  const std::vector<Configuration> configurations = {
      {"dither off", {{"dither", "off"}}},
      {"defaults (dither)", {}},
      {"grading: balance", balance},
      {"grading: LUT", lutOn},
      {"grading: balance + LUT", with(balance, {{"grading.lut", lut}})},
      {"vignette", {{"vignette", "on"}}},
      {"grain", {{"grain", "on"}}},
      {"all four", every},
      {"taa, dither off", {{"taa", "on"}, {"dither", "off"}}},
      {"taa, all four", with(every, {{"taa", "on"}})}};
  std::vector<RenderSettings> settings;
  for (const Configuration& c : configurations) settings.push_back(settingsFrom(c.set));
  std::ofstream csv(options.outDir + "/stages.csv");
  csv << "configuration,width,height,pass,median_ms\n";
  std::printf("\n8e. The display colour's stages, the still built-in scene, %s; median ms of %d frames, all "
              "configurations taking turns; each adds to the pass it is fused into (lighting; with TAA, tonemap)\n",
              context.caps().renderer.c_str(), options.frames);
  std::printf("%-24s %-9s %9s %9s %9s %9s\n", "configuration", "size", "lighting", "tonemap", "frame", "adds");
  for (auto [w, h] : sizes) {
    const std::vector<FinishPassTimer> timers =
        timeTakingTurns(options, context, scene, builtinSceneCamera(w, h), settings, false);
    for (size_t c = 0; c < configurations.size(); ++c) {
      double frameMs = 0.0;
      for (const std::string& pass : framePassNames()) frameMs += timers[c].medianMs(pass);
      // Against the frame without it: the defaults for a stage added to them, no dithering for the dithering and
      // for the four (which include it), the TAA frame without dithering for the TAA ones.
      const bool taa = c >= 8;
      const size_t base = taa ? 8 : (c == 1 || c == 7) ? 0 : 1;
      const std::string joined = taa ? "tonemap" : "lighting";
      const double adds = c == 0 || c == 8 ? 0.0 : timers[c].medianMs(joined) - timers[base].medianMs(joined);
      std::printf("%-24s %-9s %9.2f %9.2f %9.2f %+9.2f\n", configurations[c].name.c_str(),
                  (std::to_string(w) + "x" + std::to_string(h)).c_str(), timers[c].medianMs("lighting"),
                  timers[c].medianMs("tonemap"), frameMs, adds);
      for (const char* pass : {"lighting", "tonemap"})
        csv << '"' << configurations[c].name << "\"," << w << "," << h << "," << pass << ","
            << timers[c].medianMs(pass) << "\n";
      csv << '"' << configurations[c].name << "\"," << w << "," << h << ",frame," << frameMs << "\n";
      csv << '"' << configurations[c].name << "\"," << w << "," << h << ",adds-to-" << joined << "," << adds << "\n";
    }
  }
}

// Sections 1 to 5 (the full run's core; none runs alone): the defaults' passes and effects on both scenes, SAO's
// radius and sample sweeps and hierarchy storages, the quality presets, and the ratios of this run.
void coreSections(const Options& options, Bench& bench, const std::vector<BenchScene>& scenes) {
  const BenchScene& builtin = scenes[0];
  const AoSettings defaults;
  // Sections 2, 3 and 5 study SAO's own machinery (the hierarchy against the radius, the spiral's taps, the fetch
  // floor that copies SAO's spiral): they run SAO whatever the default estimator is. Sections 1 and 4 run the
  // defaults (the "sao" pass is the estimator pass, whichever estimator); section 6 compares the estimators.
  AoSettings saoDefaults = defaults;
  saoDefaults.estimator = AoEstimator::Sao;

  // Each scene at its default radius, as obscura-render and the viewers choose it (scene/SceneScale.h).
  std::string sceneRadii;
  for (const BenchScene& scene : scenes)
    sceneRadii += (sceneRadii.empty() ? "" : ", ") + scene.name + " " + formatShortest(defaultAoRadius(scene.scene));
  std::printf("\n1. Per-pass ms, default settings (every effect on; AO %d samples, r = each scene's default: %s; "
              "hierarchy %s)\n",
              defaults.samples, sceneRadii.c_str(), defaults.usesDepthHierarchy() ? "on" : "off");
  printPassHeader();
  const Options::Sizes sizes = options.sizes({{640, 360}, {1280, 720}, {1920, 1080}});
  std::vector<std::tuple<std::string, int, int, PassTimes>> perPass;
  for (const BenchScene& scene : scenes)
    for (auto [w, h] : sizes) {
      AoSettings settings = defaults;
      settings.radius = defaultAoRadius(scene.scene);
      perPass.emplace_back(scene.name, w, h, bench.measure("passes", scene, w, h, settings));
      printPassRow(scene.name, w, h, std::get<3>(perPass.back()));
    }
  std::printf("\n1b. Per-effect ms (the sum of each effect's passes), the same frames\n");
  printEffectHeader();
  for (const auto& [name, w, h, times] : perPass) printEffectRow(name, w, h, times);
  for (const auto& [absorbed, doer] : bench.doneBy())
    std::printf("(%s: 0 ms where the %s pass did its work, with nothing else reading what it reads)\n",
                absorbed.c_str(), doer.c_str());

  const auto [w, h] = options.size(1280, 720);
  std::printf("\n2. Radius sweep, built-in scene %dx%d: SAO pass ms (hierarchy pass ms)\n", w, h);
  std::printf("%10s %18s %18s\n", "radius m", "hierarchy on", "hierarchy off");
  std::ofstream sweep(options.outDir + "/radius_sweep.csv");
  sweep << "radius_m,sao_ms_hierarchy,sao_ms_no_hierarchy\n";
  // Every radius and both hierarchy settings take turns frame by frame (see Bench::measure).
  const std::vector<float> radii = {0.25f, 0.5f, 1.0f, 2.0f, 3.0f, 4.0f};
  std::vector<RenderSettings> sweepSettings;
  for (float radius : radii) {
    for (bool hierarchy : {true, false}) {
      AoSettings settings = saoDefaults;
      settings.radius = radius;
      settings.depthHierarchy = hierarchy ? DepthHierarchy::On : DepthHierarchy::Off;
      sweepSettings.push_back(settings);
    }
  }
  const std::vector<PassTimes> sweepTimes = bench.measure("radius", builtin, w, h, sweepSettings);
  double saoAt[2][2] = {};  // [hierarchy][r=0.5, r=4]
  for (size_t r = 0; r < radii.size(); ++r) {
    const PassTimes& on = sweepTimes[2 * r];
    const PassTimes& off = sweepTimes[2 * r + 1];
    const double saoOn = at(on, "sao"), saoOff = at(off, "sao");
    std::printf("%10.2f %11.2f (%4.2f) %18.2f\n", radii[r], saoOn, at(on, "hierarchy"), saoOff);
    sweep << radii[r] << "," << saoOn << "," << saoOff << "\n";
    if (radii[r] == 0.5f) saoAt[1][0] = saoOn, saoAt[0][0] = saoOff;
    if (radii[r] == 4.0f) saoAt[1][1] = saoOn, saoAt[0][1] = saoOff;
  }
  sweep.close();
  writePlot(options.outDir);

  std::printf("\n2b. Hierarchy storage, built-in scene %dx%d: SAO pass ms\n", w, h);
  std::printf("%10s %18s %18s\n", "radius m", "separate textures", "atlas");
  std::pair<double, double> storageAt[2];  // (separate, atlas) at r = 0.5 m and r = 4 m
  for (int i = 0; i < 2; ++i) {
    AoSettings settings = saoDefaults;
    settings.radius = i == 0 ? 0.5f : 4.0f;
    storageAt[i] = bench.measureStorages(builtin, w, h, settings);
    std::printf("%10.2f %18.2f %18.2f\n", settings.radius, storageAt[i].first, storageAt[i].second);
  }

  std::printf("\n3. Sample-count sweep, built-in scene %dx%d: SAO pass ms\n", w, h);
  const std::vector<int> sampleCounts = {4, 8, 11, 16, 24, 32};
  std::vector<RenderSettings> sampleSettings;
  for (int samples : sampleCounts) {
    AoSettings settings = saoDefaults;
    settings.samples = samples;
    settings.spiralTurns = SaoKernel::bestSpiralTurns(samples);
    sampleSettings.push_back(settings);
  }
  const std::vector<PassTimes> sampleTimes = bench.measure("samples", builtin, w, h, sampleSettings);
  for (size_t i = 0; i < sampleCounts.size(); ++i)
    std::printf("%10d samples %9.2f ms\n", sampleCounts[i], at(sampleTimes[i], "sao"));

  std::printf("\n4. Quality presets, built-in scene %dx%d\n", w, h);
  printPassHeader();
  std::vector<RenderSettings> presetSettings;
  for (QualityPreset preset : allQualityPresets()) {
    RenderSettings settings;
    settings.applyPreset(preset);  // every effect's preset
    presetSettings.push_back(settings);
  }
  const std::vector<PassTimes> presetTimes = bench.measure("presets", builtin, w, h, presetSettings);
  for (size_t i = 0; i < presetTimes.size(); ++i)
    printPassRow(presetName(allQualityPresets()[i]), w, h, presetTimes[i]);

  std::printf("\n5. Ratios (this run, built-in scene %dx%d)\n", w, h);
  const PassTimes base = bench.measure("ratios", builtin, w, h, saoDefaults);
  const Camera& camera = builtin.camera;
  const float distance = glm::length(camera.target - camera.eye);
  const float disk = std::min(static_cast<float>(h) / (2.0f * std::tan(camera.fovyRadians() * 0.5f)) *
                                  saoDefaults.radius / distance,
                              saoDefaults.maxScreenRadius * static_cast<float>(h));
  const auto [sao, floor] = bench.measureAgainstFloor(builtin, w, h, saoDefaults, disk);
  const double saoMs = at(base, "sao"), gbufferMs = at(base, "gbuffer");
  // Printed and written to DIR/ratios.csv, each with the two figures it divides.
  std::ofstream ratios(options.outDir + "/ratios.csv");
  ratios << "ratio,value,numerator_ms,denominator_ms\n";
  auto ratio = [&](const char* label, const char* key, double numerator, double denominator, const char* note) {
    std::printf("  %-48s %6.2f   (%.2f / %.2f ms)%s\n", label, numerator / denominator, numerator, denominator, note);
    ratios << key << "," << numerator / denominator << "," << numerator << "," << denominator << "\n";
  };
  ratio("SAO / G-buffer", "sao_over_gbuffer", saoMs, gbufferMs, "");
  ratio("SAO(r=4 m) / SAO(r=0.5 m), hierarchy (default)", "sao_r4_over_r05_hierarchy", saoAt[1][1], saoAt[1][0],
        "   goal <= 1.15");
  ratio("SAO(r=4 m) / SAO(r=0.5 m), no hierarchy", "sao_r4_over_r05_no_hierarchy", saoAt[0][1], saoAt[0][0], "");
  ratio("SAO(r=4 m) / SAO(r=0.5 m), separate textures", "sao_r4_over_r05_separate_textures", storageAt[1].first,
        storageAt[0].first, "");
  ratio("SAO(r=4 m) / SAO(r=0.5 m), atlas", "sao_r4_over_r05_atlas", storageAt[1].second, storageAt[0].second, "");
  const std::string floorLabel =
      "SAO / fetch floor (" + std::to_string(saoDefaults.samples + 1) + " fetches, disk " +
      std::to_string(static_cast<int>(std::lround(disk))) + " px)";
  ratio(floorLabel.c_str(), "sao_over_fetch_floor", sao, floor, "");
}

// What the sections share, made when a section first asks for it: the scenes (the engine loaded once), and the
// Bench, whose constructor starts DIR/bench.csv afresh: a section run alone that does not write to it leaves the
// file as the last run wrote it.
class SectionInputs {
 public:
  SectionInputs(const Options& o, HeadlessContext& c) : options(o), context(c) {}
  const Options& options;
  HeadlessContext& context;

  const std::vector<BenchScene>& scenes() {
    if (scenes_.empty()) {
      // The still room: the scene docs/benchmarks.md's figures were measured on (the pendulum and the limb would add
      // about 5,800 triangles, and no motion: nothing here advances the time).
      scenes_.push_back({"builtin", makeBuiltinScene(BuiltinSceneOptions::still()), builtinSceneCamera()});
      // The engine is modelled in centimetres; scaled to metres (about 5 x 7 x 4 m) as the tuning views do
      // (tools/tuning-views.json). Its AO radius is its default either way (scene/SceneScale.h: 5 % of the bounding
      // sphere's diameter, 0.42 m here), so the scale changes no figure.
      Scene engine = loadGltfFile(kEnginePath);
      scaleScene(engine, kEngineScale);
      const Camera engineCamera = Camera::fit(engine.worldBounds(), 1280, 720);
      scenes_.push_back({"2CylinderEngine", std::move(engine), engineCamera});
    }
    return scenes_;
  }
  const BenchScene& builtin() { return scenes().front(); }
  Bench& bench() {
    if (!bench_) bench_ = std::make_unique<Bench>(options, context);
    return *bench_;
  }
  Options::Sizes effectSizes() const { return options.sizes({{640, 360}, {1280, 720}}); }

 private:
  std::vector<BenchScene> scenes_;
  std::unique_ptr<Bench> bench_;
};

// A section: its name (--NAME-only runs it alone; none for the core, which runs only with the rest), the files it
// writes in DIR, and whether the full run takes it (in this order; start-up first, in a process that has made
// nothing yet).
struct Section {
  const char* name;
  std::vector<const char*> writes;
  bool inFullRun;
  std::function<void(SectionInputs&)> run;
};

const std::vector<Section>& sections() {
  static const std::vector<Section> table = {
      {"startup", {"startup.csv"}, true, [](SectionInputs& in) { startupSection(in.options, in.context); }},
      {nullptr, {"bench.csv", "ratios.csv", "radius_sweep.csv", "radius_sweep.png"}, true,
       [](SectionInputs& in) { coreSections(in.options, in.bench(), in.scenes()); }},
      {"estimators", {"bench.csv", "estimators.csv"}, true,
       [](SectionInputs& in) {
         const auto [w, h] = in.options.size(1280, 720);
         estimatorSection(in.bench(), in.builtin(), w, h, in.options.outDir);
       }},
      {"motion", {"motion.csv"}, true,
       [](SectionInputs& in) {
         const auto [w, h] = in.options.size(1280, 720);
         motionSection(in.options, in.context, w, h);
       }},
      // With the transparent pass's section (8d), which also runs alone below.
      {"effects", {"effects.csv"}, true,
       [](SectionInputs& in) { effectsSection(in.options, in.context, in.effectSizes()); }},
      {"finish", {"finish.csv"}, true,
       [](SectionInputs& in) { finishSection(in.options, in.context, in.effectSizes()); }},
      {"stages", {"stages.csv"}, true,
       [](SectionInputs& in) { stagesSection(in.options, in.context, in.effectSizes()); }},
      {"temporal-ao", {"temporal_ao.csv"}, true,
       [](SectionInputs& in) { temporalAoSection(in.options, in.context, in.builtin()); }},
      {"resolution", {"resolution.csv"}, true,
       [](SectionInputs& in) { resolutionSection(in.options, in.context, in.builtin()); }},
      {"host", {"host.csv"}, true, [](SectionInputs& in) { hostSection(in.options, in.context); }},
      {"scene-bounds", {"scene_bounds.csv"}, true,
       [](SectionInputs& in) { sceneBoundsSection(in.options, in.context, in.scenes()); }},
      // Alone only: the full run has the transparent pass within section 8, and leaves out the two longest studies
      // and the culling study (its views are not the other sections' scenes).
      {"transparency", {"transparency.csv"}, false,
       [](SectionInputs& in) {
         std::ofstream csv(in.options.outDir + "/transparency.csv");
         csv << kEffectCostsHeader;
         transparencySection(in.options, in.context, in.effectSizes(), csv);
       }},
      {"lighting", {"lighting.csv"}, false, [](SectionInputs& in) { lightingSection(in.options, in.context); }},
      {"ao-layers", {"bench.csv", "ao_layers.csv"}, false,
       [](SectionInputs& in) { aoLayersSection(in.bench(), in.scenes(), in.effectSizes(), in.options.outDir); }},
      {"culling", {"culling.csv"}, false, [](SectionInputs& in) { cullingSection(in.options, in.context); }},
  };
  return table;
}

int main(int argc, char** argv) {
  try {
    std::vector<std::string> alone;
    for (const Section& section : sections())
      if (section.name) alone.emplace_back(section.name);
    const Options options = parseOptions(argc, argv, alone);
    if (std::system(("mkdir -p '" + options.outDir + "'").c_str()) != 0)
      throw InputError(options.outDir + ": cannot create");
    HeadlessContext context(options.backend);
    std::printf("obscura-bench: %s (%s), %d frames per figure (median), passes bounded by glFinish\n",
                backendName(options.backend), context.caps().renderer.c_str(), options.frames);
    SectionInputs inputs(options, context);
    std::vector<std::string> wrote;
    for (const Section& section : sections()) {
      if (options.only.empty() ? !section.inFullRun : !(section.name && options.alone(section.name))) continue;
      section.run(inputs);
      for (const char* file : section.writes)
        if (std::find(wrote.begin(), wrote.end(), file) == wrote.end()) wrote.emplace_back(file);
    }
    std::string files;
    for (const std::string& file : wrote) files += (files.empty() ? "" : ", ") + file;
    std::printf("\nobscura-bench: wrote %s/%s\n", options.outDir.c_str(), files.c_str());
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "obscura-bench: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "obscura-bench: %s\n", e.what());
    return 1;
  }
}
