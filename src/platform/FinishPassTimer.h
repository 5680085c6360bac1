#pragma once
// Per-pass wall time on native contexts, bounded by glFinish on both sides so each pass is measured alone.
// (obscura-render --bench, obscura-bench, obscura-tune; the web page uses EXT_disjoint_timer_query instead.)
#include <array>
#include <chrono>
#include <vector>

#include "core/Renderer.h"

namespace obscura {

class FinishPassTimer : public PassTimer {
 public:
  void begin(Pass pass) override;
  void end(Pass pass) override;
  void clear();

  const std::vector<double>& samples(Pass pass) const { return samples_[static_cast<size_t>(pass)]; }
  // Median of the recorded milliseconds (0 when the pass never ran): robust to the odd scheduler hiccup.
  double medianMs(Pass pass) const;

 private:
  std::chrono::steady_clock::time_point start_;
  std::array<std::vector<double>, static_cast<size_t>(Pass::Count)> samples_;
};

}  // namespace obscura
