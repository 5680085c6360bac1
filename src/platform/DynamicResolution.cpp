#include "platform/DynamicResolution.h"

#include <algorithm>
#include <cmath>

namespace obscura {

float DynamicResolution::scaleOf(int step) const {
  const double s = maxScale_ * std::exp2(-static_cast<double>(step) / kStepsPerHalving);
  return std::max(minScale_, static_cast<float>(s));
}

int DynamicResolution::ladderEnd() const {
  const double steps = std::log2(static_cast<double>(maxScale_) / minScale_) * kStepsPerHalving;
  return std::max(0, static_cast<int>(std::ceil(steps - 1e-9)));
}

void DynamicResolution::configure(double targetMs, float minScale, float maxScale) {
  maxScale = std::clamp(maxScale, 0.01f, 1.0f);
  minScale = std::clamp(minScale, 0.01f, maxScale);
  if (configured_ && targetMs == targetMs_ && minScale == minScale_ && maxScale == maxScale_) return;
  const float current = scale();
  targetMs_ = targetMs;
  minScale_ = minScale;
  maxScale_ = maxScale;
  lastStep_ = ladderEnd();
  if (!configured_) {
    configured_ = true;
    step_ = lastStep_;
    frames_ = 0;
    mean_ = 0.0;
    return;
  }
  int nearest = 0;
  for (int k = 1; k <= lastStep_; ++k)
    if (std::abs(scaleOf(k) - current) < std::abs(scaleOf(nearest) - current)) nearest = k;
  if (nearest != step_ || scaleOf(nearest) != current) moveTo(nearest);
}

void DynamicResolution::forget() {
  frames_ = 0;
  mean_ = 0.0;
  tooDear_ = -1;
}

void DynamicResolution::reset() {
  if (step_ != lastStep_) moveTo(lastStep_);
  frames_ = 0;
  mean_ = 0.0;
  tooDear_ = -1;
}

double DynamicResolution::predicted(int step) const {
  const double r = scaleOf(step) / scaleOf(step_);
  return mean_ * r * r;
}

bool DynamicResolution::refining() const {
  if (step_ == 0 || step_ - 1 <= tooDear_) return false;
  const int counted = frames_ - kSettleFrames;
  if (counted <= 0) return true;
  return counted < kUpFrames && predicted(step_ - 1) <= kUpHeadroom * targetMs_;
}

void DynamicResolution::moveTo(int step) {
  step_ = std::clamp(step, 0, lastStep_);
  frames_ = 0;
  mean_ = 0.0;
  ++changes_;
}

void DynamicResolution::measured(double frameMs, float scale) {
  if (!(frameMs > 0.0) || std::abs(scale - this->scale()) > 1e-6f) return;
  if (tooDear_ >= 0 && ++sinceTooDear_ > kRetryFrames) tooDear_ = -1;
  ++frames_;
  if (frames_ <= kSettleFrames) return;
  const int counted = frames_ - kSettleFrames;
  mean_ = counted == 1 ? frameMs : mean_ + kSmoothing * (frameMs - mean_);
  if (step_ < lastStep_ && mean_ > targetMs_ && (counted >= kMeanFrames || frameMs > kOverload * targetMs_)) {
    int next = step_ + 1;
    while (next < lastStep_ && predicted(next) > kDownHeadroom * targetMs_) ++next;
    tooDear_ = step_;
    sinceTooDear_ = 0;
    moveTo(next);
  } else if (step_ > 0 && counted >= kUpFrames) {
    int next = step_;
    while (next > 0 && next - 1 > tooDear_ && predicted(next - 1) <= kUpHeadroom * targetMs_) --next;
    if (next != step_) moveTo(next);
  }
}

}  // namespace obscura
