#include "effects/fog/FogEffect.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "frame/PassContext.h"
#include "frame/Stage.h"

namespace obscura {
namespace {

constexpr FogMode kFogModes[] = {FogMode::Linear, FogMode::Exponential, FogMode::SquaredExponential};
constexpr float kLog2E = 1.4426950408889634f;
// exp's argument is kept within +-80 (e^80 ~ 5.5e34, inside binary32), in the shader alike.
constexpr float kMaxExponent = 80.0f;
// The distance standing for "no end" (the background, a ray into unending fog): every mode's f is 0 there.
constexpr float kEndless = 1e30f;

}  // namespace

const char* fogModeName(FogMode mode) {
  switch (mode) {
    case FogMode::Linear: return "linear";
    case FogMode::Exponential: return "exp";
    case FogMode::SquaredExponential: return "exp2";
  }
  return "?";
}

const std::vector<Parameter<FogSettings>>& FogSettings::parameters() {
  using S = FogSettings;
  static const std::vector<Parameter<S>> table = [] {
    std::vector<std::pair<std::string, FogMode>> modes;
    for (FogMode choice : kFogModes) modes.emplace_back(fogModeName(choice), choice);
    return std::vector<Parameter<S>>{
        switchParameter<S>("fog", "distance fog on or off (from the G-buffer's depth, before tone mapping)",
                           &S::enabled)
            .primary(),
        choiceParameter<S, FogMode>("mode", "fog factor: linear (start .. end), exp e^-(density d), exp2 "
                                    "e^-(density d)^2",
                                    &S::mode, modes)
            .primary(),
        numberParameter<S>("density", 0, 100, "per metre", "exp and exp2: the fog's density", &S::density).primary(),
        numberParameter<S>("start", 0, 1e6, "metres", "linear: the distance where the fog begins", &S::start),
        numberParameter<S>("end", 0, 1e6, "metres", "linear: the distance where nothing but fog is seen", &S::end),
        colorParameter<S>("color", 0, 65408, "the fog's colour, linear HDR (tone-mapped with the scene)", &S::color)
            .primary(),
        numberParameter<S>("height-falloff", 0, 100, "per metre",
                           "the density at world height h is density x e^(-falloff h); 0: uniform fog",
                           &S::heightFalloff)
            .shapesPlan()};  // above 0 the stage's variant with height
  }();
  return table;
}

FogFactor FogFactor::of(const FogSettings& settings, const glm::mat4& view) {
  FogFactor f;
  f.mode = settings.mode;
  switch (settings.mode) {
    case FogMode::Linear: {
      // (d_end - d) / (d_end - d_start) = offset - scale d; an empty interval is a step at d_start.
      const float span = std::max(settings.end - settings.start, 1e-6f);
      f.scale = 1.0f / span;
      f.offset = std::max(settings.end, settings.start + 1e-6f) / span;
      break;
    }
    case FogMode::Exponential: f.scale = settings.density * kLog2E; break;
    case FogMode::SquaredExponential: f.scale = settings.density * std::sqrt(kLog2E); break;
  }
  f.falloff = settings.heightFalloff;
  const glm::mat4 cameraToWorld = glm::inverse(view);
  const float cameraHeight = cameraToWorld[3][1];
  f.heightScale = std::exp(std::clamp(-f.falloff * cameraHeight, -kMaxExponent, kMaxExponent));
  f.upInView = glm::vec3(view[1]);  // view x (0, 1, 0, 0)
  return f;
}

float FogFactor::fogDistance(float distance, float up) const {
  if (falloff <= 0.0f) return distance;
  const float climb = falloff * up;
  if (std::isinf(distance)) return climb > 0.0f ? std::min(heightScale / climb, kEndless) : kEndless;
  const float x = climb * distance;
  float g;
  if (std::abs(x) < 1e-3f) g = 1.0f - 0.5f * x;  // (1 - e^-x) / x to second order
  else g = (1.0f - std::exp(std::min(-x, kMaxExponent))) / x;
  return std::min(distance * heightScale * g, kEndless);
}

float FogFactor::at(const glm::vec3& viewPosition, bool background, const glm::vec3& rayOrigin) const {
  const glm::vec3 ray = viewPosition - rayOrigin;
  const float distance = glm::length(ray);
  const float up = glm::dot(ray / distance, upInView);
  FogFactor fromOrigin = *this;  // the ray starts dot(origin, up) higher than the eye
  fromOrigin.heightScale *=
      std::exp(std::clamp(-falloff * glm::dot(rayOrigin, upInView), -kMaxExponent, kMaxExponent));
  const float d = fromOrigin.fogDistance(background ? std::numeric_limits<float>::infinity() : distance, up);
  switch (mode) {
    case FogMode::Linear: return std::clamp(offset - scale * d, 0.0f, 1.0f);
    case FogMode::Exponential: return std::exp2(-std::min(scale * d, 126.0f));
    case FogMode::SquaredExponential: {
      const float s = std::min(scale * d, 12.0f);
      return std::exp2(-s * s);
    }
  }
  return 1.0f;
}

EffectInfo FogEffect::info() { return {"fog", "Fog", true, false, {"fog"}, {}}; }

StageDecl FogEffect::stage(FogMode mode, bool height) {
  StageDecl stage;
  stage.name = "fog";
  stage.variant = std::string(fogModeName(mode)) + (height ? ",height" : "");
  stage.file = "fog/fog.glsl";
  stage.function = "fogStage";
  stage.defines = {{"FOG_MODE", std::to_string(static_cast<int>(mode))}, {"FOG_HEIGHT", height ? "1" : "0"}};
  stage.input = "scene-color";
  stage.position = true;
  // u_fogColor (vec3) and u_fogFactor (vec2) in two rows; with the height, u_fogUpInView (vec3) in a third, its
  // two floats beside the vec3s.
  stage.uniformVectors = height ? 3 : 2;
  stage.uniforms = [height](const gl::Program& program, const PassContext& context) {
    const FogSettings& fog = context.settings().of<FogSettings>();
    const FogFactor factor = FogFactor::of(fog, context.camera().view);
    program.set("u_fogColor", fog.color);
    program.set("u_fogFactor", glm::vec2(factor.offset, factor.scale));
    if (height) {
      program.set("u_fogFalloff", factor.falloff);
      program.set("u_fogHeightScale", factor.heightScale);
      program.set("u_fogUpInView", factor.upInView);
    }
  };
  return stage;
}

std::vector<StageDecl> FogEffect::stages() {
  std::vector<StageDecl> stages;
  for (FogMode mode : kFogModes)
    for (bool height : {false, true}) stages.push_back(stage(mode, height));
  return stages;
}

void FogEffect::plan(FramePlanner& planner) {
  const FogSettings& settings = planner.settings().of<FogSettings>();
  if (!settings.enabled) return;
  // A per-pixel stage: it runs inside the lighting where it can, and as a pass of its own otherwise.
  planner.add(stagePass(resources_, stage(settings.mode, settings.heightFalloff > 0.0f), "scene-color"));
}

}  // namespace obscura
