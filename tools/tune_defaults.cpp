// obscura-tune: fits SAO's intensity sigma, bias beta and contrast k, per quality preset and radius, so that its
// blurred AO best matches the ray-traced reference at the same radius over a set of views; writes the fitted table
// the core reads (src/core/TunedDefaults.inc), and the accuracy report (docs/accuracy.md and its images).
// tools/tune-defaults.sh runs the whole procedure; see docs/accuracy.md.
//
//   obscura-tune --views tools/tuning-views.json --fit src/core/TunedDefaults.inc
//   obscura-tune --views tools/tuning-views.json --report docs/accuracy.md --images docs/images
//
// The reference images are cached under --cache (default build/tuning-cache), keyed by a hash of the scene's
// geometry, the camera, the radius, the ray count and the tracer's version, so they are traced once.
//
// Fit: for each preset (qualityPresets()) and radius, Nelder-Mead (Nelder & Mead 1965; Lagarias et al. 1998 for
// the coefficients: reflection 1, expansion 2, contraction 1/2, shrink 1/2) over (ln(sigma k), beta / r, ln k)
// clamped to a box, minimising the mean over views of MAE + w (1 - SSIM) over geometry pixels (w: "ssim_weight").
// Every evaluation renders the real pipeline (Renderer, headless), so the fit sees exactly what users see.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "apps/SceneInput.h"
#include "core/AoSettings.h"
#include "base/Error.h"
#include "core/Renderer.h"
#include "gl/RenderTarget.h"
#include "metrics/AoMetrics.h"
#include "platform/FinishPassTimer.h"
#include "platform/HeadlessContext.h"
#include "reference/AoReferenceTracer.h"
#include "scene/ImageIo.h"

namespace fs = std::filesystem;
using namespace obscura;

namespace {

// Bump when the tracer's output changes, so cached references are traced again.
constexpr const char* kReferenceVersion = "obscura-reference-1";

struct ViewSpec {
  std::string name;
  SceneInput input;
};

struct TuningConfig {
  int width = 480, height = 270;
  int rays = 256;
  std::vector<float> radii;
  float reportRadius = 1.0f;
  double ssimWeight = 0.0;
  int evaluations = 40;         // Nelder-Mead budget for the first preset fitted at each radius
  int followEvaluations = 15;   // ... and for the others, which start from its result
  std::vector<ViewSpec> views;
};

TuningConfig loadConfig(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError(path + ": cannot open tuning views");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(file);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path + ": malformed JSON: " + e.what());
  }
  auto fail = [&](const std::string& what) -> void { throw InputError(path + ": " + what); };
  TuningConfig config;
  try {
    const auto size = json.at("size");
    config.width = size.at(0).get<int>();
    config.height = size.at(1).get<int>();
    config.rays = json.at("rays").get<int>();
    config.radii = json.at("radii").get<std::vector<float>>();
    config.reportRadius = json.value("report_radius", 1.0f);
    config.ssimWeight = json.value("ssim_weight", 0.0);
    config.evaluations = json.value("evaluations", 40);
    config.followEvaluations = json.value("follow_evaluations", 15);
    for (const auto& view : json.at("views")) {
      ViewSpec spec;
      spec.name = view.at("name").get<std::string>();
      const std::string scene = view.value("scene", std::string("builtin"));
      if (scene != "builtin") spec.input.scenePath = scene;
      spec.input.sceneScale = view.value("scene_scale", 1.0f);
      spec.input.cameraPath = view.at("camera").get<std::string>();
      spec.input.width = config.width;
      spec.input.height = config.height;
      config.views.push_back(spec);
    }
  } catch (const nlohmann::json::exception& e) {
    fail(std::string("unexpected content: ") + e.what());
  }
  if (config.width < 16 || config.height < 16 || config.width > 4096 || config.height > 4096)
    fail("size: each side must be in 16 .. 4096");
  if (config.radii.empty() || !std::is_sorted(config.radii.begin(), config.radii.end()))
    fail("radii: expected an increasing list");
  for (float r : config.radii)
    if (!(r >= 0.01f && r <= 100.0f)) fail("radii: each must be in 0.01 .. 100 metres");
  if (config.views.empty()) fail("views: empty");
  if (config.evaluations < 4 || config.followEvaluations < 4) fail("evaluations: at least 4");
  return config;
}

// FNV-1a, 64-bit: a stable key for the cache (not security).
struct Hasher {
  std::uint64_t value = 0xcbf29ce484222325ULL;
  void bytes(const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) value = (value ^ p[i]) * 0x100000001b3ULL;
  }
  template <typename T>
  void vector(const std::vector<T>& v) {
    bytes(v.data(), v.size() * sizeof(T));
  }
  void text(const std::string& s) { bytes(s.data(), s.size()); }
  std::string hex() const {
    char out[17];
    std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(value));
    return out;
  }
};

std::string referenceKey(const Scene& scene, const Camera& camera, int rays) {
  Hasher h;
  h.text(kReferenceVersion);
  for (const Mesh& mesh : scene.meshes) {
    h.vector(mesh.positions);
    h.vector(mesh.indices);
    const bool doubleSided = mesh.material >= 0 && scene.materials[static_cast<size_t>(mesh.material)].doubleSided;
    h.bytes(&doubleSided, sizeof doubleSided);
  }
  for (const Instance& instance : scene.instances) {
    h.bytes(&instance.mesh, sizeof instance.mesh);
    h.bytes(&instance.world, sizeof instance.world);
  }
  h.text(camera.toJson());
  h.bytes(&rays, sizeof rays);
  return h.hex();
}

std::string radiusText(float radius) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", static_cast<double>(radius));
  return text;
}

// One view: its scene in a renderer, its camera, and its reference images per radius.
struct TuningView {
  ViewSpec spec;
  Camera camera;
  std::unique_ptr<Renderer> renderer;
  std::unique_ptr<gl::RenderTarget> output;
  std::vector<std::uint8_t> mask, haloBand;  // from the reference's mask and depth views
  std::map<float, Image> referenceAo;
  std::map<float, GreyImage> referenceGrey;
};

void loadReferences(TuningView& view, const Scene& scene, const TuningConfig& config, const fs::path& cache,
                    int threads) {
  fs::create_directories(cache);
  const std::string key = referenceKey(scene, view.camera, config.rays);
  const fs::path depthPath = cache / (view.spec.name + "-" + key + "-depth.png");
  const fs::path maskPath = cache / (view.spec.name + "-" + key + "-mask.png");
  std::unique_ptr<AoReferenceTracer> tracer;
  for (float radius : config.radii) {
    const fs::path aoPath = cache / (view.spec.name + "-" + key + "-r" + radiusText(radius) + ".png");
    if (!fs::exists(aoPath) || !fs::exists(depthPath) || !fs::exists(maskPath)) {
      if (!tracer) tracer = std::make_unique<AoReferenceTracer>(scene, threads);
      const auto start = std::chrono::steady_clock::now();
      const ReferenceFrame frame = tracer->trace(view.camera, {radius, config.rays, threads});
      writePng(aoPath.string(), frame.aoImage());
      writePng(depthPath.string(), frame.depthImage());
      writePng(maskPath.string(), frame.maskImage());
      std::printf("  traced %s at r = %s m: %.1f s\n", view.spec.name.c_str(), radiusText(radius).c_str(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      std::fflush(stdout);
    }
    view.referenceAo[radius] = readPng(aoPath.string());
    view.referenceGrey[radius] = GreyImage::fromRed(view.referenceAo[radius]);
  }
  view.mask = maskFromImage(readPng(maskPath.string()));
  view.haloBand = discontinuityBand(GreyImage::fromRed(readPng(depthPath.string())), {});
}

Image renderAo(TuningView& view, const AoSettings& settings, PassTimer* timer = nullptr) {
  view.renderer->render(view.camera, settings, obscura::View::Ao,
                        OutputTarget{view.output->framebuffer(), view.camera.width, view.camera.height, {}}, timer);
  Image image;
  image.width = view.camera.width;
  image.height = view.camera.height;
  image.rgba = view.output->readRgba();
  return image;
}

AoComparison measure(TuningView& view, const AoSettings& settings, float radius, bool ssim = true) {
  const GreyImage sao = GreyImage::fromRed(renderAo(view, settings));
  return compareAo(view.referenceGrey.at(radius), sao, view.mask, view.haloBand, ssim);
}

struct Score {
  double objective = 0, mae = 0, ssim = 0, haloMae = 0;
};

Score score(std::vector<TuningView>& views, const AoSettings& settings, float radius, double ssimWeight,
            bool ssim = true) {
  Score s;
  for (TuningView& view : views) {
    const AoComparison c = measure(view, settings, radius, ssim);
    s.mae += c.mae;
    s.ssim += c.ssim;
    s.haloMae += c.haloMae;
  }
  const double n = static_cast<double>(views.size());
  s.mae /= n;
  s.ssim /= n;
  s.haloMae /= n;
  s.objective = s.mae + ssimWeight * (1.0 - s.ssim);
  return s;
}

// --- The fit -------------------------------------------------------------------------------------------------------

// The search runs over (ln(sigma k), beta / r, ln k). SAO's visibility is max(0, 1 - sigma S)^k for the tap sum S;
// for large k it tends to exp(-sigma k S), so sigma and k trade against each other along sigma k = const. Searching
// ln(sigma k) and ln k separately keeps that valley axis-aligned, where Nelder-Mead walks it quickly.
using Point = std::array<double, 3>;

// The box the search stays in: inside AoSettings' ranges (intensity 0 .. 20, contrast 0.1 .. 10, bias 0 .. 1 m), and
// narrower where that costs nothing: a bias beyond half the radius ignores nearly every occluder, and contrast stops
// at 5 because the fit runs up the sigma k = const valley towards exp(-sigma k S), where the error is flat (at
// r = 1 m, k = 10 instead of 5 lowered the mean MAE by 0.0001) while the default would pin the contrast control to
// the top of its range.
Point clampToBox(const Point& p) {
  const double lnK = std::clamp(p[2], std::log(0.2), std::log(5.0));
  const double lnSigmaK = std::clamp(p[0], std::log(0.05) + lnK, std::log(20.0) + lnK);
  return {lnSigmaK, std::clamp(p[1], 0.0, 0.5), lnK};
}

EstimatorParameters toParameters(const Point& p, float radius) {
  const Point q = clampToBox(p);
  // Rounded to what the table stores, so the fitted figures are those of the written values.
  auto round4 = [](double v) { return static_cast<float>(std::round(v * 1e4) / 1e4); };
  return {round4(std::exp(q[0] - q[2])), std::min(round4(q[1] * radius), 1.0f), round4(std::exp(q[2]))};
}

Point fromParameters(const EstimatorParameters& e, float radius) {
  return clampToBox({std::log(e.intensity * e.contrast), e.bias / radius, std::log(e.contrast)});
}

Point nelderMead(const std::function<double(const Point&)>& f, const Point& start, const Point& step,
                 int maxEvaluations) {
  std::array<Point, 4> simplex;
  std::array<double, 4> value;
  int evaluations = 0;
  auto eval = [&](const Point& p) {
    ++evaluations;
    return f(clampToBox(p));
  };
  simplex[0] = clampToBox(start);
  for (int i = 0; i < 3; ++i) {
    simplex[static_cast<size_t>(i + 1)] = simplex[0];
    Point& vertex = simplex[static_cast<size_t>(i + 1)];
    vertex[static_cast<size_t>(i)] += step[static_cast<size_t>(i)];
    // A vertex clamped back onto the start would make the simplex degenerate: step the other way instead.
    if (clampToBox(vertex) == simplex[0]) vertex[static_cast<size_t>(i)] -= 2 * step[static_cast<size_t>(i)];
    vertex = clampToBox(vertex);
  }
  for (size_t i = 0; i < 4; ++i) value[i] = eval(simplex[i]);
  while (evaluations < maxEvaluations) {
    std::array<size_t, 4> order{0, 1, 2, 3};
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return value[a] < value[b]; });
    std::array<Point, 4> s;
    std::array<double, 4> v;
    for (size_t i = 0; i < 4; ++i) {
      s[i] = simplex[order[i]];
      v[i] = value[order[i]];
    }
    simplex = s;
    value = v;
    if (value[3] - value[0] < 2e-5) break;  // spread below a tenth of a grey level of MAE: converged
    Point centroid{0, 0, 0};
    for (size_t i = 0; i < 3; ++i)
      for (size_t d = 0; d < 3; ++d) centroid[d] += simplex[i][d] / 3.0;
    auto along = [&](double t) {
      Point p;
      for (size_t d = 0; d < 3; ++d) p[d] = centroid[d] + t * (simplex[3][d] - centroid[d]);
      return clampToBox(p);
    };
    const Point reflected = along(-1.0);
    const double fr = eval(reflected);
    if (fr < value[0]) {
      const Point expanded = along(-2.0);
      const double fe = eval(expanded);
      if (fe < fr) {
        simplex[3] = expanded;
        value[3] = fe;
      } else {
        simplex[3] = reflected;
        value[3] = fr;
      }
    } else if (fr < value[2]) {
      simplex[3] = reflected;
      value[3] = fr;
    } else {
      const bool outside = fr < value[3];
      const Point contracted = along(outside ? -0.5 : 0.5);
      const double fc = eval(contracted);
      if (fc < std::min(fr, value[3])) {
        simplex[3] = contracted;
        value[3] = fc;
      } else {
        for (size_t i = 1; i < 4; ++i) {
          for (size_t d = 0; d < 3; ++d) simplex[i][d] = simplex[0][d] + 0.5 * (simplex[i][d] - simplex[0][d]);
          value[i] = eval(simplex[i]);
        }
      }
    }
  }
  return simplex[static_cast<size_t>(std::min_element(value.begin(), value.end()) - value.begin())];
}

AoSettings settingsFor(QualityPreset preset, float radius) {
  AoSettings settings;
  settings.applyPreset(preset);
  settings.radius = radius;
  return settings;
}

AoSettings withParameters(AoSettings settings, const EstimatorParameters& e) {
  settings.intensity = e.intensity;
  settings.bias = e.bias;
  settings.contrast = e.contrast;
  return settings;
}

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

std::string floatLiteral(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", static_cast<double>(value));
  std::string s = text;
  while (s.size() > 1 && s.back() == '0' && s[s.size() - 2] != '.') s.pop_back();
  return s + "f";
}

std::string presetEnumName(const PresetInfo& preset) {
  std::string name = preset.name;
  name[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
  return "QualityPreset::" + name;
}

std::string viewList(const TuningConfig& config) {
  std::string names;
  for (const ViewSpec& v : config.views) names += (names.empty() ? "" : ", ") + v.name;
  return names;
}

void fit(std::vector<TuningView>& views, const TuningConfig& config, const std::string& tablePath) {
  struct Row {
    const PresetInfo* preset;
    float radius;
    EstimatorParameters fitted;
    Score tuned, paper;
  };
  std::vector<Row> rows;
  const auto& presets = qualityPresets();
  // The default preset first: the others start from its result at the same radius.
  std::vector<const PresetInfo*> order;
  for (const PresetInfo& p : presets)
    if (p.preset == AoSettings{}.preset) order.push_back(&p);
  for (const PresetInfo& p : presets)
    if (p.preset != AoSettings{}.preset) order.push_back(&p);

  std::map<float, EstimatorParameters> leader;
  for (const PresetInfo* preset : order) {
    EstimatorParameters start = kPaperEstimatorParameters;
    for (float radius : config.radii) {
      const bool first = leader.count(radius) == 0;
      if (!first) start = leader[radius];
      const AoSettings base = settingsFor(preset->preset, radius);
      int evaluations = 0;
      auto objective = [&](const Point& p) {
        ++evaluations;
        // SSIM costs as much as the render: computed only when the objective weighs it.
        return score(views, withParameters(base, toParameters(p, radius)), radius, config.ssimWeight,
                     config.ssimWeight > 0.0)
            .objective;
      };
      const auto begin = std::chrono::steady_clock::now();
      const Point step = first ? Point{0.4, 0.03, 0.4} : Point{0.15, 0.01, 0.15};
      const Point best = nelderMead(objective, fromParameters(start, radius), step,
                                    first ? config.evaluations : config.followEvaluations);
      Row row{preset, radius, toParameters(best, radius), {}, {}};
      row.tuned = score(views, withParameters(base, row.fitted), radius, config.ssimWeight);
      row.paper = score(views, withParameters(base, kPaperEstimatorParameters), radius, config.ssimWeight);
      std::printf("  %-6s r = %-4s sigma %.3f beta %.4f k %.3f | MAE %.4f SSIM %.3f halo %.4f | paper MAE %.4f SSIM "
                  "%.3f | %d renders x %zu views, %.0f s\n",
                  preset->name, radiusText(radius).c_str(), static_cast<double>(row.fitted.intensity),
                  static_cast<double>(row.fitted.bias), static_cast<double>(row.fitted.contrast), row.tuned.mae,
                  row.tuned.ssim, row.tuned.haloMae, row.paper.mae, row.paper.ssim, evaluations, views.size(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count());
      std::fflush(stdout);
      if (first) leader[radius] = row.fitted;
      start = row.fitted;
      rows.push_back(row);
    }
  }

  // Rows grouped by preset in qualityPresets() order, radii increasing, as tunedEstimatorParameters expects.
  std::ostringstream out;
  const std::string objective =
      config.ssimWeight > 0.0 ? "MAE + " + format("%g", config.ssimWeight) + " (1 - SSIM)" : std::string("MAE");
  out << "// Generated by tools/tune-defaults.sh (obscura-tune --fit): do not edit by hand.\n"
      << "// SAO's intensity sigma, bias beta and contrast k per quality preset and radius, fitted to the ray-traced\n"
      << "// reference (obscura-reference, " << config.rays << " rays per pixel) at " << config.width << "x"
      << config.height << ", minimising the mean " << objective << "\n"
      << "// of the blurred AO over geometry pixels across the views of tools/tuning-views.json:\n"
      << "// " << viewList(config) << ".\n"
      << "// docs/accuracy.md explains the procedure.\n"
      << "// {preset, radius (m), {intensity sigma, bias beta (m), contrast k}},  // fitted | SAO paper's values\n";
  for (const PresetInfo& preset : presets) {
    for (const Row& row : rows) {
      if (row.preset != &preset) continue;
      char comment[160];
      std::snprintf(comment, sizeof comment, "  // MAE %.4f SSIM %.3f | paper MAE %.4f SSIM %.3f", row.tuned.mae,
                    row.tuned.ssim, row.paper.mae, row.paper.ssim);
      out << "{" << presetEnumName(preset) << ", " << floatLiteral(row.radius) << ", {"
          << floatLiteral(row.fitted.intensity) << ", " << floatLiteral(row.fitted.bias) << ", "
          << floatLiteral(row.fitted.contrast) << "}}," << comment << "\n";
    }
  }
  std::ofstream file(tablePath);
  if (!(file << out.str())) throw InputError(tablePath + ": cannot write");
  std::printf("obscura-tune: wrote %s\n", tablePath.c_str());
}

// --- The report ------------------------------------------------------------------------------------------------------

double aoMilliseconds(TuningView& view, const AoSettings& settings) {
  // The median over a few frames of the AO effect's passes: the cost AO adds.
  FinishPassTimer timer;
  constexpr int kFrames = 11;
  for (int i = 0; i < kFrames; ++i) renderAo(view, settings, &timer);
  std::vector<double> frames(kFrames, 0.0);
  for (const std::string& pass : effectEntry("ao").info.passes) {
    const std::vector<double>& samples = timer.samples(pass);
    for (size_t i = 0; i < samples.size() && i < frames.size(); ++i) frames[i] += samples[i];
  }
  std::sort(frames.begin(), frames.end());
  return frames[kFrames / 2];
}

void report(std::vector<TuningView>& views, const TuningConfig& config, const std::string& docPath,
            const std::string& imageDir, const HeadlessContext& context) {
  const float radius = config.reportRadius;
  if (std::find(config.radii.begin(), config.radii.end(), radius) == config.radii.end())
    throw InputError("report_radius: must be one of the fitted radii");
  std::ostringstream md;
  md << "Generated by `tools/tune-defaults.sh` (`obscura-tune --report`) on " << context.caps().renderer << ", "
     << config.width << "x" << config.height << ", reference " << config.rays << " rays per pixel. Errors are in AO "
     << "units (0 = black, 1 = white) over geometry pixels; *halo* is the MAE within 3 pixels of a depth "
     << "discontinuity; *AO ms* is the median time of the AO passes (everything but the G-buffer and the composite), "
     << "glFinish-bounded.\n\n";

  md << "### Each view and preset at r = " << radiusText(radius) << " m, default (tuned) parameters\n\n"
     << "| view | preset | MAE | RMSE | SSIM | Pearson | halo MAE | interior MAE | bias | AO ms | MAE, paper's sigma/beta/k "
        "|\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::map<std::string, std::array<double, 5>> meanByPreset;  // MAE, SSIM, halo, paper MAE, Pearson
  for (TuningView& view : views) {
    for (const PresetInfo& preset : qualityPresets()) {
      const AoSettings tuned = settingsFor(preset.preset, radius);  // estimator parameters left to the table
      const AoComparison c = measure(view, tuned, radius);
      const AoComparison paper = measure(view, withParameters(tuned, kPaperEstimatorParameters), radius);
      const double ms = aoMilliseconds(view, tuned);
      md << "| " << view.spec.name << " | " << preset.name << " | " << format("%.4f", c.mae) << " | "
         << format("%.4f", c.rmse) << " | " << format("%.3f", c.ssim) << " | " << format("%.3f", c.pearson) << " | "
         << format("%.4f", c.haloMae) << " | "
         << format("%.4f", c.interiorMae) << " | " << format("%+.4f", c.bias) << " | " << format("%.1f", ms) << " | "
         << format("%.4f", paper.mae) << " |\n";
      auto& mean = meanByPreset[preset.name];
      mean[0] += c.mae / static_cast<double>(views.size());
      mean[1] += c.ssim / static_cast<double>(views.size());
      mean[2] += c.haloMae / static_cast<double>(views.size());
      mean[3] += paper.mae / static_cast<double>(views.size());
      mean[4] += c.pearson / static_cast<double>(views.size());
    }
  }
  md << "\n**Mean over the views:**\n\n"
     << "| preset | MAE | SSIM | Pearson | halo MAE | MAE, paper's sigma/beta/k |\n|---|---|---|---|---|---|\n";
  for (const PresetInfo& preset : qualityPresets()) {
    const auto& mean = meanByPreset[preset.name];
    md << "| " << preset.name << " | " << format("%.4f", mean[0]) << " | " << format("%.3f", mean[1]) << " | "
       << format("%.3f", mean[4]) << " | " << format("%.4f", mean[2]) << " | " << format("%.4f", mean[3]) << " |\n";
  }

  const AoSettings defaults;
  md << "\n### Every fitted radius, preset " << presetName(defaults.preset)
     << " (mean over the views)\n\n"
     << "| radius (m) | sigma | beta (m) | k | MAE | SSIM | halo MAE | MAE, paper's values | SSIM, paper's values |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  for (float r : config.radii) {
    AoSettings tuned = settingsFor(defaults.preset, r);
    const EstimatorParameters e = tuned.estimator();
    const Score s = score(views, tuned, r, 0.0);
    const Score paper = score(views, withParameters(tuned, kPaperEstimatorParameters), r, 0.0);
    md << "| " << radiusText(r) << " | " << format("%.3f", e.intensity) << " | " << format("%.4f", e.bias) << " | "
       << format("%.3f", e.contrast) << " | " << format("%.4f", s.mae) << " | " << format("%.3f", s.ssim) << " | "
       << format("%.4f", s.haloMae) << " | " << format("%.4f", paper.mae) << " | " << format("%.3f", paper.ssim)
       << " |\n";
  }

  md << "\n### Reference | SAO | difference\n\nPreset " << presetName(defaults.preset)
     << ", r = " << radiusText(radius) << " m, tuned parameters. Difference: red where SAO is darker than the "
     << "reference, blue where lighter, full colour at 0.25; grey: background.\n\n";
  fs::create_directories(imageDir);
  const fs::path docDir = fs::path(docPath).parent_path();
  for (TuningView& view : views) {
    const AoSettings tuned = settingsFor(defaults.preset, radius);
    const Image sao = renderAo(view, tuned);
    const Image& reference = view.referenceAo.at(radius);
    const Image diff = differenceImage(view.referenceGrey.at(radius), GreyImage::fromRed(sao), view.mask);
    const fs::path file = fs::path(imageDir) / ("accuracy-" + view.spec.name + ".png");
    writePng(file.string(), sideBySide({reference, sao, diff}));
    md << "**" << view.spec.name << "**\n\n![" << view.spec.name << ": reference | SAO | difference]("
       << fs::relative(file, docDir.empty() ? fs::path(".") : docDir).generic_string() << ")\n\n";
  }

  // Replace the generated part of the document, between the markers, keeping the prose around it.
  const std::string begin = "<!-- obscura-tune:begin -->", end = "<!-- obscura-tune:end -->";
  std::ifstream in(docPath);
  if (!in) throw InputError(docPath + ": cannot open (the report goes between " + begin + " and " + end + ")");
  std::stringstream text;
  text << in.rdbuf();
  std::string doc = text.str();
  const size_t a = doc.find(begin), b = doc.find(end);
  if (a == std::string::npos || b == std::string::npos || b < a)
    throw InputError(docPath + ": missing the markers " + begin + " ... " + end);
  doc = doc.substr(0, a + begin.size()) + "\n" + md.str() + doc.substr(b);
  std::ofstream outFile(docPath);
  if (!(outFile << doc)) throw InputError(docPath + ": cannot write");
  std::printf("obscura-tune: wrote %s and %zu images in %s\n", docPath.c_str(), views.size(), imageDir.c_str());
}

std::string usage() {
  return "usage: obscura-tune [--views FILE] [--cache DIR] [--fit TABLE.inc] [--report DOC.md --images DIR]\n"
         "                    [--threads N] [--backend osmesa|egl]\n"
         "\n"
         "Fits SAO's intensity, bias and contrast per preset and radius to the ray-traced reference (--fit), or\n"
         "measures the current defaults against it and writes the accuracy report (--report). tools/tune-defaults.sh\n"
         "runs both.\n"
         "  --views FILE   the views, radii and sizes (default tools/tuning-views.json)\n"
         "  --cache DIR    where reference images are kept between runs (default build/tuning-cache)\n"
         "  --fit FILE     write the fitted table (src/core/TunedDefaults.inc)\n"
         "  --report FILE  rewrite the generated part of FILE (docs/accuracy.md)\n"
         "  --images DIR   where the report's pictures go (default docs/images)\n"
         "  --threads N    ray-tracing threads (default: the number of cores)\n"
         "  --backend B    osmesa (default) or egl\n";
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string viewsPath = "tools/tuning-views.json", cache = "build/tuning-cache", tablePath, docPath,
                imageDir = "docs/images";
    int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    HeadlessBackend backend = HeadlessBackend::OSMesa;
    const std::vector<std::string> args(argv + 1, argv + argc);
    for (size_t i = 0; i < args.size(); ++i) {
      const std::string& arg = args[i];
      auto value = [&]() -> const std::string& {
        if (i + 1 >= args.size()) throw InputError(arg + ": missing value");
        return args[++i];
      };
      if (arg == "--help" || arg == "-h") {
        std::cout << usage();
        return 0;
      } else if (arg == "--views") viewsPath = value();
      else if (arg == "--cache") cache = value();
      else if (arg == "--fit") tablePath = value();
      else if (arg == "--report") docPath = value();
      else if (arg == "--images") imageDir = value();
      else if (arg == "--threads") threads = parseCount(arg, value(), 256);
      else if (arg == "--backend") backend = parseBackend(value());
      else throw InputError("unknown option '" + arg + "' (see --help)");
    }
    if (tablePath.empty() == docPath.empty()) throw InputError("expected exactly one of --fit and --report");
    const TuningConfig config = loadConfig(viewsPath);

    const auto start = std::chrono::steady_clock::now();
    HeadlessContext context(backend);
    std::vector<TuningView> views(config.views.size());
    std::printf("obscura-tune: %zu views at %dx%d, radii", views.size(), config.width, config.height);
    for (float r : config.radii) std::printf(" %s", radiusText(r).c_str());
    std::printf(" m; references in %s\n", cache.c_str());
    for (size_t i = 0; i < views.size(); ++i) {
      TuningView& view = views[i];
      view.spec = config.views[i];
      SceneInput::Loaded input = view.spec.input.load();
      view.spec.input.printWarnings("obscura-tune", input.warnings);
      const Scene scene = std::move(input.scene);
      view.camera = input.camera;
      loadReferences(view, scene, config, cache, threads);
      view.renderer = std::make_unique<Renderer>(context.caps());
      view.renderer->setScene(scene);
      view.output = std::make_unique<gl::RenderTarget>("tuning output", view.camera.width, view.camera.height,
                                                       GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                                       context.caps().depth24);
    }
    if (!tablePath.empty()) fit(views, config, tablePath);
    else report(views, config, docPath, imageDir, context);
    std::printf("obscura-tune: done in %.0f s\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return 0;
  } catch (const InputError& e) {
    std::cerr << "obscura-tune: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "obscura-tune: " << e.what() << "\n";
    return 1;
  }
}
