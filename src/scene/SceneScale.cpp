#include "scene/SceneScale.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace obscura {

float roundToTwoSignificantFigures(float value) {
  if (value == 0.0f || !std::isfinite(value)) return value;
  const double v = value;
  // A step of one unit in the second significant figure; rounding may carry into a third digit (99.6 -> 100).
  const double step = std::pow(10.0, std::floor(std::log10(std::abs(v))) - 1.0);
  return static_cast<float>(std::round(v / step) * step);
}

float suggestedAoRadius(const Bounds& bounds) {
  if (bounds.empty()) return 1.0f;
  const float diameter = 2.0f * bounds.radius();
  if (!(diameter > 0.0f) || !std::isfinite(diameter)) return 1.0f;
  return std::clamp(roundToTwoSignificantFigures(kDefaultAoRadiusFraction * diameter), kMinAoRadius, kMaxAoRadius);
}

float defaultAoRadius(const Scene& scene) {
  if (scene.designedAoRadius > 0.0f) return scene.designedAoRadius;
  return suggestedAoRadius(scene.worldBounds());
}

std::string defaultAoRadiusReason(const Scene& scene) {
  if (scene.designedAoRadius > 0.0f) return "the radius the " + scene.name + " was designed for";
  const Bounds bounds = scene.worldBounds();
  if (bounds.empty() || !(bounds.radius() > 0.0f)) return "the scene has no extent to take 5 % of";
  char text[160];
  std::snprintf(text, sizeof text, "%g %% of the scene's bounding-sphere diameter, %.6g",
                static_cast<double>(kDefaultAoRadiusFraction * 100.0f), static_cast<double>(2.0f * bounds.radius()));
  return text;
}

}  // namespace obscura
