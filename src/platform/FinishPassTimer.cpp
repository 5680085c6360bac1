#include "platform/FinishPassTimer.h"

#include <algorithm>

namespace obscura {

void FinishPassTimer::begin(Pass) {
  glFinish();
  start_ = std::chrono::steady_clock::now();
}

void FinishPassTimer::end(Pass pass) {
  glFinish();
  samples_[static_cast<size_t>(pass)].push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count());
}

void FinishPassTimer::clear() {
  for (auto& s : samples_) s.clear();
}

double FinishPassTimer::medianMs(Pass pass) const {
  std::vector<double> s = samples(pass);
  if (s.empty()) return 0.0;
  std::nth_element(s.begin(), s.begin() + static_cast<long>(s.size() / 2), s.end());
  return s[s.size() / 2];
}

}  // namespace obscura
