#include "effects/ao/AoSettings.h"

#include <algorithm>
#include <cmath>

#include "base/Error.h"
#include "effects/ao/SaoKernel.h"

namespace obscura {

const std::vector<Parameter<AoSettings>>& AoSettings::parameters() {
  using S = AoSettings;
  static const std::vector<Parameter<S>> table = [] {
    std::vector<Parameter<S>> t;
    t.push_back(switchParameter<S>("ao", "ambient obscurance on or off", &S::enabled).primary());

    t.push_back(presetParameter<S>("quality preset: samples, spiral turns, blur, resolution").primary());

    std::vector<std::pair<std::string, AoEstimator>> estimators;
    for (AoEstimator choice : allAoEstimators()) estimators.emplace_back(estimatorName(choice), choice);
    t.push_back(choiceParameter<S, AoEstimator>("estimator", "obscurance estimator (docs/accuracy.md compares them)",
                                                &S::estimator, estimators));
    t.push_back(numberParameter<S>("radius", 1e-4, 1e6, "scene units",
                                   "world-space obscurance radius r (metres in the built-in scene)", &S::radius)
                    .primary());
    t.push_back(autoNumberParameter<S>("intensity", 0, 20, "", "intensity sigma (auto: fitted to the reference)",
                                       &S::intensity, [](const S& s) { return s.estimatorAt().intensity; })
                    .primary());
    t.push_back(autoNumberParameter<S>("bias", 0, 1, "fraction of radius",
                                       "tangent-plane bias beta against self-occlusion (auto: fitted to the reference)",
                                       &S::bias, [](const S& s) { return s.estimatorAt().bias; })
                    .primary());
    t.push_back(autoNumberParameter<S>("contrast", 0.1, 10, "", "contrast exponent k (auto: fitted to the reference)",
                                       &S::contrast, [](const S& s) { return s.estimatorAt().contrast; })
                    .primary());
    t.push_back(integerParameter<S>("samples", 1, 64, "", "", "taps per pixel (also picks the best spiral turns)",
                                    &S::samples, [](S& s, const std::string&) {
                                      s.spiralTurns = SaoKernel::bestSpiralTurns(s.samples);
                                    })
                    .primary());
    Parameter<S> turns = integerParameter<S>(
        "turns", 1, 63, "", "coprime with samples", "spiral turns tau", &S::spiralTurns,
        [](S& s, const std::string& v) {
          if (SaoKernel::greatestCommonDivisor(s.spiralTurns, s.samples) != 1)
            throw InputError("turns: " + v + " shares a factor with samples = " + std::to_string(s.samples) +
                             "; taps would line up");
        });
    turns.valid = [](const S& s) {
      return s.spiralTurns >= 1 && SaoKernel::greatestCommonDivisor(s.spiralTurns, s.samples) == 1;
    };
    t.push_back(turns);
    t.push_back(choiceParameter<S, Falloff>("falloff", "distance falloff of the estimator", &S::falloff,
                                            {{"sao2012", Falloff::Sao2012}, {"alchemy2011", Falloff::Alchemy2011}}));
    t.push_back(numberParameter<S>("max-screen-radius", 0.01, 1, "fraction of height", "clamp of the projected radius",
                                   &S::maxScreenRadius));
    Parameter<S> hierarchy = choiceParameter<S, DepthHierarchy>(
        "hierarchy", "depth hierarchy for far taps (auto: none, the cheaper on every device measured)",
        &S::depthHierarchy, {{"auto", DepthHierarchy::Auto}, {"on", DepthHierarchy::On}, {"off", DepthHierarchy::Off}});
    hierarchy.effective = [](const S& s) { return std::string(s.usesDepthHierarchy() ? "on" : "off"); };
    t.push_back(std::move(hierarchy));
    t.push_back(switchParameter<S>("half-res", "AO at half resolution, upsampled depth-aware", &S::halfResolution));
    t.push_back(switchParameter<S>("blur", "bilateral blur", &S::blur).primary());
    t.push_back(integerParameter<S>("blur-radius", 0, 8, "taps each side", "", "blur radius; 0 turns the blur off",
                                    &S::blurRadius)
                    .primary());
    t.push_back(integerParameter<S>("blur-stride", 1, 8, "pixels", "", "pixels between blur taps", &S::blurStride));
    t.push_back(switchParameter<S>("blur-normals", "normal-aware blur weights", &S::blurNormalAware));
    t.push_back(numberParameter<S>("blur-depth-sigma", 0.001, 10, "fraction of radius",
                                   "depth difference at which blur weights fall to 1/e", &S::blurDepthSigma));
    // Before effects had prefixes these were the only parameters, named without "ao.": those names stay accepted.
    // ("preset" is now the frame's preset, which sets this one too.)
    for (Parameter<S>& p : t)
      if (p.info.name != "ao" && p.info.name != "preset") p.info.alias = p.info.name;
    // Newer than prefixes: "ao." names only.
    t.push_back(integerParameter<S>("layers", 1, 2, "", "",
                                    "depth layers GTAO reads (2: a second geometry pass peels the surface behind)",
                                    &S::layers)
                    .shapesPlan()  // the peel pass, and the estimator's and hierarchy's two-layer programs
                    .primary());
    t.push_back(numberParameter<S>("layer-separation", 0, 10, "fraction of radius",
                                   "the second layer's least distance behind the first", &S::layerSeparation));
    t.push_back(autoNumberParameter<S>("thickness", 0.01, 1000, "fraction of radius",
                                       "one layer: the thickness GTAO assumes behind an occluder's front (auto: "
                                       "fitted to the reference)",
                                       &S::thickness, [](const S& s) { return s.estimatorAt().thickness; }));
    t.push_back(numberParameter<S>("surface-gap", 0, 1000, "fraction of radius",
                                   "depth gap between taps that GTAO still takes for one occluder", &S::surfaceGap));
    t.push_back(switchParameter<S>("temporal", "accumulate the AO over frames through the motion vectors",
                                   &S::temporal)
                    .primary());
    t.push_back(integerParameter<S>("temporal-frames", 1, 64, "frames", "",
                                    "longest memory of the temporal AO's running mean", &S::temporalFrames));
    return t;
  }();
  return table;
}

const std::vector<PresetInfo>& qualityPresets() {
  // samples / spiral turns / blur radius / blur stride / half resolution. Turns are bestSpiralTurns(samples) (a test
  // holds them equal). The blur stride stays 1: a stride of 2 aliases with the interleaved-gradient rotation and
  // leaves a regular pattern. Costs measured by obscura-bench are in docs/benchmarks.md.
  static const std::vector<PresetInfo> presets = {
      {QualityPreset::Low, "low", 8, 3, 3, 1, true},
      {QualityPreset::Medium, "medium", 11, 3, 4, 1, false},
      {QualityPreset::High, "high", 16, 3, 5, 1, false},
      {QualityPreset::Ultra, "ultra", 32, 7, 6, 1, false},
  };
  return presets;
}

const std::vector<AoEstimator>& allAoEstimators() {
  static const std::vector<AoEstimator> all = {AoEstimator::Sao, AoEstimator::Gtao, AoEstimator::Hbao,
                                               AoEstimator::Vo, AoEstimator::Crytek};
  return all;
}

const char* estimatorName(AoEstimator estimator) {
  switch (estimator) {
    case AoEstimator::Sao: return "sao";
    case AoEstimator::Gtao: return "gtao";
    case AoEstimator::Hbao: return "hbao";
    case AoEstimator::Vo: return "vo";
    case AoEstimator::Crytek: return "crytek";
  }
  return "sao";
}

AoEstimator parseEstimator(const std::string& name) {
  std::vector<std::string> names;
  for (AoEstimator estimator : allAoEstimators()) {
    if (name == estimatorName(estimator)) return estimator;
    names.emplace_back(estimatorName(estimator));
  }
  throw InputError("estimator: expected " + parse::oneOf(names) + ", got '" + name + "'");
}

const char* falloffName(Falloff falloff) { return falloff == Falloff::Sao2012 ? "sao2012" : "alchemy2011"; }

void AoSettings::applyPreset(QualityPreset which) {
  for (const PresetInfo& p : qualityPresets()) {
    if (p.preset != which) continue;
    preset = which;
    samples = p.samples;
    spiralTurns = p.spiralTurns;
    blurRadius = p.blurRadius;
    blurStride = p.blurStride;
    halfResolution = p.halfResolution;
  }
}

bool AoSettings::matchesPreset(QualityPreset which) const {
  for (const PresetInfo& p : qualityPresets())
    if (p.preset == which)
      return preset == which && samples == p.samples && spiralTurns == p.spiralTurns &&
             blurRadius == p.blurRadius && blurStride == p.blurStride && halfResolution == p.halfResolution;
  return false;
}

void AoSettings::validate() const {
  validateParameters("AO");
  // The estimator parameters are also checked as resolved, so a tuned table entry out of range is caught too.
  for (const EstimatorParameters& e : estimatorKnots().at)
    if (!(e.bias >= 0.0f && e.bias <= 1.0f && e.intensity >= 0.0f && e.intensity <= 20.0f && e.contrast >= 0.1f &&
          e.contrast <= 10.0f && e.thickness >= 0.01f && e.thickness <= 1000.0f))
      throw InputError("invalid AO settings: the tuned estimator parameters for this preset are out of range");
}

namespace {

struct TunedEntry {
  AoEstimator estimator;
  QualityPreset preset;
  int layers;  // ao.layers (the estimator's table for two layers, where it reads them)
  float radiusPixels;
  EstimatorParameters parameters;
};

// One row per estimator, preset and knot.
constexpr TunedEntry kTunedTable[] = {
#include "effects/ao/TunedDefaults.inc"
};

}  // namespace

float estimatorKnotPixels(int knot) { return kFirstKnotPixels * std::exp2(static_cast<float>(knot)); }

EstimatorParameters EstimatorKnots::interpolate(float radiusPixels) const {
  // The shader's form (sao.frag): tent weights max(0, 1 - |t - j|) at t = clamp(log2(h / h_0), 0, knots - 1).
  const float t = std::clamp(std::log2(std::max(radiusPixels, 1e-3f) / kFirstKnotPixels), 0.0f,
                             static_cast<float>(kEstimatorKnots - 1));
  EstimatorParameters e{0.0f, 0.0f, 0.0f, 0.0f};
  for (int j = 0; j < kEstimatorKnots; ++j) {
    const float w = std::max(0.0f, 1.0f - std::abs(t - static_cast<float>(j)));
    e.intensity += w * at[j].intensity;
    e.bias += w * at[j].bias;
    e.contrast += w * at[j].contrast;
    e.thickness += w * at[j].thickness;
  }
  return e;
}

bool estimatorReadsSecondLayer(AoEstimator estimator) { return estimator == AoEstimator::Gtao; }

bool hasTunedEstimatorKnots(AoEstimator estimator, QualityPreset preset, int layers) {
  for (const TunedEntry& entry : kTunedTable)
    if (entry.estimator == estimator && entry.preset == preset && entry.layers == layers) return true;
  return false;
}

EstimatorKnots tunedEstimatorKnots(AoEstimator estimator, QualityPreset preset, int layers) {
  if (!hasTunedEstimatorKnots(estimator, preset, layers)) layers = 1;
  EstimatorKnots knots;
  for (EstimatorParameters& e : knots.at) e = kPaperEstimatorParameters;
  for (const TunedEntry& entry : kTunedTable) {
    if (entry.estimator != estimator || entry.preset != preset || entry.layers != layers) continue;
    for (int j = 0; j < kEstimatorKnots; ++j)
      if (std::abs(entry.radiusPixels - estimatorKnotPixels(j)) < 1e-3f) knots.at[j] = entry.parameters;
  }
  return knots;
}

EstimatorKnots AoSettings::estimatorKnots() const {
  EstimatorKnots knots = tunedEstimatorKnots(estimator, preset, layersRead());
  for (EstimatorParameters& e : knots.at) {
    if (intensity) e.intensity = *intensity;
    if (bias) e.bias = *bias;
    if (contrast) e.contrast = *contrast;
    if (thickness) e.thickness = *thickness;
  }
  return knots;
}

EstimatorParameters AoSettings::estimatorAt(float radiusPixels) const {
  return estimatorKnots().interpolate(radiusPixels);
}

const std::vector<ParameterInfo>& aoParameters() {
  static const std::vector<ParameterInfo> infos = [] {
    std::vector<ParameterInfo> out;
    for (const Parameter<AoSettings>& p : AoSettings::parameters()) out.push_back(p.info);
    return out;
  }();
  return infos;
}

}  // namespace obscura
