// obscura-tune: fits SAO's intensity sigma, bias beta and contrast k, per quality preset and radius in pixels, so
// that its blurred AO best matches the ray-traced reference at the same radius over a set of views (each at several
// radii, multiples of a typical object's size in that scene's units); writes the fitted table
// the core reads (src/core/TunedDefaults.inc), and the accuracy report (docs/accuracy.md and its images).
// tools/tune-defaults.sh runs the whole procedure; see docs/accuracy.md.
//
//   obscura-tune --views tools/tuning-views.json --fit src/core/TunedDefaults.inc
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
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "apps/SceneInput.h"
#include "core/AoSettings.h"
#include "base/Error.h"
#include "core/FrameContext.h"
#include "core/LinearDepthPacking.h"
#include "core/SaoKernel.h"
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
  float objectSize = 1.0f;  // a typical object's size in the scene's units: the radii are multiples of it
};

struct TuningConfig {
  int width = 480, height = 270;
  int rays = 256;
  std::vector<float> radiusFactors;  // each view is measured at these multiples of its object size
  float reportFactor = 1.0f;         // the one the per-view tables and pictures show
  int evaluations = 40;         // Nelder-Mead budget for the first preset fitted at each knot
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
    config.radiusFactors = json.at("radius_factors").get<std::vector<float>>();
    config.reportFactor = json.value("report_factor", 1.0f);
    config.evaluations = json.value("evaluations", 40);
    config.followEvaluations = json.value("follow_evaluations", 15);
    for (const auto& view : json.at("views")) {
      ViewSpec spec;
      spec.name = view.at("name").get<std::string>();
      const std::string scene = view.value("scene", std::string("builtin"));
      if (scene != "builtin") spec.input.scenePath = scene;
      spec.input.sceneScale = view.value("scene_scale", 1.0f);
      spec.input.cameraPath = view.at("camera").get<std::string>();
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
  std::vector<float> radiusPixels;  // the SAO pass's projected radius h at each pixel (clamped as the shader does)
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
      view.viewDepth[i] = view.camera.near + LinearDepthPacking::depthFromCode(code) * (view.camera.far - view.camera.near);
  }
  // h = min(projScale r / -z, maxScreenRadius * height), as SaoKernel::diskRadiusPixels at G-buffer resolution.
  const AoSettings defaults;
  const float projScale = FrameCamera::from(view.camera, view.camera.width, view.camera.height)
                              .projScale(view.camera.height);
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

Image renderAo(TuningView& view, const AoSettings& settings, PassTimer* timer = nullptr) {
  view.renderer->render(view.camera, settings, obscura::View::Ao,
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
  double mae = 0, ssim = 0, pearson = 0, haloMae = 0, interiorMae = 0, paperMae = 0, minSkill = 1;
  int cases = 0;
  void add(const AoComparison& c, double whiteMae) {
    mae += c.mae;
    ssim += c.ssim;
    pearson += c.pearson;
    haloMae += c.haloMae;
    interiorMae += c.interiorMae;
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
    s.paperMae /= n;
    return s;
  }
};

// --- The fit -------------------------------------------------------------------------------------------------------

// The search runs over (ln(sigma k), beta, ln k), beta a fraction of the radius. SAO's visibility is max(0, 1 - sigma S)^k for the tap sum S;
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

EstimatorParameters toParameters(const Point& p) {
  const Point q = clampToBox(p);
  // Rounded to what the table stores, so the fitted figures are those of the written values.
  auto round4 = [](double v) { return static_cast<float>(std::round(v * 1e4) / 1e4); };
  return {round4(std::exp(q[0] - q[2])), round4(q[1]), round4(std::exp(q[2]))};
}

Point fromParameters(const EstimatorParameters& e) {
  return clampToBox({std::log(e.intensity * e.contrast), e.bias, std::log(e.contrast)});
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

AoSettings settingsFor(QualityPreset preset) {
  AoSettings settings;
  settings.applyPreset(preset);
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

// Every estimator the table holds, in its order.
constexpr AoEstimator kEstimators[] = {AoEstimator::Sao, AoEstimator::Gtao};

std::string estimatorEnumName(AoEstimator estimator) {
  return estimator == AoEstimator::Gtao ? "AoEstimator::Gtao" : "AoEstimator::Sao";
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
void fit(std::vector<TuningCase>& cases, const TuningConfig& config, const std::string& tablePath) {
  constexpr size_t kMinCasePixels = 200, kMinKnotPixels = 2000;
  struct Row {
    AoEstimator estimator;
    const PresetInfo* preset;
    int knot;
    EstimatorParameters fitted;
    double mae = 0, paperMae = 0;
    size_t pixels = 0;
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
      if (c.view->mask[i]) byKnot[static_cast<size_t>(knotOf(c.radiusPixels[i]))].push_back(static_cast<std::uint32_t>(i));
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

  for (AoEstimator estimator : kEstimators) {
  std::map<int, EstimatorParameters> leader;
  for (const PresetInfo* preset : order) {
    AoSettings base = settingsFor(preset->preset);
    base.estimator = estimator;
    std::map<int, Row> fitted;
    for (int knot = 0; knot < kEstimatorKnots; ++knot) {
      if (knotPixels[static_cast<size_t>(knot)] < kMinKnotPixels) continue;
      const bool first = leader.count(knot) == 0;
      EstimatorParameters start = kPaperEstimatorParameters;
      if (!first) start = leader[knot];
      else if (fitted.count(knot - 1)) start = fitted[knot - 1].fitted;
      int evaluations = 0;
      auto objective = [&](const Point& p) {
        ++evaluations;
        return knotMae(knot, withParameters(base, toParameters(p)));
      };
      const auto begin = std::chrono::steady_clock::now();
      const Point step = first ? Point{0.4, 0.05, 0.4} : Point{0.15, 0.02, 0.15};
      const Point best =
          nelderMead(objective, fromParameters(start), step, first ? config.evaluations : config.followEvaluations);
      Row row{estimator, preset, knot, toParameters(best)};
      row.mae = knotMae(knot, withParameters(base, row.fitted));
      row.paperMae = knotMae(knot, withParameters(base, kPaperEstimatorParameters));
      row.pixels = knotPixels[static_cast<size_t>(knot)];
      std::printf("  %-4s %-6s h = %3.0f px sigma %.3f beta %.4f k %.3f | MAE %.4f | paper MAE %.4f | %zu px in %zu "
                  "cases, %d renders each, %.0f s\n",
                  estimatorName(estimator), preset->name, static_cast<double>(estimatorKnotPixels(knot)),
                  static_cast<double>(row.fitted.intensity), static_cast<double>(row.fitted.bias),
                  static_cast<double>(row.fitted.contrast), row.mae, row.paperMae, row.pixels,
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

  // Rows grouped by preset in qualityPresets() order, knots increasing, as tunedEstimatorKnots expects.
  std::ostringstream out;
  out << "// Generated by tools/tune-defaults.sh (obscura-tune --fit): do not edit by hand.\n"
      << "// Each estimator's intensity sigma, bias beta (a fraction of the radius) and contrast k per quality preset, at\n"
      << "// knots of"
      << " the projected radius in pixels (AoSettings.h), fitted to the ray-traced reference (obscura-reference,\n"
      << "// " << config.rays << " rays per pixel) at " << config.width << "x" << config.height
      << ": per knot, the MAE of the blurred AO over the pixels whose\n"
      << "// radius in pixels lies nearest it, across the views of tools/tuning-views.json at radii of";
  for (float f : config.radiusFactors) out << " " << radiusText(f);
  out << "\n// times each view's object size: " << viewList(config) << ".\n"
      << "// docs/accuracy.md explains the procedure.\n"
      << "// {estimator, preset, radius in pixels (knot), {intensity sigma, bias beta (fraction of r), contrast k}},  // fitted | "
         "SAO paper's values\n";
  for (AoEstimator estimator : kEstimators) {
  for (const PresetInfo& preset : presets) {
    for (const Row& row : rows) {
      if (row.preset != &preset || row.estimator != estimator) continue;
      char comment[160];
      if (row.pixels)
        std::snprintf(comment, sizeof comment, "  // MAE %.4f | paper MAE %.4f, %zu px", row.mae, row.paperMae,
                      row.pixels);
      else
        std::snprintf(comment, sizeof comment, "  // too few pixels: the nearest fitted knot's values");
      out << "{" << estimatorEnumName(estimator) << ", " << presetEnumName(preset) << ", "
          << floatLiteral(estimatorKnotPixels(row.knot)) << ", {" << floatLiteral(row.fitted.intensity) << ", "
          << floatLiteral(row.fitted.bias) << ", " << floatLiteral(row.fitted.contrast) << "}}," << comment << "\n";
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

void report(std::vector<TuningCase>& cases, std::vector<TuningView>& views, const TuningConfig& config,
            const std::string& docPath, const std::string& imageDir, const HeadlessContext& context) {
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
  std::map<QualityPreset, Score> byPreset;
  std::map<float, Score> byFactor;  // default preset
  for (TuningCase& c : cases) {
    for (const PresetInfo& preset : qualityPresets()) {
      const AoSettings tuned = settingsFor(preset.preset);
      const AoComparison m = measure(c, tuned);
      Score& s = byPreset[preset.preset];
      s.add(m, c.whiteMae);
      s.paperMae += measure(c, withParameters(tuned, kPaperEstimatorParameters), false).mae;
      if (preset.preset == defaults.preset) byFactor[c.factor].add(m, c.whiteMae);
    }
  }
  const Score target = byPreset[defaults.preset].mean();
  const double haloRatio = target.haloMae / std::max(target.interiorMae, 1e-9);
  md << "### Targets (issue 12), preset " << presetName(defaults.preset) << ", mean over the " << cases.size()
     << " cases\n\n"
     << "| figure | target | reached | |\n|---|---|---|---|\n"
     << "| mean Pearson correlation | >= 0.93 | " << format("%.3f", target.pearson) << " | "
     << passFail(target.pearson >= 0.93) << " |\n"
     << "| mean MAE | <= 0.030 | " << format("%.4f", target.mae) << " | " << passFail(target.mae <= 0.030) << " |\n"
     << "| halo MAE / interior MAE | <= 1.1 | " << format("%.2f", haloRatio) << " | " << passFail(haloRatio <= 1.1)
     << " |\n"
     << "| lowest skill of any case | >= 0.5 | " << format("%.2f", target.minSkill) << " | "
     << passFail(target.minSkill >= 0.5) << " |\n\n";

  md << "### Each preset, mean over the cases\n\n"
     << "| preset | MAE | SSIM | Pearson | halo MAE | interior MAE | halo / interior | lowest skill | MAE, paper's "
        "sigma/beta/k |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const PresetInfo& preset : qualityPresets()) {
    const Score s = byPreset[preset.preset].mean();
    md << "| " << preset.name << " | " << format("%.4f", s.mae) << " | " << format("%.3f", s.ssim) << " | "
       << format("%.3f", s.pearson) << " | " << format("%.4f", s.haloMae) << " | " << format("%.4f", s.interiorMae)
       << " | " << format("%.2f", s.haloMae / std::max(s.interiorMae, 1e-9)) << " | " << format("%.2f", s.minSkill)
       << " | " << format("%.4f", s.paperMae) << " |\n";
  }

  md << "\n### Each radius (in object sizes), preset " << presetName(defaults.preset) << ", mean over the views\n\n"
     << "| radius / object size | MAE | SSIM | Pearson | halo MAE | interior MAE | lowest skill |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const auto& [factor, score] : byFactor) {
    const Score s = score.mean();
    md << "| " << radiusText(factor) << " | " << format("%.4f", s.mae) << " | " << format("%.3f", s.ssim) << " | "
       << format("%.3f", s.pearson) << " | " << format("%.4f", s.haloMae) << " | " << format("%.4f", s.interiorMae)
       << " | " << format("%.2f", s.minSkill) << " |\n";
  }

  md << "\n### Each view at " << radiusText(config.reportFactor) << " object size, preset "
     << presetName(defaults.preset) << "\n\n"
     << "| view | r (scene units) | MAE | RMSE | SSIM | Pearson | halo MAE | interior MAE | bias | skill | AO ms | MAE, "
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

  md << "\n### The fitted knots, preset " << presetName(defaults.preset) << "\n\n"
     << "| radius in pixels | sigma | beta (fraction of r) | k |\n|---|---|---|---|\n";
  const EstimatorKnots knots = tunedEstimatorKnots(defaults.estimator, defaults.preset);
  for (int j = 0; j < kEstimatorKnots; ++j)
    md << "| " << radiusText(estimatorKnotPixels(j)) << " | " << format("%.3f", knots.at[j].intensity) << " | "
       << format("%.4f", knots.at[j].bias) << " | " << format("%.3f", knots.at[j].contrast) << " |\n";

  md << "\n### Reference | SAO | difference\n\nPreset " << presetName(defaults.preset) << ", r = "
     << radiusText(config.reportFactor) << " object size, tuned parameters. Difference: red where SAO is darker than "
     << "the reference, blue where lighter, full colour at 0.25; grey: background.\n\n";
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
    md << "**" << name << "** (r = " << radiusText(c.radius) << ")\n\n![" << name << ": reference | SAO | difference]("
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
    for (float f : config.radiusFactors) std::printf(" %s", radiusText(f).c_str());
    std::printf(" x object size; references in %s\n", cache.c_str());
    std::vector<TuningCase> cases;
    for (size_t i = 0; i < views.size(); ++i) {
      TuningView& view = views[i];
      view.spec = config.views[i];
      SceneInput::Loaded input = view.spec.input.load();
      view.spec.input.printWarnings("obscura-tune", input.warnings);
      const Scene scene = std::move(input.scene);
      view.camera = input.camera;
      for (TuningCase& c : loadReferences(view, scene, config, cache, threads)) cases.push_back(std::move(c));
      view.renderer = std::make_unique<Renderer>(context.caps());
      view.renderer->setScene(scene);
      view.output = std::make_unique<gl::RenderTarget>("tuning output", view.camera.width, view.camera.height,
                                                       GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                                       context.caps().depth24);
    }
    if (!tablePath.empty()) fit(cases, config, tablePath);
    else report(cases, views, config, docPath, imageDir, context);
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
