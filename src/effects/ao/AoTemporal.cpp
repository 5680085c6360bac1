#include "effects/ao/AoTemporal.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "frame/FrameContext.h"

namespace obscura::AoTemporal {
namespace {

std::uint32_t sequenceIndex(std::uint64_t frameIndex) {
  return static_cast<std::uint32_t>(frameIndex % static_cast<std::uint64_t>(kSequenceLength)) + 1;
}

}  // namespace

glm::vec2 frameOffset(std::uint64_t frameIndex) {
  const std::uint32_t k = sequenceIndex(frameIndex);
  return {halton(k, 2), halton(k, 3)};
}

float ditherOffset(std::uint64_t frameIndex) { return halton(sequenceIndex(frameIndex), 5); }

bool keepsHistory(const glm::vec3& normal, const glm::vec3& centre, const glm::vec3& historyPoint, float tolerance) {
  return std::abs(glm::dot(normal, historyPoint - centre)) <= tolerance;
}

bool rectifies(float relativeMotionPixels) { return relativeMotionPixels > kRelativeMotionPixels; }

int maxFramesAt(float relativeMotionPixels, int maxFrames) {
  if (!rectifies(relativeMotionPixels)) return maxFrames;
  return static_cast<int>(std::clamp(std::floor(2.0f * kLagPixels / relativeMotionPixels), 1.0f,
                                     static_cast<float>(maxFrames)));
}

Accumulated accumulate(float history, int historyFrames, float current, float low, float high, int maxFrames) {
  const int frames = std::min(historyFrames + 1, maxFrames);
  if (historyFrames <= 0) return {current, frames};
  const float previous = std::clamp(history, low, high);
  return {previous + (current - previous) / static_cast<float>(frames), frames};
}

std::uint8_t quantise(float ao, float dither) {
  const float level = std::floor(std::clamp(ao, 0.0f, 1.0f) * 255.0f + dither);
  return static_cast<std::uint8_t>(std::min(level, 255.0f));
}

}  // namespace obscura::AoTemporal
