#pragma once
// Distance fog (shaders_es2/fog/fog.glsl): the lit HDR colour ("scene-color") blended towards a fog colour by the
// distance from the camera. It runs right after the lighting, on linear HDR colour before TAA, bloom and tone
// mapping, so the fog colour is tone-mapped with the scene and the AO (which darkens the lighting's ambient term) is
// covered by the fog like everything else. It is a per-pixel stage (frame/Stage.h): inside the lighting's pass where
// nothing comes between them, with the surface's own position, and otherwise a pass of its own that reconstructs the
// position from the G-buffer's 16-bit linear depth (no extra geometry pass either way).
//
// The lecture decks' equations (Schmalstieg, "Image-space effects", "Fog function"; Samuelcik, "Post-processing"):
//   c = f c_s + (1 - f) c_f                   c_s the surface's colour, c_f the fog colour, f the fog factor
//   linear                  f = (d_end - d) / (d_end - d_start), clamped to [0, 1]
//   exponential             f = e^(-d_f d)
//   squared exponential     f = e^(-(d_f d)^2)
// with d the fragment's distance from the camera (the deck's length(camera.position - p), not the view depth) and
// d_f the density. The background (depth code 65535: nothing drawn) is at infinite distance: fully fogged.
//
// Height falloff b (fog.height-falloff, per metre; 0: uniform fog): the density falls off with world height h as
// d_f e^(-b h) (thickest at h = 0, thinning upwards), and the distance d in the equations above is replaced by the
// distance through fog of density d_f that holds as much fog as the ray does:
//   d' = integral_0^d e^(-b (h_0 + t u)) dt = d e^(-b h_0) g(b u d),    g(x) = (1 - e^-x) / x,  g(0) = 1
// with h_0 the camera's height and u the world-up component of the ray's unit direction (Quilez, "Better fog", the
// same integral for exponential fog). For exponential fog that is the exact optical depth; linear and squared
// exponential fog take it as their distance. A background ray climbing out of the fog (b u > 0) sees the finite
// d' = e^(-b h_0) / (b u); one level with or below the horizon sees infinite fog.
//
// An orthographic camera's rays are parallel, each from its own point of the eye's plane (lib/reconstruct.glsl:
// eyeRayOrigin): d is the distance from there (the view depth), and h_0 that point's height.
//
// CPU mirror: FogFactor below (tests/test_fog.cpp reads the GPU's result back against it per pixel).
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"

namespace obscura {

enum class FogMode { Linear = 0, Exponential = 1, SquaredExponential = 2 };
const char* fogModeName(FogMode mode);  // "linear", "exp", "exp2" (OpenGL's GL_LINEAR, GL_EXP, GL_EXP2)

struct FogSettings : ParameterAccess<FogSettings> {
  bool enabled = false;
  FogMode mode = FogMode::Exponential;
  float density = 0.02f;  // d_f, per metre (scene unit): exponential fog halves the colour every ln 2 / d_f = 35 m
  float start = 10.0f;    // d_start, metres (linear fog)
  float end = 100.0f;     // d_end, metres (linear fog); at or before start, the fog is a step at start
  glm::vec3 color{0.5f, 0.6f, 0.7f};  // c_f, linear HDR (a pale blue-grey sky)
  float heightFalloff = 0.0f;         // b, per metre: the density at height h is d_f e^(-b h); 0: uniform fog

  static const std::vector<Parameter<FogSettings>>& parameters();
  void validate() const { validateParameters("fog"); }
};

// The fog factor f of the settings for one camera, with the constants the shader gets derived once.
struct FogFactor {
  FogMode mode = FogMode::Exponential;
  // f = clamp(offset - scale d', 0, 1) (linear), exp2(-scale d') (exponential), exp2(-(scale d')^2) (squared): the
  // deck's equations with e^x = 2^(x log2 e) folded into the scale.
  float offset = 0.0f, scale = 0.0f;
  float falloff = 0.0f;      // b
  float heightScale = 1.0f;  // e^(-b h_0), h_0 the camera's height
  glm::vec3 upInView{0.0f, 1.0f, 0.0f};  // world up in view space (the ray's u is its dot with the ray)

  static FogFactor of(const FogSettings& settings, const glm::mat4& view);
  // d' of a ray of length `distance` (infinity: the background) whose unit direction has world-up component `up`.
  float fogDistance(float distance, float up) const;
  // f at a view-space point, seen along the ray from `rayOrigin` (ViewReconstruction::eyeRayOrigin: the eye, or the
  // eye's plane); `background`: that ray through `viewPosition` to infinity.
  float at(const glm::vec3& viewPosition, bool background, const glm::vec3& rayOrigin = glm::vec3(0.0f)) const;
};

class FogEffect : public Effect {
 public:
  using Settings = FogSettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs() { return {}; }  // its programs are the fused ones (stages())
  // Its stage in a variant (the mode; the height falloff or not), and every variant, for the shader checks.
  static StageDecl stage(FogMode mode, bool height);
  static std::vector<StageDecl> stages();

  explicit FogEffect(const EffectResources& resources) : resources_(resources) {}
  void plan(FramePlanner& planner) override;

 private:
  const EffectResources& resources_;
};

}  // namespace obscura
