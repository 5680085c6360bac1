#include "effects/ao/SaoKernel.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

namespace obscura::SaoKernel {

int greatestCommonDivisor(int a, int b) {
  while (b != 0) {
    const int t = a % b;
    a = b;
    b = t;
  }
  return a;
}

int bestSpiralTurns(int samples) {
  if (samples <= 2) return 1;
  // Tap i sits at (alpha_i, frac(tau alpha_i)) in (radius fraction, angle fraction): a rank-1 lattice. The best tau
  // keeps the closest two taps farthest apart, with the angle measured around the circle (Fibonacci-like choices:
  // 8 -> 3, 13 -> 5, 21 -> 8, as in the SAO reference code's tuned table).
  int best = 1;
  double bestSpacing = -1.0;
  for (int turns = 1; turns < samples; ++turns) {
    if (greatestCommonDivisor(turns, samples) != 1) continue;
    double minDistance = 1e9;
    for (int i = 0; i < samples; ++i) {
      for (int j = i + 1; j < samples; ++j) {
        const double dr = static_cast<double>(j - i) / samples;
        double da = std::fmod(static_cast<double>(turns) * (j - i) / samples, 1.0);
        da = std::min(da, 1.0 - da);
        minDistance = std::min(minDistance, std::sqrt(dr * dr + da * da));
      }
    }
    if (minDistance > bestSpacing + 1e-9) {
      bestSpacing = minDistance;
      best = turns;
    }
  }
  return best;
}

int hierarchyLevel(float tapDistance) {
  const int octave = static_cast<int>(std::floor(std::log2(std::max(tapDistance, 1.0f))));
  return std::clamp(octave - kLogMaxOffset, 0, kMaxMipLevel);
}

glm::ivec2 hierarchyLevelSize(glm::ivec2 levelZeroSize, int level) {
  return glm::max(levelZeroSize / (1 << level), glm::ivec2(1));
}

glm::ivec2 hierarchySourcePixel(glm::ivec2 p, int level, glm::ivec2 levelZeroSize) {
  for (int k = level; k >= 1; --k)
    p = glm::min(2 * p + glm::ivec2(p.y % 2, p.x % 2), hierarchyLevelSize(levelZeroSize, k - 1) - 1);
  return p;
}

glm::ivec2 aoCentrePixel(glm::ivec2 aoPixel, int aoScale, glm::ivec2 levelZeroSize) {
  return glm::min(aoPixel * aoScale, levelZeroSize - 1);
}

float rotationAngle(float pixelX, float pixelY) {
  const float inner = 0.06711056f * pixelX + 0.00583715f * pixelY;
  const float noise = 52.9829189f * (inner - std::floor(inner));
  return 6.28318530718f * (noise - std::floor(noise));
}

glm::vec2 tapDirection(int tapIndex, int samples, int spiralTurns, float rotation, float* radiusFraction) {
  const float alpha = (static_cast<float>(tapIndex) + 0.5f) * (1.0f / static_cast<float>(samples));
  const float angle = alpha * (static_cast<float>(spiralTurns) * 6.28318530718f) + rotation;
  *radiusFraction = alpha;
  return glm::vec2(std::cos(angle), std::sin(angle));
}

float diskRadiusPixels(float radius, float viewZ, glm::vec2 projScale, float maxRadiusPixels) {
  return std::min(radius * (projScale.x / -viewZ + projScale.y), maxRadiusPixels);
}

float tapObscurance(Falloff falloff, const glm::vec3& v, const glm::vec3& n, float radius, float bias) {
  const glm::vec3 u = v * (1.0f / radius);  // the tap in units of the radius
  const float uu = glm::dot(u, u);
  const float angular = std::max(glm::dot(u, n) - bias, 0.0f) / (uu + kEpsilon);
  if (falloff == Falloff::Alchemy2011) return uu < 1.0f ? angular : 0.0f;
  const float f = std::max(1.0f - uu, 0.0f);
  return f * f * f * angular;
}

float intensityScale(Falloff falloff, float intensity, int samples) {
  return intensity * (falloff == Falloff::Alchemy2011 ? 2.0f : 5.0f) / static_cast<float>(samples);
}

float ambientVisibility(Falloff falloff, float sum, int samples, float intensity, float contrast) {
  return std::pow(std::max(0.0f, 1.0f - sum * intensityScale(falloff, intensity, samples)), contrast);
}

}  // namespace obscura::SaoKernel
