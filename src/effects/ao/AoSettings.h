#pragma once
// The settings of the ambient obscurance effect (effects/ao/AoEffect.h): every knob of SAO, its depth hierarchy and its
// blur, with its default, range and documentation (parameters()). Set by name through RenderSettings as "ao.NAME";
// the plain names ("radius", "samples", ...) are the names they had before effects had prefixes, and stay accepted
// everywhere (command line, URLs, the JS API).
#include <optional>
#include <string>
#include <vector>

#include "frame/Parameters.h"

namespace obscura {

// The obscurance estimator: how the pass turns G-buffer taps into visibility. Every estimator reads the same G-buffer
// and depth hierarchy, goes through the same blur, and has its own fitted parameters (docs/accuracy.md compares them).
enum class AoEstimator {
  Sao,     // Scalable Ambient Obscurance (McGuire, Mara, Luebke 2012): shaders_es2/ao/sao.frag
  Gtao,    // Ground-truth AO (Jimenez et al. 2016), horizon-based, cosine-weighted: shaders_es2/ao/gtao.frag
  Hbao,    // Horizon-based AO (Bavoil, Sainz, Dimitrov, SIGGRAPH 2008 talk): shaders_es2/ao/hbao.frag
  Vo,      // Volumetric obscurance (Loos, Sloan, I3D 2010), paired line samples of a ball: shaders_es2/ao/vo.frag
  Crytek,  // CryEngine 2's SSAO (Mittring, SIGGRAPH 2007 course), points in a sphere, the baseline: crytek.frag
};
// Every estimator, in the order the settings, the fitted table and the reports list them.
const std::vector<AoEstimator>& allAoEstimators();
const char* estimatorName(AoEstimator estimator);  // "sao", "gtao", "hbao", "vo", "crytek": ao.estimator's values
AoEstimator parseEstimator(const std::string& name);  // throws InputError

// Per-tap distance falloff of the Alchemy estimator family (see SaoKernel.h for the equations).
// Whether the AO builds a depth hierarchy (AoSettings::depthHierarchy).
enum class DepthHierarchy { Auto, On, Off };

enum class Falloff {
  Alchemy2011,  // McGuire et al., HPG 2011: a hard cut at the radius
  Sao2012,      // McGuire, Mara, Luebke, HPG 2012 reference code: smooth (r^2 - v.v)^3 falloff
};
const char* falloffName(Falloff falloff);

// The estimator parameters SAO's pass uses (SaoKernel.h).
struct EstimatorParameters {
  float intensity = 1.0f;  // sigma
  float bias = 0.012f;     // beta, as a fraction of the radius
  float contrast = 1.0f;   // k
  // t: GTAO with one layer, an occluder's assumed depth behind its front face, a fraction of r (unused by the other
  // estimators and with two layers, where the second layer bounds it)
  float thickness = 0.5f;
};
// The SAO paper's and reference code's values (sigma 1, beta 0.012 m at r = 1 m, k 1): what obscura used before
// tuning, and the fallback for a preset the tuned table does not cover.
constexpr EstimatorParameters kPaperEstimatorParameters{};

// The fitted parameters are keyed by what changes the estimator's error once distances are in units of the radius:
// the radius in pixels h (how finely the taps sample the disk, which hierarchy levels they read, how far the blur
// reaches in units of r) and the sample count (the preset). They are tabulated at knots h_j = 4 * 2^j pixels,
// j = 0 .. 5 (4 .. 128 px), and each pixel interpolates them linearly in log2(h) at its own projected radius (held at
// the ends): a near surface and a far one in the same frame each get the parameters fitted for their sampling.
constexpr int kEstimatorKnots = 6;
constexpr float kFirstKnotPixels = 4.0f;
// The radius in pixels of knot j.
float estimatorKnotPixels(int knot);
// The radius in pixels at which settings show a single "auto" value (the middle of the fitted range).
constexpr float kShownKnotPixels = 32.0f;

struct EstimatorKnots {
  EstimatorParameters at[kEstimatorKnots];
  // The parameters at a projected radius of `radiusPixels`: linear in log2(radiusPixels) between knots.
  EstimatorParameters interpolate(float radiusPixels) const;
};

// Whether the estimator reads a second depth layer (ao.layers 2): GTAO, where an occluder covers only the directions
// between its two layers. The others read the first alone, and ao.layers 2 draws no second layer for them.
bool estimatorReadsSecondLayer(AoEstimator estimator);

// The knots fitted to the ray-traced reference (src/effects/ao/TunedDefaults.inc, written by tools/tune-defaults.sh)
// for `preset` and `layers` depth layers (those for one layer where the table has none for two); the SAO paper's
// values at every knot for a preset the table does not cover.
EstimatorKnots tunedEstimatorKnots(AoEstimator estimator, QualityPreset preset, int layers = 1);
// Whether the table has rows of its own for this estimator, preset and layer count.
bool hasTunedEstimatorKnots(AoEstimator estimator, QualityPreset preset, int layers);

struct AoSettings : ParameterAccess<AoSettings> {
  bool enabled = true;

  // --- Estimator (see SaoKernel.h) ---
  // GTAO by default: against the ray-traced reference it beats SAO at every radius in pixels up to 64 and over the
  // tuning views as a whole, at about the same cost on a GPU (docs/accuracy.md; docs/benchmarks.md section 6); SAO
  // stays one setting away.
  AoEstimator estimator = AoEstimator::Gtao;
  // r: world-space obscurance radius, in the scene's units (metres for the built-in scene). The estimator measures
  // every distance in units of r, so a scene and its radius scaled together give the same AO.
  float radius = 1.0f;
  // beta (ignores occluders closer than this to the tangent plane, a fraction of r), sigma (scales the obscurance
  // sum) and k
  // (exponent on the final value): explicit values when set; unset, estimator() resolves them to the values fitted
  // to the ray-traced reference for `preset` at each pixel's radius in pixels (tunedEstimatorKnots,
  // docs/accuracy.md), so that a radius means the obscurance of that radius.
  std::optional<float> bias, intensity, contrast;
  QualityPreset preset = QualityPreset::Medium;  // the preset these settings came from (applyPreset sets it)
  int samples = 11;        // s: taps per pixel, a compile-time constant of the shader variant
  int spiralTurns = 3;     // tau: turns of the tap spiral, coprime with samples (SaoKernel::bestSpiralTurns)
  // Alchemy's hard cut at r: fitted to the reference, it beats SAO 2012's smooth falloff at every radius in pixels
  // (docs/accuracy.md), as the reference itself cuts at r.
  Falloff falloff = Falloff::Alchemy2011;
  // Clamp of the projected radius, as a fraction of the AO target's height. The whole height: with the depth
  // hierarchy the cost does not grow with the disk (65.9 ms at r = 4 m either way on llvmpipe at 1280x720), and at
  // radii of 2 to 4 object sizes a clamp at half the height left out occluders the reference counts (GTAO's mean MAE
  // at 4 object sizes 0.096 -> 0.082; docs/accuracy.md).
  float maxScreenRadius = 1.0f;

  // --- Occluders' thickness (GTAO: shaders_es2/ao/gtao.frag) ---
  // An occluder occludes only between its front face and a back point on the same pixel ray: with one layer the
  // point `thickness` r behind the front (a heuristic: a height field, infinitely thick, puts halos around thin
  // objects in front of far surfaces), with two layers the second layer's. Unset, the knots' value per radius in
  // pixels (estimatorKnots): 0.5 r in the shipped table, as a thickness fitted per radius in pixels (obscura-tune
  // --fit-thickness) wins on average but loses on the built-in scene (docs/accuracy.md, "Thickness"); set, it holds
  // at every radius.
  std::optional<float> thickness;
  // Two consecutive taps whose depth ranges (front to back) overlap within this gap, a fraction of r, are one
  // occluder, solid between them; a larger step lets the sky through between them (docs/accuracy.md).
  float surfaceGap = 0.5f;

  // --- Depth layers ---
  // 1: the G-buffer's depth alone. 2: a second geometry pass peels the nearest surface at least layerSeparation r
  // behind the visible one (effects/ao/DepthPeelPass.h), and GTAO counts an occluder only between the two layers
  // (the other estimators read the first layer alone, and no second layer is drawn for them).
  int layers = 1;
  // The peel's minimum separation, a fraction of r (and at least two depth codes): 0.01 measured best against the
  // reference; 0.05 skipped thin balusters' back faces, which then took the wall behind as their back (halos).
  float layerSeparation = 0.01f;

  // --- Depth hierarchy and resolution ---
  // SAO's depth MIP: far taps read coarser levels, so neighbouring pixels' far taps share texels. Auto builds none:
  // it costs more than it saves on every device measured (llvmpipe, SwiftShader, an H100 and an H200: the estimator's
  // level arithmetic and the hierarchy's own pass against a cache that holds the frame; docs/benchmarks.md, section
  // 2, "The depth hierarchy only where it pays" and "On a GPU: an NVIDIA H200"), with one layer and with two (whose
  // depths its texels fold into one fetch a tap: two fetches a tap still cost less), and the AO is the same within
  // 0.0004 MAE. On a GPU whose caches are small next to the G-buffer `on` may pay (the SAO paper's case).
  DepthHierarchy depthHierarchy = DepthHierarchy::Auto;
  bool halfResolution = false; // AO at half size, upsampled depth-aware to full size

  // --- Bilateral blur ---
  bool blur = true;
  int blurRadius = 4;            // taps on each side of the centre, per direction (0 .. 8)
  int blurStride = 1;            // pixels between taps (2 aliases with the interleaved-gradient rotation)
  bool blurNormalAware = true;   // also weight by normals and by distance to the centre's tangent plane
  float blurDepthSigma = 0.1f;   // fraction of the radius: range weight exp(-(dz/sigma)^2)

  // --- Temporal accumulation (effects/ao/AoTemporal.h) ---
  // Off by default: on, each frame's taps turn to new directions and distances, and the AO before the blur is
  // accumulated over frames through the motion vectors (a running mean of at most temporalFrames frames), with the
  // history rejected where the surface it saw is not this pixel's (docs/temporal-effects.md, "Temporal AO").
  bool temporal = false;
  int temporalFrames = 8;  // N: the running mean's longest memory (the weight of a new frame is at least 1/N)

  // Every parameter, by its local name ("radius"; the switch is "ao"). set/get/effective come from ParameterAccess;
  // "auto" for bias, intensity or contrast returns that parameter to its tuned value, and "preset" reads as the
  // preset whose values the settings hold, or "" when they match none.
  static const std::vector<Parameter<AoSettings>>& parameters();

  // Applies a preset's samples, spiral turns, blur radius/stride and resolution, and remembers the preset (for the
  // tuned estimator parameters), leaving the rest alone.
  void applyPreset(QualityPreset which);
  // Whether the settings still hold `which`'s values.
  bool matchesPreset(QualityPreset which) const;
  // sigma, beta and k as the estimator pass uses them, per knot: the explicit values where set, the tuned ones
  // elsewhere.
  EstimatorKnots estimatorKnots() const;
  // The same at one projected radius (kShownKnotPixels: the value controls show for "auto").
  EstimatorParameters estimatorAt(float radiusPixels = kShownKnotPixels) const;
  // The blur's depth sigma in scene units (blurDepthSigma times the radius).
  float blurDepthSigmaDistance() const { return blurDepthSigma * radius; }
  // The depth layers the estimator reads: `layers`, or 1 for an estimator that reads one alone.
  int layersRead() const { return estimatorReadsSecondLayer(estimator) ? layers : 1; }
  // Whether the passes build and read the depth hierarchy (depthHierarchy, auto resolved).
  bool usesDepthHierarchy() const { return depthHierarchy == DepthHierarchy::On; }
  // Throws InputError if a field is out of range (for settings built in code).
  void validate() const;
};

// The AO parameters' documentation, by local name.
const std::vector<ParameterInfo>& aoParameters();

struct PresetInfo {
  QualityPreset preset;
  const char* name;
  int samples;
  int spiralTurns;
  int blurRadius;
  int blurStride;
  bool halfResolution;
};
// The single table of the AO's quality presets, used by the CLI, the viewers and the page.
const std::vector<PresetInfo>& qualityPresets();

}  // namespace obscura
