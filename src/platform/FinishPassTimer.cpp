#include "platform/FinishPassTimer.h"

#include <algorithm>

namespace obscura {

void FinishPassTimer::begin(const std::string&) {
  glFinish();
  start_ = std::chrono::steady_clock::now();
}

void FinishPassTimer::end(const std::string& pass) {
  glFinish();
  samples_[pass].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count());
}

void FinishPassTimer::clear() { samples_.clear(); }

const std::vector<double>& FinishPassTimer::samples(const std::string& pass) const {
  static const std::vector<double> none;
  const auto it = samples_.find(pass);
  return it == samples_.end() ? none : it->second;
}

double FinishPassTimer::medianMs(const std::string& pass) const {
  std::vector<double> s = samples(pass);
  if (s.empty()) return 0.0;
  std::nth_element(s.begin(), s.begin() + static_cast<long>(s.size() / 2), s.end());
  return s[s.size() / 2];
}

}  // namespace obscura
