#pragma once
// Per-pass wall time on native contexts, bounded by glFinish on both sides so each pass is measured alone
// (obscura-render --bench, obscura-tune's report).
#include <chrono>
#include <vector>

#include "core/Renderer.h"

namespace obscura {

class FinishPassTimer : public PassTimer {
 public:
  void begin(Pass) override {
    glFinish();
    start_ = std::chrono::steady_clock::now();
  }
  void end(Pass pass) override {
    glFinish();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    samples_[static_cast<size_t>(pass)].push_back(ms);
  }
  const std::vector<double>& samples(Pass pass) const { return samples_[static_cast<size_t>(pass)]; }

 private:
  std::chrono::steady_clock::time_point start_;
  std::vector<double> samples_[static_cast<size_t>(Pass::Count)];
};

}  // namespace obscura
