#pragma once
// Every user-facing knob of the AO pipeline, with its default, its range and its documentation, in one place. The
// command line, the desktop viewer and the web page all set parameters through AoSettings::set, so they accept the
// same names and the same ranges, and an out-of-range value never reaches a shader.
#include <optional>
#include <string>
#include <vector>

namespace obscura {

// Per-tap distance falloff of the Alchemy estimator family (see SaoKernel.h for the equations).
enum class Falloff {
  Alchemy2011,  // McGuire et al., HPG 2011: a hard cut at the radius
  Sao2012,      // McGuire, Mara, Luebke, HPG 2012 reference code: smooth (r^2 - v.v)^3 falloff
};

enum class QualityPreset { Low, Medium, High, Ultra };

// The estimator parameters SAO's pass uses (SaoKernel.h).
struct EstimatorParameters {
  float intensity = 1.0f;  // sigma
  float bias = 0.012f;     // beta, metres
  float contrast = 1.0f;   // k
};
// The SAO paper's and reference code's values (sigma 1, beta 0.012 m, k 1): what obscura used before tuning, and the
// fallback for a preset the tuned table does not cover.
constexpr EstimatorParameters kPaperEstimatorParameters{};

// The parameters fitted to the ray-traced reference (src/core/TunedDefaults.inc, written by tools/tune-defaults.sh)
// for `preset` at `radius`: linear in log(radius) between the fitted radii, held at the ends of the fitted range.
EstimatorParameters tunedEstimatorParameters(QualityPreset preset, float radius);

struct AoSettings {
  bool enabled = true;

  // --- Estimator (see SaoKernel.h) ---
  float radius = 1.0f;  // r: world-space obscurance radius, metres
  // beta (ignores occluders closer than this to the tangent plane, metres), sigma (scales the obscurance sum) and k
  // (exponent on the final value): explicit values when set; unset, estimator() resolves them to the values fitted
  // to the ray-traced reference for `preset` and `radius` (tunedEstimatorParameters, docs/accuracy.md), so that a
  // radius means the obscurance of that radius.
  std::optional<float> bias, intensity, contrast;
  QualityPreset preset = QualityPreset::Medium;  // the preset these settings came from (applyPreset sets it)
  int samples = 11;        // s: taps per pixel, a compile-time constant of the shader variant
  int spiralTurns = 3;     // tau: turns of the tap spiral, coprime with samples (SaoKernel::bestSpiralTurns)
  Falloff falloff = Falloff::Sao2012;
  float maxScreenRadius = 0.5f;  // clamp of the projected radius, as a fraction of the AO target's height

  // --- Depth hierarchy and resolution ---
  bool depthHierarchy = true;  // SAO's depth MIP: far taps read coarser levels (cost independent of radius)
  bool halfResolution = false; // AO at half size, upsampled depth-aware to full size

  // --- Bilateral blur ---
  bool blur = true;
  int blurRadius = 4;            // taps on each side of the centre, per direction (0 .. 8)
  int blurStride = 1;            // pixels between taps (2 aliases with the interleaved-gradient rotation)
  bool blurNormalAware = true;   // also weight by normals and by distance to the centre's tangent plane
  float blurDepthSigma = 0.1f;   // metres: range weight exp(-(dz/sigma)^2)

  // Applies a preset's samples, spiral turns, blur radius/stride and resolution, and remembers the preset (for the
  // tuned estimator parameters), leaving the rest alone.
  void applyPreset(QualityPreset which);
  // Sets `name` (the command-line spelling without "--", e.g. "radius") from text. Throws InputError naming the
  // parameter, the value and the accepted range when the name is unknown or the value is out of range.
  // "auto" for bias, intensity or contrast returns that parameter to its tuned value.
  void set(const std::string& name, const std::string& value);
  // sigma, beta and k as the SAO pass uses them: the explicit values where set, the tuned ones elsewhere.
  EstimatorParameters estimator() const;
  // The current value of `name` as text that set() accepts (numbers in their shortest exact form), so settings
  // round-trip through text (the web page's URL, the viewers' key bindings). "auto" for bias, intensity or
  // contrast left to their tuned values. For "preset": the preset whose values the settings hold, or "" when they
  // match none. Throws InputError for an unknown name.
  std::string get(const std::string& name) const;
  // The value in use, as text: get(name), except that bias, intensity and contrast left on "auto" read as the
  // values estimator() resolves them to (for sliders and the viewers' +/- keys).
  std::string effective(const std::string& name) const;
  // Throws InputError if a field is out of range (for settings built in code).
  void validate() const;
};

// What kind of value a parameter takes, so a user interface can offer the right control.
enum class ParameterKind {
  Switch,   // "on" | "off"
  Number,   // a real number in min .. max
  Integer,  // a whole number in min .. max
  Choice,   // one of `choices`
};

// Documentation of one parameter accepted by AoSettings::set.
struct ParameterInfo {
  const char* name;
  std::string range;  // human-readable, made from the fields below, e.g. "0.01 .. 100 (metres)"
  const char* help;
  ParameterKind kind;
  double min = 0.0, max = 0.0;       // Number and Integer
  std::vector<std::string> choices;  // Switch and Choice, in the order to offer them; for a Number, words accepted
                                     // besides numbers ("auto": bias, intensity and contrast)
};
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
// The single table of quality presets used by the CLI, the viewer and the page.
const std::vector<PresetInfo>& qualityPresets();
QualityPreset parsePreset(const std::string& name);  // throws InputError
const char* presetName(QualityPreset preset);
const char* falloffName(Falloff falloff);

// The shortest decimal text that reads back as exactly `value`: how get() writes numbers (and the viewers' state
// text writes camera coordinates), so "0.3" stays "0.3" rather than "0.300000012".
std::string formatShortest(float value);

}  // namespace obscura
