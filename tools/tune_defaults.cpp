// obscura-tune: fits each AO estimator's intensity sigma, bias beta and contrast k (ao.estimator: SAO, GTAO, HBAO, VO,
// Crytek), per quality preset and radius in pixels, so that its blurred AO best matches the ray-traced reference at
// the same radius over a set of views (each at several radii, multiples of a typical object's size in that scene's
// units); writes the fitted table
// the core reads (src/effects/ao/TunedDefaults.inc), and the accuracy report (docs/accuracy.md and its images).
// tools/tune-defaults.sh runs the whole procedure; see docs/accuracy.md.
//
//   obscura-tune --views tools/tuning-views.json --fit src/effects/ao/TunedDefaults.inc
//   obscura-tune --views tools/tuning-views.json --report docs/accuracy.md --images docs/images
//
// The reference images are cached under --cache (default build/tuning-cache), keyed by a hash of the scene's
// geometry, the camera, the radius, the ray count and the tracer's version, so they are traced once.
//
// Fit: for each preset (qualityPresets()) and knot of the projected radius in pixels (AoSettings.h), Nelder-Mead
// (Nelder & Mead 1965; Lagarias et al. 1998 for the coefficients: reflection 1, expansion 2, contraction 1/2,
// shrink 1/2) over (ln(sigma k), beta / r, ln k) clamped to a box, minimising the MAE over the geometry pixels whose
// radius in pixels lies nearest that knot, across every view and radius (see fit()).
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
#include <numeric>
#include <optional>
#include <sstream>
#include <thread>

#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "apps/SceneInput.h"
#include "base/Error.h"
#include "base/Text.h"
#include "effects/ao/AoSettings.h"
#include "effects/ao/SaoKernel.h"
#include "encoding/LinearDepthPacking.h"
#include "frame/FrameContext.h"
#include "gl/RenderTarget.h"
#include "metrics/AoMetrics.h"
#include "platform/FinishPassTimer.h"
#include "platform/HeadlessContext.h"
#include "reference/AoReferenceTracer.h"
#include "renderer/Renderer.h"
#include "scene/BuiltinScene.h"
#include "scene/ImageIo.h"

namespace fs = std::filesystem;
using namespace obscura;

namespace {

// Bump when the tracer's output changes, so cached references are traced again.
constexpr const char* kReferenceVersion = "obscura-reference-1";

struct ViewSpec {
  std::string name;
  SceneInput input;
  float objectSize = 1.0f;  // a typical object's size in the scene's units: the radii are multiples of it
};

struct TuningConfig {
  int width = 480, height = 270;
  int rays = 256;
  std::vector<float> radiusFactors;  // each view is measured at these multiples of its object size
  float reportFactor = 1.0f;         // the one the per-view tables and pictures show
  int evaluations = 40;         // Nelder-Mead budget for the first preset fitted at each knot
  int followEvaluations = 15;   // ... and for the others, which start from its result
  // Where --report writes in the document: between <!-- obscura-tune:begin --> and <!-- obscura-tune:end -->, or, for
  // a section named S, <!-- obscura-tune:S:begin --> and <!-- obscura-tune:S:end --> (another set of views measured
  // with the same defaults, e.g. tools/orthographic-views.json).
  std::string reportSection;
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
    config.radiusFactors = json.at("radius_factors").get<std::vector<float>>();
    config.reportFactor = json.value("report_factor", 1.0f);
    config.evaluations = json.value("evaluations", 40);
    config.followEvaluations = json.value("follow_evaluations", 15);
    config.reportSection = json.value("report_section", std::string());
    for (const auto& view : json.at("views")) {
      ViewSpec spec;
      spec.name = view.at("name").get<std::string>();
      const std::string scene = view.value("scene", std::string("builtin"));
      if (scene != "builtin") spec.input.scenePath = scene;
      spec.input.sceneScale = view.value("scene_scale", 1.0f);
      // A camera file, or one of the scene's own cameras ("camera_node": its name or index, at time 0).
      if (view.contains("camera_node")) spec.input.cameraNode = view.at("camera_node").get<std::string>();
      else spec.input.cameraPath = view.at("camera").get<std::string>();
      spec.objectSize = view.at("object_size").get<float>();
      if (!(spec.objectSize > 0.0f)) fail("views: " + spec.name + ": object_size must be positive");
      spec.input.width = config.width;
      spec.input.height = config.height;
      config.views.push_back(spec);
    }
  } catch (const nlohmann::json::exception& e) {
    fail(std::string("unexpected content: ") + e.what());
  }
  if (config.width < 16 || config.height < 16 || config.width > 4096 || config.height > 4096)
    fail("size: each side must be in 16 .. 4096");
  if (config.radiusFactors.empty() || !std::is_sorted(config.radiusFactors.begin(), config.radiusFactors.end()))
    fail("radius_factors: expected an increasing list");
  for (float f : config.radiusFactors)
    if (!(f >= 0.01f && f <= 100.0f)) fail("radius_factors: each must be in 0.01 .. 100");
  if (std::find(config.radiusFactors.begin(), config.radiusFactors.end(), config.reportFactor) ==
      config.radiusFactors.end())
    fail("report_factor: must be one of radius_factors");
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

// One view: its scene in a renderer, its camera, and what the reference says of it.
struct TuningView {
  ViewSpec spec;
  Camera camera;
  std::unique_ptr<Renderer> renderer;
  std::unique_ptr<gl::RenderTarget> output;
  std::vector<std::uint8_t> mask, haloBand;  // from the reference's mask and depth views
  std::vector<float> viewDepth;              // -z_view per pixel (0 on background), from the 16-bit depth code
};

// One view at one radius: the unit the fit and the report measure.
struct TuningCase {
  TuningView* view = nullptr;
  float factor = 1.0f;  // the radius in units of the view's object size
  float radius = 1.0f;  // in the scene's units
  Image referenceAo;
  GreyImage reference;
  std::vector<float> radiusPixels;  // the estimator's projected radius h at each pixel (clamped as the shader does)
  double whiteMae = 0;              // MAE of an all-white image: what "no AO" would score
};

// The 16-bit depth code per pixel in R (high byte) and G (low byte): the depth view's 8 bits are too coarse to place
// a pixel's projected radius in its knot.
Image depthCodeImage(const ReferenceFrame& frame) {
  Image image{frame.width, frame.height, std::vector<std::uint8_t>(frame.linearDepth.size() * 4, 255)};
  for (size_t i = 0; i < frame.linearDepth.size(); ++i) {
    const std::uint16_t code = LinearDepthPacking::codeFromDepth(frame.linearDepth[i]);
    image.rgba[i * 4 + 0] = static_cast<std::uint8_t>(code >> 8);
    image.rgba[i * 4 + 1] = static_cast<std::uint8_t>(code & 0xff);
    image.rgba[i * 4 + 2] = 0;
  }
  return image;
}

std::vector<TuningCase> loadReferences(TuningView& view, const Scene& scene, const TuningConfig& config,
                                       const fs::path& cache, int threads) {
  fs::create_directories(cache);
  const std::string key = referenceKey(scene, view.camera, config.rays);
  const std::string stem = (cache / (view.spec.name + "-" + key)).string();
  const std::string depthPath = stem + "-depth.png", codePath = stem + "-depth16.png", maskPath = stem + "-mask.png";
  std::unique_ptr<AoReferenceTracer> tracer;
  std::vector<TuningCase> cases;
  for (float factor : config.radiusFactors) {
    const float radius = factor * view.spec.objectSize;
    const std::string aoPath = stem + "-r" + radiusText(radius) + ".png";
    if (!fs::exists(aoPath) || !fs::exists(depthPath) || !fs::exists(codePath) || !fs::exists(maskPath)) {
      if (!tracer) tracer = std::make_unique<AoReferenceTracer>(scene, threads);
      const auto start = std::chrono::steady_clock::now();
      const ReferenceFrame frame = tracer->trace(view.camera, {radius, config.rays, threads});
      writePng(aoPath, frame.aoImage());
      writePng(depthPath, frame.depthImage());
      writePng(codePath, depthCodeImage(frame));
      writePng(maskPath, frame.maskImage());
      std::printf("  traced %s at r = %s: %.1f s\n", view.spec.name.c_str(), radiusText(radius).c_str(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      std::fflush(stdout);
    }
    TuningCase c;
    c.view = &view;
    c.factor = factor;
    c.radius = radius;
    c.referenceAo = readPng(aoPath);
    c.reference = GreyImage::fromRed(c.referenceAo);
    cases.push_back(std::move(c));
  }
  view.mask = maskFromImage(readPng(maskPath));
  // The halo band: geometry within 4 pixels of a depth discontinuity.
  DiscontinuityOptions band;
  band.haloWidth = 4;
  view.haloBand = discontinuityBand(GreyImage::fromRed(readPng(depthPath)), band);
  const Image codes = readPng(codePath);
  view.viewDepth.assign(view.mask.size(), 0.0f);
  for (size_t i = 0; i < view.mask.size(); ++i) {
    const auto code = static_cast<std::uint16_t>((codes.rgba[i * 4] << 8) | codes.rgba[i * 4 + 1]);
    if (view.mask[i])
      view.viewDepth[i] =
          view.camera.near + LinearDepthPacking::depthFromCode(code) * (view.camera.far - view.camera.near);
  }
  // h = min(projScale r / -z, maxScreenRadius * height), as SaoKernel::diskRadiusPixels at G-buffer resolution.
  const AoSettings defaults;
  const glm::vec2 projScale =
      FrameCamera::from(view.camera, view.camera.width, view.camera.height).projScale(view.camera.height);
  const float maxPixels = defaults.maxScreenRadius * static_cast<float>(view.camera.height);
  for (TuningCase& c : cases) {
    c.radiusPixels.assign(view.mask.size(), 0.0f);
    double white = 0.0;
    size_t pixels = 0;
    for (size_t i = 0; i < view.mask.size(); ++i) {
      if (!view.mask[i]) continue;
      c.radiusPixels[i] = SaoKernel::diskRadiusPixels(c.radius, -view.viewDepth[i], projScale, maxPixels);
      white += 1.0 - c.reference.values[i];
      ++pixels;
    }
    c.whiteMae = pixels ? white / static_cast<double>(pixels) : 0.0;
  }
  return cases;
}

// --set NAME=VALUE: parameters of the frame every render of this run takes (RenderSettings::set, after the
// estimator's, the preset's and the fitted parameters): to measure an option against the reference (ao.layers 2,
// gbuffer.normals reconstructed) with --evaluate, or to fit and report with it.
std::vector<std::pair<std::string, std::string>>& frameOverrides() {
  static std::vector<std::pair<std::string, std::string>> overrides;
  return overrides;
}

Image renderAo(TuningView& view, const AoSettings& settings, PassTimer* timer = nullptr) {
  RenderSettings frame(settings);
  for (const auto& [name, value] : frameOverrides()) frame.set(name, value);
  view.renderer->render(view.camera, frame, obscura::View::Ao,
                        OutputTarget{view.output->framebuffer(), view.camera.width, view.camera.height, {}}, timer);
  Image image;
  image.width = view.camera.width;
  image.height = view.camera.height;
  image.rgba = view.output->readRgba();
  return image;
}

AoComparison measure(TuningCase& c, const AoSettings& settings, bool ssim = true) {
  AoSettings at = settings;
  at.radius = c.radius;
  const GreyImage ao = GreyImage::fromRed(renderAo(*c.view, at));
  return compareAo(c.reference, ao, c.view->mask, c.view->haloBand, ssim);
}

// The knot a projected radius h belongs to when fitting: the nearest in log2(h), the ends taking everything beyond.
int knotOf(float radiusPixels) {
  const float t = std::log2(std::max(radiusPixels, 1e-3f) / kFirstKnotPixels);
  return std::clamp(static_cast<int>(std::lround(t)), 0, kEstimatorKnots - 1);
}

// Means over cases, each case weighted alike.
struct Score {
  double mae = 0, ssim = 0, pearson = 0, haloMae = 0, interiorMae = 0, nearSideMae = 0, farSideMae = 0, paperMae = 0,
         minSkill = 1;
  int cases = 0;
  void add(const AoComparison& c, double whiteMae) {
    mae += c.mae;
    ssim += c.ssim;
    pearson += c.pearson;
    haloMae += c.haloMae;
    interiorMae += c.interiorMae;
    nearSideMae += c.nearSideMae;
    farSideMae += c.farSideMae;
    minSkill = std::min(minSkill, whiteMae > 0 ? 1.0 - c.mae / whiteMae : 0.0);
    ++cases;
  }
  Score mean() const {
    Score s = *this;
    const double n = std::max(cases, 1);
    s.mae /= n;
    s.ssim /= n;
    s.pearson /= n;
    s.haloMae /= n;
    s.interiorMae /= n;
    s.nearSideMae /= n;
    s.farSideMae /= n;
    s.paperMae /= n;
    return s;
  }
};

// --- The fit -------------------------------------------------------------------------------------------------------

// The search runs over (ln(sigma k), beta, ln k), beta a fraction of the radius. Every estimator's visibility is
// max(0, 1 - sigma O)^k for its obscurance O; for large k it tends to exp(-sigma k O), so sigma and k trade against
// each other along sigma k = const. Searching ln(sigma k) and ln k separately keeps that valley axis-aligned, where
// Nelder-Mead walks it quickly.
// With --fit-thickness, GTAO with one layer also fits its occluders' thickness t (a fraction of r, the 4th
// coordinate, ln t): the assumed depth behind a tap's front, which trades halos around thin objects against open
// creases behind thick ones. Otherwise, and for the other rows, the search runs over the first three and t stays at
// 0.5 (the measured trade-off: docs/accuracy.md, "Thickness").
using Point = std::array<double, 4>;

// The box the search stays in: inside AoSettings' ranges (intensity 0 .. 20, contrast 0.1 .. 10, bias 0 .. 1 m), and
// narrower where that costs nothing: a bias beyond half the radius ignores nearly every occluder, and contrast stops
// at 5 because the fit runs up the sigma k = const valley towards exp(-sigma k S), where the error is flat (at
// r = 1 m, k = 10 instead of 5 lowered the mean MAE by 0.0001) while the default would pin the contrast control to
// the top of its range. The thickness stays within 0.05 .. 8 r: thinner is a hair, thicker a height field.
Point clampToBox(const Point& p) {
  const double lnK = std::clamp(p[2], std::log(0.2), std::log(5.0));
  const double lnSigmaK = std::clamp(p[0], std::log(0.05) + lnK, std::log(20.0) + lnK);
  return {lnSigmaK, std::clamp(p[1], 0.0, 0.5), lnK, std::clamp(p[3], std::log(0.05), std::log(8.0))};
}

EstimatorParameters toParameters(const Point& p) {
  const Point q = clampToBox(p);
  // Rounded to what the table stores, so the fitted figures are those of the written values.
  auto round4 = [](double v) { return static_cast<float>(std::round(v * 1e4) / 1e4); };
  return {round4(std::exp(q[0] - q[2])), round4(q[1]), round4(std::exp(q[2])), round4(std::exp(q[3]))};
}

Point fromParameters(const EstimatorParameters& e) {
  return clampToBox({std::log(e.intensity * e.contrast), e.bias, std::log(e.contrast), std::log(e.thickness)});
}

// Nelder-Mead over the first `dimensions` coordinates of Point (3 or 4); the others keep the start's values.
Point nelderMead(const std::function<double(const Point&)>& f, const Point& start, const Point& step,
                 int maxEvaluations, size_t dimensions) {
  const size_t n = dimensions;
  std::vector<Point> simplex(n + 1);
  std::vector<double> value(n + 1);
  int evaluations = 0;
  auto eval = [&](const Point& p) {
    ++evaluations;
    return f(clampToBox(p));
  };
  simplex[0] = clampToBox(start);
  for (size_t i = 0; i < n; ++i) {
    simplex[i + 1] = simplex[0];
    Point& vertex = simplex[i + 1];
    vertex[i] += step[i];
    // A vertex clamped back onto the start would make the simplex degenerate: step the other way instead.
    if (clampToBox(vertex) == simplex[0]) vertex[i] -= 2 * step[i];
    vertex = clampToBox(vertex);
  }
  for (size_t i = 0; i <= n; ++i) value[i] = eval(simplex[i]);
  while (evaluations < maxEvaluations) {
    std::vector<size_t> order(n + 1);
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return value[a] < value[b]; });
    const std::vector<Point> s = simplex;
    const std::vector<double> v = value;
    for (size_t i = 0; i <= n; ++i) {
      simplex[i] = s[order[i]];
      value[i] = v[order[i]];
    }
    if (value[n] - value[0] < 2e-5) break;  // spread below a tenth of a grey level of MAE: converged
    Point centroid = simplex[0];
    for (size_t d = 0; d < n; ++d) {
      centroid[d] = 0.0;
      for (size_t i = 0; i < n; ++i) centroid[d] += simplex[i][d] / static_cast<double>(n);
    }
    auto along = [&](double t) {
      Point p = centroid;
      for (size_t d = 0; d < n; ++d) p[d] = centroid[d] + t * (simplex[n][d] - centroid[d]);
      return clampToBox(p);
    };
    const Point reflected = along(-1.0);
    const double fr = eval(reflected);
    if (fr < value[0]) {
      const Point expanded = along(-2.0);
      const double fe = eval(expanded);
      if (fe < fr) {
        simplex[n] = expanded;
        value[n] = fe;
      } else {
        simplex[n] = reflected;
        value[n] = fr;
      }
    } else if (fr < value[n - 1]) {
      simplex[n] = reflected;
      value[n] = fr;
    } else {
      const bool outside = fr < value[n];
      const Point contracted = along(outside ? -0.5 : 0.5);
      const double fc = eval(contracted);
      if (fc < std::min(fr, value[n])) {
        simplex[n] = contracted;
        value[n] = fc;
      } else {
        for (size_t i = 1; i <= n; ++i) {
          for (size_t d = 0; d < n; ++d) simplex[i][d] = simplex[0][d] + 0.5 * (simplex[i][d] - simplex[0][d]);
          value[i] = eval(simplex[i]);
        }
      }
    }
  }
  return simplex[static_cast<size_t>(std::min_element(value.begin(), value.end()) - value.begin())];
}

AoSettings settingsFor(QualityPreset preset, int layers = 1) {
  AoSettings settings;
  settings.applyPreset(preset);
  settings.layers = layers;
  return settings;
}

AoSettings withParameters(AoSettings settings, const EstimatorParameters& e) {
  settings.intensity = e.intensity;
  settings.bias = e.bias;
  settings.contrast = e.contrast;
  settings.thickness = e.thickness;
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

// The C++ enumerator for a settings name: ("QualityPreset", "medium") -> "QualityPreset::Medium" (the enumerators
// are the names capitalised).
std::string enumeratorName(const char* type, std::string name) {
  name[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
  return std::string(type) + "::" + name;
}

std::string viewList(const TuningConfig& config) {
  std::string names;
  for (const ViewSpec& v : config.views) names += (names.empty() ? "" : ", ") + v.name;
  return names;
}

// The fit, per preset and knot j: the pixels whose projected radius lies nearest knot j (knotOf), over every case
// (view x radius), rendered with one (sigma, beta, k) everywhere; Nelder-Mead minimises their pixel-weighted MAE.
// Each pixel then interpolates the knots at its own radius in pixels (EstimatorKnots::interpolate). A knot with too
// few pixels over all cases copies its neighbour's fit.
// What --estimators and --presets keep (all when empty), for experiments on part of the table.
struct Selection {
  std::vector<AoEstimator> estimators;
  std::vector<QualityPreset> presets;
  bool has(AoEstimator e) const {
    return estimators.empty() || std::find(estimators.begin(), estimators.end(), e) != estimators.end();
  }
  bool has(QualityPreset p) const {
    return presets.empty() || std::find(presets.begin(), presets.end(), p) != presets.end();
  }
};

// `layers`: the rows fitted are those for that many depth layers (ao.layers), of the estimators that read them; every
// other row of the table is kept.
// `fitThickness` (--fit-thickness): GTAO's one-layer rows fit their thickness too (see Point).
void fit(std::vector<TuningCase>& cases, const TuningConfig& config, const Selection& selection, int layers,
         bool fitThickness, const std::string& tablePath) {
  constexpr size_t kMinCasePixels = 200, kMinKnotPixels = 2000;
  struct Row {
    AoEstimator estimator;
    const PresetInfo* preset;
    int layers;
    int knot;
    EstimatorParameters fitted;
    double mae = 0, paperMae = 0;
    size_t pixels = 0;
    bool kept = false;  // copied from the current table, not fitted
  };
  std::vector<Row> rows;
  const auto& presets = qualityPresets();
  // The default preset first: the others start from its result at the same knot.
  std::vector<const PresetInfo*> order;
  for (const PresetInfo& p : presets)
    if (p.preset == AoSettings{}.preset) order.push_back(&p);
  for (const PresetInfo& p : presets)
    if (p.preset != AoSettings{}.preset) order.push_back(&p);

  // Which pixels of which cases belong to each knot.
  struct Member {
    TuningCase* c;
    std::vector<std::uint32_t> pixels;
  };
  std::array<std::vector<Member>, kEstimatorKnots> members;
  std::array<size_t, kEstimatorKnots> knotPixels{};
  for (TuningCase& c : cases) {
    std::array<std::vector<std::uint32_t>, kEstimatorKnots> byKnot;
    for (size_t i = 0; i < c.radiusPixels.size(); ++i)
      if (c.view->mask[i])
        byKnot[static_cast<size_t>(knotOf(c.radiusPixels[i]))].push_back(static_cast<std::uint32_t>(i));
    for (size_t j = 0; j < byKnot.size(); ++j) {
      if (byKnot[j].size() < kMinCasePixels) continue;
      knotPixels[j] += byKnot[j].size();
      members[j].push_back({&c, std::move(byKnot[j])});
    }
  }
  auto knotMae = [&](int knot, const AoSettings& settings) {
    double sum = 0.0;
    size_t n = 0;
    for (const Member& m : members[static_cast<size_t>(knot)]) {
      AoSettings at = settings;
      at.radius = m.c->radius;
      const Image ao = renderAo(*m.c->view, at);
      for (std::uint32_t i : m.pixels) sum += std::abs(ao.rgba[i * 4] / 255.0 - m.c->reference.values[i]);
      n += m.pixels.size();
    }
    return n ? sum / static_cast<double>(n) : 0.0;
  };

  // Not fitted this time: the rows the core has now are kept, so a partial fit can extend the table.
  for (AoEstimator estimator : allAoEstimators())
    for (const PresetInfo& preset : presets)
      for (int kept = 1; kept <= 2; ++kept) {
        const bool fitting = kept == layers && selection.has(estimator) && selection.has(preset.preset) &&
                             (layers == 1 || estimatorReadsSecondLayer(estimator));
        if (fitting || !hasTunedEstimatorKnots(estimator, preset.preset, kept)) continue;
        const EstimatorKnots knots = tunedEstimatorKnots(estimator, preset.preset, kept);
        for (int knot = 0; knot < kEstimatorKnots; ++knot) {
          Row row{estimator, &preset, kept, knot, knots.at[knot]};
          row.kept = true;
          rows.push_back(row);
        }
      }
  for (AoEstimator estimator : allAoEstimators()) {
    if (!selection.has(estimator) || (layers == 2 && !estimatorReadsSecondLayer(estimator))) continue;
    std::map<int, EstimatorParameters> leader;
    for (const PresetInfo* preset : order) {
      if (!selection.has(preset->preset)) continue;
      AoSettings base = settingsFor(preset->preset, layers);
      base.estimator = estimator;
      std::map<int, Row> fitted;
      for (int knot = 0; knot < kEstimatorKnots; ++knot) {
        if (knotPixels[static_cast<size_t>(knot)] < kMinKnotPixels) continue;
        const bool first = leader.count(knot) == 0;
        EstimatorParameters start = kPaperEstimatorParameters;
        if (!first)
          start = leader[knot];
        else if (fitted.count(knot - 1))
          start = fitted[knot - 1].fitted;
        int evaluations = 0;
        auto objective = [&](const Point& p) {
          ++evaluations;
          return knotMae(knot, withParameters(base, toParameters(p)));
        };
        const auto begin = std::chrono::steady_clock::now();
        const Point step = first ? Point{0.4, 0.05, 0.4, 0.5} : Point{0.15, 0.02, 0.15, 0.2};
        // A fourth coordinate needs about a third more evaluations to converge as far.
        const size_t dimensions = fitThickness && estimator == AoEstimator::Gtao && layers == 1 ? 4 : 3;
        const int budget = (first ? config.evaluations : config.followEvaluations) * static_cast<int>(dimensions) / 3;
        const Point best = nelderMead(objective, fromParameters(start), step, budget, dimensions);
        Row row{estimator, preset, layers, knot, toParameters(best)};
        row.mae = knotMae(knot, withParameters(base, row.fitted));
        row.paperMae = knotMae(knot, withParameters(base, kPaperEstimatorParameters));
        row.pixels = knotPixels[static_cast<size_t>(knot)];
        std::printf(
            "  %-4s %-6s %d layer%s h = %3.0f px sigma %.3f beta %.4f k %.3f t %.3f | MAE %.4f | paper MAE %.4f | "
            "%zu px in %zu cases, %d renders each, %.0f s\n",
            estimatorName(estimator), preset->name, layers, layers == 1 ? "" : "s",
            static_cast<double>(estimatorKnotPixels(knot)),
            static_cast<double>(row.fitted.intensity), static_cast<double>(row.fitted.bias),
            static_cast<double>(row.fitted.contrast), static_cast<double>(row.fitted.thickness), row.mae,
            row.paperMae, row.pixels,
            members[static_cast<size_t>(knot)].size(), evaluations,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count());
        std::fflush(stdout);
        if (first) leader[knot] = row.fitted;
        fitted[knot] = row;
      }
      if (fitted.empty()) throw InputError("no knot has enough pixels: add views or radius factors");
      for (int knot = 0; knot < kEstimatorKnots; ++knot) {
        Row row;
        if (fitted.count(knot)) {
          row = fitted[knot];
        } else {  // the nearest fitted knot's values
          int nearest = fitted.begin()->first;
          for (const auto& [k, r] : fitted)
            if (std::abs(k - knot) < std::abs(nearest - knot)) nearest = k;
          row = fitted[nearest];
          row.knot = knot;
          row.pixels = 0;
        }
        rows.push_back(row);
      }
    }
  }

  // The table's lines now on disk, by their key (everything up to the parameters' brace).
  std::map<std::string, std::string> existingRows;
  {
    std::ifstream existing(tablePath);
    for (std::string line; std::getline(existing, line);) {
      const size_t brace = line.find(", {");
      if (line.rfind("{AoEstimator::", 0) == 0 && brace != std::string::npos)
        existingRows[line.substr(0, brace + 3)] = line;
    }
  }
  // Rows grouped by preset in qualityPresets() order, knots increasing, as tunedEstimatorKnots expects.
  std::ostringstream out;
  out << "// Generated by tools/tune-defaults.sh (obscura-tune --fit): do not edit by hand.\n"
      << "// Each estimator's intensity sigma, bias beta (a fraction of the radius) and contrast k per quality preset, "
         "at\n"
      << "// knots of"
      << " the projected radius in pixels (AoSettings.h), fitted to the ray-traced reference (obscura-reference,\n"
      << "// " << config.rays << " rays per pixel) at " << config.width << "x" << config.height
      << ": per knot, the MAE of the blurred AO over the pixels whose\n"
      << "// radius in pixels lies nearest it, across the views of tools/tuning-views.json at radii of";
  for (float f : config.radiusFactors) out << " " << radiusText(f);
  out << "\n// times each view's object size: " << viewList(config) << ".\n"
      << "// docs/accuracy.md explains the procedure.\n"
      << "// The rows for ao.layers 2 (estimators that read a second depth layer) are fitted with it.\n"
      << "// {estimator, preset, depth layers, radius in pixels (knot), {intensity sigma, bias beta (fraction of r), "
         "contrast k,\n"
      << "// thickness t (fraction of r; fitted for GTAO with one layer by --fit-thickness, else 0.5; unused "
         "elsewhere)}},\n"
      << "//   fitted | SAO paper's values\n";
  for (AoEstimator estimator : allAoEstimators()) {
    for (const PresetInfo& preset : presets) {
      for (int rowLayers = 1; rowLayers <= 2; ++rowLayers) {
      for (const Row& row : rows) {
        if (row.preset != &preset || row.estimator != estimator || row.layers != rowLayers) continue;
        std::ostringstream key;
        key << "{" << enumeratorName("AoEstimator", estimatorName(estimator)) << ", "
            << enumeratorName("QualityPreset", preset.name) << ", " << row.layers << ", "
            << floatLiteral(estimatorKnotPixels(row.knot)) << ", {";
        // A row not fitted in this run keeps the file's line as it is (its values and its fit's comment): the file
        // may be newer than the table this binary was built with (tools/tune-defaults.sh fits two runs in a row).
        if (row.kept && existingRows.count(key.str())) {
          out << existingRows.at(key.str()) << "\n";
          continue;
        }
        char comment[160];
        if (row.kept)
          std::snprintf(comment, sizeof comment, "  // kept from the previous table (not fitted in this run)");
        else if (row.pixels)
          std::snprintf(comment, sizeof comment, "  // MAE %.4f | paper MAE %.4f, %zu px", row.mae, row.paperMae,
                        row.pixels);
        else
          std::snprintf(comment, sizeof comment, "  // too few pixels: the nearest fitted knot's values");
        out << key.str() << floatLiteral(row.fitted.intensity) << ", "
            << floatLiteral(row.fitted.bias) << ", " << floatLiteral(row.fitted.contrast) << ", "
            << floatLiteral(row.fitted.thickness) << "}}," << comment << "\n";
      }
      }
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

std::string passFail(bool met) { return met ? "met" : "**not met**"; }

// Issue 30's targets over the cases at the default settings, each with the figure reached: the report's table and
// --evaluate's lines. With two depth layers (`againstOneLayer`: the largest increase of any case's MAE over the same
// case with one layer), the halo target is 1.05 and no case may be worse than with one layer by more than 0.005.
struct TargetCheck {
  const char* figure;
  const char* target;
  std::string reached;
  bool met;
};

std::vector<TargetCheck> targetChecks(const Score& s, std::optional<double> againstOneLayer = std::nullopt) {
  const double haloRatio = s.haloMae / std::max(s.interiorMae, 1e-9);
  std::vector<TargetCheck> checks = {
      {"mean Pearson correlation", ">= 0.90", format("%.3f", s.pearson), s.pearson >= 0.90},
      {"mean MAE", "<= 0.040", format("%.4f", s.mae), s.mae <= 0.040},
      againstOneLayer ? TargetCheck{"halo MAE / interior MAE", "<= 1.05", format("%.2f", haloRatio), haloRatio <= 1.05}
                      : TargetCheck{"halo MAE / interior MAE", "<= 1.15", format("%.2f", haloRatio), haloRatio <= 1.15},
      {"lowest skill of any case", ">= 0.3", format("%.2f", s.minSkill), s.minSkill >= 0.3}};
  if (againstOneLayer)
    checks.push_back({"largest MAE increase of a case over one layer", "<= 0.005", format("%+.4f", *againstOneLayer),
                      *againstOneLayer <= 0.005});
  return checks;
}

// --guard-band F: what a guard band (Gravas 2013, sec. 2.3.3.1: G-buffer pixels beyond the frame, so that taps near
// its edges find geometry) would gain. Each view is rendered with the same eye and centre but a field of view and an
// image F times larger in each direction (the frame in its middle, pixel for pixel the same rays), and the middle is
// compared with the reference; the screen-space clamp is scaled back so only the extra pixels differ. Prints the
// mean figures without and with the band, per radius factor.
void guardBandStudy(std::vector<TuningCase>& cases, const HeadlessContext& context, float factor) {
  const AoSettings defaults;
  for (AoEstimator estimator : allAoEstimators()) {
    Score plain, banded;
    std::map<float, std::pair<Score, Score>> byFactor;
    for (TuningCase& c : cases) {
      TuningView& view = *c.view;
      AoSettings settings = defaults;
      settings.estimator = estimator;
      settings.radius = c.radius;
      const AoComparison without =
          compareAo(c.reference, GreyImage::fromRed(renderAo(view, settings)), view.mask, view.haloBand, false);
      Camera wide = view.camera;
      const int bandX = static_cast<int>(std::lround(0.5f * (factor - 1.0f) * static_cast<float>(view.camera.width)));
      const int bandY = static_cast<int>(std::lround(0.5f * (factor - 1.0f) * static_cast<float>(view.camera.height)));
      wide.width = view.camera.width + 2 * bandX;
      wide.height = view.camera.height + 2 * bandY;
      wide.fovyDegrees = glm::degrees(2.0f * std::atan(std::tan(0.5f * view.camera.fovyRadians()) *
                                                        static_cast<float>(wide.height) /
                                                        static_cast<float>(view.camera.height)));
      wide.ymag = view.camera.ymag * static_cast<float>(wide.height) / static_cast<float>(view.camera.height);
      AoSettings wideSettings = settings;
      wideSettings.maxScreenRadius =
          settings.maxScreenRadius * static_cast<float>(view.camera.height) / static_cast<float>(wide.height);
      gl::RenderTarget target("guard band", wide.width, wide.height, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                              context.caps().depth24);
      view.renderer->render(wide, wideSettings, obscura::View::Ao,
                            OutputTarget{target.framebuffer(), wide.width, wide.height, {}});
      const std::vector<std::uint8_t> rgba = target.readRgba();
      Image middle{view.camera.width, view.camera.height,
                   std::vector<std::uint8_t>(static_cast<size_t>(view.camera.width * view.camera.height) * 4)};
      for (int y = 0; y < view.camera.height; ++y)
        std::copy_n(&rgba[(static_cast<size_t>(y + bandY) * static_cast<size_t>(wide.width) + bandX) * 4],
                    view.camera.width * 4, &middle.rgba[static_cast<size_t>(y) * view.camera.width * 4]);
      const AoComparison with = compareAo(c.reference, GreyImage::fromRed(middle), view.mask, view.haloBand, false);
      plain.add(without, c.whiteMae);
      banded.add(with, c.whiteMae);
      byFactor[c.factor].first.add(without, c.whiteMae);
      byFactor[c.factor].second.add(with, c.whiteMae);
    }
    const Score a = plain.mean(), b = banded.mean();
    std::printf("%-5s guard band x%.2f: MAE %.4f -> %.4f, Pearson %.3f -> %.3f |", estimatorName(estimator),
                static_cast<double>(factor), a.mae, b.mae, a.pearson, b.pearson);
    for (const auto& [f, pair] : byFactor)
      std::printf(" r %sx: %.4f -> %.4f", radiusText(f).c_str(), pair.first.mean().mae, pair.second.mean().mae);
    std::printf("\n");
  }
}

// --evaluate: the figures for each selected estimator and preset (default: the default preset), with the
// table's parameters, at `layers` depth layers, on stdout, and for the defaults each target beside the figure
// reached; with two layers, each case against one layer too. Quick (no SSIM): for trying a change to an estimator
// before fitting everything. `perCase`: a line per case as well.
void evaluate(std::vector<TuningCase>& cases, const Selection& selection, bool perCase, int layers) {
  for (AoEstimator estimator : allAoEstimators()) {
    if (!selection.has(estimator)) continue;
    for (const PresetInfo& preset : qualityPresets()) {
      if (selection.presets.empty() ? preset.preset != AoSettings{}.preset : !selection.has(preset.preset)) continue;
      AoSettings settings = settingsFor(preset.preset, layers);
      settings.estimator = estimator;
      const bool compared = settings.layersRead() == 2;
      AoSettings oneLayer = settings;
      oneLayer.layers = 1;
      Score score;
      std::map<float, Score> byFactor;
      double worstIncrease = -1.0;
      for (TuningCase& c : cases) {
        const AoComparison m = measure(c, settings, false);
        score.add(m, c.whiteMae);
        byFactor[c.factor].add(m, c.whiteMae);
        double increase = 0.0;
        if (compared) {
          increase = m.mae - measure(c, oneLayer, false).mae;
          worstIncrease = std::max(worstIncrease, increase);
        }
        if (perCase)
          std::printf("  %-16s r %-4sx MAE %.4f halo %.4f (near %.4f far %.4f bias %+.4f) interior %.4f bias %+.4f "
                      "Pearson %.3f skill %.2f%s\n",
                      c.view->spec.name.c_str(), radiusText(c.factor).c_str(), m.mae, m.haloMae, m.nearSideMae,
                      m.farSideMae, m.haloBias, m.interiorMae, m.bias, m.pearson,
                      1.0 - m.mae / std::max(c.whiteMae, 1e-9),
                      compared ? format(" | against one layer %+.4f", increase).c_str() : "");
      }
      const Score s = score.mean();
      std::printf("%-5s %-6s %d layer%s MAE %.4f Pearson %.3f halo/interior %.2f (near side %.2f, far side %.2f) "
                  "lowest skill %.2f |",
                  estimatorName(estimator), preset.name, settings.layersRead(), settings.layersRead() == 1 ? "" : "s",
                  s.mae, s.pearson, s.haloMae / std::max(s.interiorMae, 1e-9),
                  s.nearSideMae / std::max(s.interiorMae, 1e-9), s.farSideMae / std::max(s.interiorMae, 1e-9),
                  s.minSkill);
      for (const auto& [factor, f] : byFactor)
        std::printf(" r %sx: %.4f/%.3f", radiusText(factor).c_str(), f.mean().mae, f.mean().pearson);
      std::printf("\n");
      if (estimator != AoSettings{}.estimator || preset.preset != AoSettings{}.preset) continue;
      std::printf("      targets (issue 30), the defaults%s:", compared ? " with ao.layers 2" : "");
      for (const TargetCheck& t : targetChecks(s, compared ? std::optional<double>(worstIncrease) : std::nullopt))
        std::printf(" %s %s: %s %s;", t.figure, t.target, t.reached.c_str(), t.met ? "met" : "NOT MET");
      std::printf("\n");
    }
  }
}

// The AO passes' milliseconds in the browser per estimator and preset, as tools/browser-bench/estimator-costs.mjs
// writes them (estimator,preset,width,height,ao_ms,frame_ms): a C++ tool cannot drive a browser, so the report
// reads what the script measured.
struct BrowserCosts {
  std::map<std::pair<AoEstimator, QualityPreset>, double> aoMs;
  std::string size;  // "WxH", the page's size they were measured at
};

BrowserCosts loadBrowserCosts(const std::string& path) {
  BrowserCosts costs;
  if (path.empty()) return costs;
  std::ifstream file(path);
  if (!file) throw InputError(path + ": cannot open the browser costs (tools/browser-bench/estimator-costs.mjs)");
  std::string line;
  if (!std::getline(file, line) || line.rfind("estimator,preset,width,height,ao_ms", 0) != 0)
    throw InputError(path + ": expected the header estimator,preset,width,height,ao_ms,frame_ms");
  while (std::getline(file, line)) {
    if (line.empty()) continue;
    std::stringstream row(line);
    std::vector<std::string> fields;
    for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
    if (fields.size() < 5) throw InputError(path + ": short row '" + line + "'");
    costs.aoMs[{parseEstimator(fields[0]), parsePreset(fields[1])}] = parseNumber(path, fields[4], 0.0, 1e6);
    costs.size = fields[2] + "x" + fields[3];
  }
  return costs;
}

void report(std::vector<TuningCase>& cases, std::vector<TuningView>& views, const TuningConfig& config,
            const std::string& docPath, const std::string& imageDir, const HeadlessContext& context,
            const BrowserCosts& browser) {
  std::ostringstream md;
  md << "Generated by `tools/tune-defaults.sh` (`obscura-tune --report`) on " << context.caps().renderer << ", "
     << config.width << "x" << config.height << ", reference " << config.rays << " rays per pixel, " << views.size()
     << " views at radii of";
  for (float f : config.radiusFactors) md << " " << radiusText(f);
  md << " times each view's object size (" << cases.size() << " cases). Errors are in AO units (0 = black, "
     << "1 = white) over geometry pixels; *halo* is the MAE within 4 pixels of a depth discontinuity, *interior* the "
     << "MAE elsewhere; *skill* is 1 - MAE / (MAE of an all-white image); *AO ms* is the median time of the AO passes "
     << "(everything but the G-buffer and the composite), glFinish-bounded.\n\n";

  const AoSettings defaults;
  std::map<std::pair<AoEstimator, QualityPreset>, Score> byEstimator;
  std::map<std::pair<AoEstimator, QualityPreset>, std::vector<double>> milliseconds;  // at the report factor
  std::map<float, Score> byFactor, byFactorTwoLayers;  // default estimator and preset
  // ao.layers 2, for the estimators that read a second layer: the scores, each case's MAE increase over one layer
  // (the largest of them), and the AO's milliseconds.
  std::map<std::pair<AoEstimator, QualityPreset>, Score> twoLayers;
  std::map<std::pair<AoEstimator, QualityPreset>, double> worstIncrease;
  std::map<std::pair<AoEstimator, QualityPreset>, std::vector<double>> twoLayerMilliseconds;
  for (TuningCase& c : cases) {
    for (AoEstimator estimator : allAoEstimators()) {
      for (const PresetInfo& preset : qualityPresets()) {
        AoSettings tuned = settingsFor(preset.preset);
        tuned.estimator = estimator;
        const AoComparison m = measure(c, tuned);
        Score& s = byEstimator[{estimator, preset.preset}];
        s.add(m, c.whiteMae);
        s.paperMae += measure(c, withParameters(tuned, kPaperEstimatorParameters), false).mae;
        const bool defaultRow = estimator == defaults.estimator && preset.preset == defaults.preset;
        if (defaultRow) byFactor[c.factor].add(m, c.whiteMae);
        AoSettings layered = settingsFor(preset.preset, 2);
        layered.estimator = estimator;
        const bool layers = estimatorReadsSecondLayer(estimator);
        if (layers) {
          const AoComparison m2 = measure(c, layered);
          twoLayers[{estimator, preset.preset}].add(m2, c.whiteMae);
          double& worst = worstIncrease.try_emplace({estimator, preset.preset}, -1.0).first->second;
          worst = std::max(worst, m2.mae - m.mae);
          if (defaultRow) byFactorTwoLayers[c.factor].add(m2, c.whiteMae);
        }
        if (c.factor == config.reportFactor) {
          tuned.radius = layered.radius = c.radius;
          milliseconds[{estimator, preset.preset}].push_back(aoMilliseconds(*c.view, tuned));
          if (layers) twoLayerMilliseconds[{estimator, preset.preset}].push_back(aoMilliseconds(*c.view, layered));
        }
      }
    }
  }
  auto meanOf = [](const std::vector<double>& values) {
    double mean = 0.0;
    for (double v : values) mean += v / static_cast<double>(std::max<size_t>(values.size(), 1));
    return mean;
  };
  const std::pair<AoEstimator, QualityPreset> defaultRow{defaults.estimator, defaults.preset};
  md << "### Targets (issue 30), " << estimatorName(defaults.estimator) << " (the default estimator), preset "
     << presetName(defaults.preset) << ", mean over the " << cases.size() << " cases\n\n"
     << "| figure | target | reached | |\n|---|---|---|---|\n";
  for (const TargetCheck& t : targetChecks(byEstimator[defaultRow].mean()))
    md << "| " << t.figure << " | " << t.target << " | " << t.reached << " | " << passFail(t.met) << " |\n";
  md << "\n";
  if (twoLayers.count(defaultRow)) {
    md << "### Targets (issue 30) with `ao.layers 2`, " << estimatorName(defaults.estimator) << ", preset "
       << presetName(defaults.preset) << "\n\n"
       << "| figure | target | reached | |\n|---|---|---|---|\n";
    for (const TargetCheck& t : targetChecks(twoLayers[defaultRow].mean(), worstIncrease[defaultRow]))
      md << "| " << t.figure << " | " << t.target << " | " << t.reached << " | " << passFail(t.met) << " |\n";
    md << "\n### Two depth layers (`ao.layers 2`) against one, each preset, mean over the cases\n\n"
       << "*Largest increase*: the largest MAE increase of any case over the same case with one layer. *AO ms*: as "
       << "below (the peel pass included).\n\n"
       << "| estimator | preset | layers | MAE | SSIM | Pearson | halo / interior | lowest skill | largest increase | "
          "AO ms |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& [key, score] : twoLayers) {
      for (int layers = 1; layers <= 2; ++layers) {
        const Score sc = (layers == 1 ? byEstimator[key] : score).mean();
        md << "| " << estimatorName(key.first) << " | " << presetName(key.second) << " | " << layers << " | "
           << format("%.4f", sc.mae) << " | " << format("%.3f", sc.ssim) << " | " << format("%.3f", sc.pearson)
           << " | " << format("%.2f", sc.haloMae / std::max(sc.interiorMae, 1e-9)) << " | "
           << format("%.2f", sc.minSkill) << " | "
           << (layers == 1 ? std::string("-") : format("%+.4f", worstIncrease[key])) << " | "
           << format("%.1f", meanOf(layers == 1 ? milliseconds[key] : twoLayerMilliseconds[key])) << " |\n";
      }
    }
    md << "\n";
  }

  md << "### Each estimator and preset, mean over the cases\n\n"
     << "*AO ms*: natively, the mean over the views at " << radiusText(config.reportFactor)
     << " object size of the median AO time, on this machine at " << config.width << "x" << config.height << "; "
     << (browser.aoMs.empty()
             ? std::string("in the browser: not measured (run tools/browser-bench/estimator-costs.mjs, then "
                           "obscura-tune --report with --browser-ms)")
             : "in the browser, the GPU time of the AO passes (timer queries) of the demo page at " + browser.size +
                   " on 2CylinderEngine.glb at its default radius (tools/browser-bench/estimator-costs.mjs)")
     << "; docs/benchmarks.md has both at 1280x720 natively and the whole frame in the browser.\n\n"
     << "| estimator | preset | MAE | SSIM | Pearson | halo MAE | interior MAE | halo / interior | lowest skill | "
        "AO ms | browser AO ms | MAE, paper's sigma/beta/k |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (AoEstimator estimator : allAoEstimators()) {
    for (const PresetInfo& preset : qualityPresets()) {
      const Score s = byEstimator[{estimator, preset.preset}].mean();
      const double meanMs = meanOf(milliseconds[{estimator, preset.preset}]);
      md << "| " << estimatorName(estimator) << " | " << preset.name << " | " << format("%.4f", s.mae) << " | "
         << format("%.3f", s.ssim) << " | " << format("%.3f", s.pearson) << " | " << format("%.4f", s.haloMae)
         << " | " << format("%.4f", s.interiorMae) << " | " << format("%.2f", s.haloMae / std::max(s.interiorMae, 1e-9))
         << " | " << format("%.2f", s.minSkill) << " | " << format("%.1f", meanMs) << " | ";
      const auto inBrowser = browser.aoMs.find({estimator, preset.preset});
      md << (inBrowser == browser.aoMs.end() ? std::string("-") : format("%.1f", inBrowser->second)) << " | "
         << format("%.4f", s.paperMae) << " |\n";
    }
  }

  md << "\n### Each radius (in object sizes), " << estimatorName(defaults.estimator) << ", preset "
     << presetName(defaults.preset) << ", mean over the views\n\n"
     << "| radius / object size | MAE | SSIM | Pearson | halo MAE | interior MAE | lowest skill | MAE, 2 layers | "
        "halo / interior, 2 layers |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [factor, score] : byFactor) {
    const Score s = score.mean();
    md << "| " << radiusText(factor) << " | " << format("%.4f", s.mae) << " | " << format("%.3f", s.ssim) << " | "
       << format("%.3f", s.pearson) << " | " << format("%.4f", s.haloMae) << " | " << format("%.4f", s.interiorMae)
       << " | " << format("%.2f", s.minSkill) << " | ";
    if (byFactorTwoLayers.count(factor)) {
      const Score two = byFactorTwoLayers[factor].mean();
      md << format("%.4f", two.mae) << " | " << format("%.2f", two.haloMae / std::max(two.interiorMae, 1e-9))
         << " |\n";
    } else {
      md << "- | - |\n";
    }
  }

  md << "\n### Each view at " << radiusText(config.reportFactor) << " object size, "
     << estimatorName(defaults.estimator) << ", preset " << presetName(defaults.preset) << "\n\n"
     << "| view | r (scene units) | MAE | RMSE | SSIM | Pearson | halo MAE | interior MAE | bias | skill | AO ms | "
        "MAE, "
        "paper's sigma/beta/k |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (TuningCase& c : cases) {
    if (c.factor != config.reportFactor) continue;
    const AoSettings tuned = settingsFor(defaults.preset);
    const AoComparison m = measure(c, tuned);
    const AoComparison paper = measure(c, withParameters(tuned, kPaperEstimatorParameters), false);
    AoSettings timed = tuned;
    timed.radius = c.radius;
    const double ms = aoMilliseconds(*c.view, timed);
    md << "| " << c.view->spec.name << " | " << radiusText(c.radius) << " | " << format("%.4f", m.mae) << " | "
       << format("%.4f", m.rmse) << " | " << format("%.3f", m.ssim) << " | " << format("%.3f", m.pearson) << " | "
       << format("%.4f", m.haloMae) << " | " << format("%.4f", m.interiorMae) << " | " << format("%+.4f", m.bias)
       << " | " << format("%.2f", 1.0 - m.mae / std::max(c.whiteMae, 1e-9)) << " | " << format("%.1f", ms) << " | "
       << format("%.4f", paper.mae) << " |\n";
  }

  md << "\n### The fitted knots, " << estimatorName(defaults.estimator) << ", preset " << presetName(defaults.preset)
     << "\n\n"
     << "| radius in pixels | sigma | beta (fraction of r) | k |\n|---|---|---|---|\n";
  const EstimatorKnots knots = tunedEstimatorKnots(defaults.estimator, defaults.preset);
  for (int j = 0; j < kEstimatorKnots; ++j)
    md << "| " << radiusText(estimatorKnotPixels(j)) << " | " << format("%.3f", knots.at[j].intensity) << " | "
       << format("%.4f", knots.at[j].bias) << " | " << format("%.3f", knots.at[j].contrast) << " |\n";

  md << "\n### Reference | " << estimatorName(defaults.estimator) << " | difference\n\nPreset "
     << presetName(defaults.preset) << ", r = " << radiusText(config.reportFactor)
     << " object size, tuned parameters. Difference: red where the AO is darker than the reference, blue where "
     << "lighter, full colour at 0.25; grey: background.\n\n";
  fs::create_directories(imageDir);
  const fs::path docDir = fs::path(docPath).parent_path();
  for (TuningCase& c : cases) {
    if (c.factor != config.reportFactor) continue;
    AoSettings tuned = settingsFor(defaults.preset);
    tuned.radius = c.radius;
    const Image sao = renderAo(*c.view, tuned);
    const Image diff = differenceImage(c.reference, GreyImage::fromRed(sao), c.view->mask);
    const std::string& name = c.view->spec.name;
    const fs::path file = fs::path(imageDir) / ("accuracy-" + name + ".png");
    writePng(file.string(), sideBySide({c.referenceAo, sao, diff}));
    md << "**" << name << "** (r = " << radiusText(c.radius) << ")\n\n![" << name << ": reference | AO | difference]("
       << fs::relative(file, docDir.empty() ? fs::path(".") : docDir).generic_string() << ")\n\n";
  }

  // Replace the generated part of the document, between the markers, keeping the prose around it.
  const std::string section = config.reportSection.empty() ? "" : config.reportSection + ":";
  const std::string begin = "<!-- obscura-tune:" + section + "begin -->";
  const std::string end = "<!-- obscura-tune:" + section + "end -->";
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
  return "usage: obscura-tune [--views FILE] [--cache DIR] [--fit TABLE.inc [--fit-thickness] |\n"
         "                    --report DOC.md --images DIR\n"
         "                    [--browser-ms CSV] | --evaluate [--cases] | --guard-band F] [--estimators LIST]\n"
         "                    [--presets LIST] [--layers N] [--set NAME=VALUE ...]\n"
         "                    [--threads N] [--backend osmesa|egl]\n"
         "\n"
         "Fits each estimator's intensity, bias and contrast per preset and radius in pixels to the ray-traced\n"
         "reference (--fit), or measures the current defaults against it and writes the accuracy report\n"
         "(--report). tools/tune-defaults.sh runs both.\n"
         "  --views FILE   the views, radii and sizes (default tools/tuning-views.json)\n"
         "  --cache DIR    where reference images are kept between runs (default build/tuning-cache)\n"
         "  --fit FILE     write the fitted table (src/effects/ao/TunedDefaults.inc)\n"
         "  --fit-thickness  with --fit: GTAO's one-layer rows fit ao.thickness too (else 0.5; docs/accuracy.md,\n"
         "                 \"Thickness\", says why it is not fitted by default)\n"
         "  --report FILE  rewrite the generated part of FILE (docs/accuracy.md)\n"
         "  --images DIR   where the report's pictures go (default docs/images)\n"
         "  --browser-ms F the browser's AO milliseconds for the report's estimator table (the CSV of\n"
         "                 tools/browser-bench/estimator-costs.mjs)\n"
         "  --evaluate     print the mean figures of the current table's defaults (quick; for experiments)\n"
         "  --cases        with --evaluate: a line per case too\n"
         "  --layers N     1 (default) or 2: fit or evaluate with ao.layers N (--fit writes the rows for N layers\n"
         "                 of the estimators that read them, keeping the others; --evaluate compares every case\n"
         "                 with one layer)\n"
         "  --set NAME=V   a parameter every render takes (e.g. gbuffer.normals=reconstructed), repeatable\n"
         "  --guard-band F what a guard band would gain: the frame rendered F times larger, its middle compared\n"
         "  --estimators LIST, --presets LIST   comma-separated: fit or evaluate only these (e.g. gtao; medium)\n"
         "  --threads N    ray-tracing threads (default: the number of cores)\n"
         "  --backend B    osmesa (default) or egl\n";
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string viewsPath = "tools/tuning-views.json", cache = "build/tuning-cache", tablePath, docPath,
                imageDir = "docs/images", browserCostsPath;
    int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    HeadlessBackend backend = HeadlessBackend::OSMesa;
    bool evaluateOnly = false, perCase = false, fitThickness = false;
    int layers = 1;
    float guardBand = 0.0f;
    Selection selection;
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
      else if (arg == "--browser-ms") browserCostsPath = value();
      else if (arg == "--threads") threads = parseCount(arg, value(), 256);
      else if (arg == "--backend") backend = parseBackend(value());
      else if (arg == "--evaluate") evaluateOnly = true;
      else if (arg == "--cases") perCase = true;
      else if (arg == "--fit-thickness") fitThickness = true;
      else if (arg == "--layers") layers = parseCount(arg, value(), 2);
      else if (arg == "--set") {
        const std::string& assignment = value();
        const size_t equals = assignment.find('=');
        if (equals == std::string::npos) throw InputError("--set: expected NAME=VALUE, got '" + assignment + "'");
        const std::string name = assignment.substr(0, equals), setting = assignment.substr(equals + 1);
        RenderSettings().set(name, setting);  // fails now, naming the parameter, rather than at the first render
        frameOverrides().emplace_back(name, setting);
      }
      else if (arg == "--guard-band") {
        guardBand = parseNumber(arg, value(), 1.01, 2.0);
        evaluateOnly = true;
      }
      else if (arg == "--estimators" || arg == "--presets") {
        std::stringstream list(value());
        for (std::string name; std::getline(list, name, ',');) {
          if (arg == "--presets") selection.presets.push_back(parsePreset(name));
          else selection.estimators.push_back(parseEstimator(name));
        }
      }
      else throw InputError("unknown option '" + arg + "' (see --help)");
    }
    if (tablePath.empty() + docPath.empty() + !evaluateOnly != 2)
      throw InputError("expected exactly one of --fit, --report and --evaluate");
    const TuningConfig config = loadConfig(viewsPath);
    const BrowserCosts browserCosts = loadBrowserCosts(browserCostsPath);

    const auto start = std::chrono::steady_clock::now();
    HeadlessContext context(backend);
    std::vector<TuningView> views(config.views.size());
    std::printf("obscura-tune: %zu views at %dx%d, radii", views.size(), config.width, config.height);
    for (float f : config.radiusFactors) std::printf(" %s", radiusText(f).c_str());
    std::printf(" x object size; references in %s\n", cache.c_str());
    std::vector<TuningCase> cases;
    for (size_t i = 0; i < views.size(); ++i) {
      TuningView& view = views[i];
      view.spec = config.views[i];
      SceneInput::Loaded input = view.spec.input.load();
      view.spec.input.printWarnings("obscura-tune", input.warnings);
      Scene scene = std::move(input.scene);
      if (view.spec.input.scenePath.empty()) {
        // The built-in views measure the still room (no pendulum, no limb), whatever SceneInput's default: the scene
        // the tuned defaults were fitted on and docs/accuracy.md's figures measured on (scene/BuiltinScene.h).
        scene = makeBuiltinScene(BuiltinSceneOptions::still());
        if (view.spec.input.sceneScale != 1.0f) scaleScene(scene, view.spec.input.sceneScale);
      }
      view.camera = input.camera;
      for (TuningCase& c : loadReferences(view, scene, config, cache, threads)) cases.push_back(std::move(c));
      view.renderer = std::make_unique<Renderer>(context.caps());
      view.renderer->setScene(scene);
      view.output = std::make_unique<gl::RenderTarget>("tuning output", view.camera.width, view.camera.height,
                                                       GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                                       context.caps().depth24);
    }
    if (guardBand > 0.0f) guardBandStudy(cases, context, guardBand);
    else if (evaluateOnly) evaluate(cases, selection, perCase, layers);
    else if (!tablePath.empty()) fit(cases, config, selection, layers, fitThickness, tablePath);
    else report(cases, views, config, docPath, imageDir, context, browserCosts);
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
