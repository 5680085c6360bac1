#pragma once
// Per-pass wall time on native contexts, bounded by glFinish on both sides so each pass is measured alone.
// (obscura-render --bench, obscura-bench, obscura-tune; the web page uses EXT_disjoint_timer_query instead.)
#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "renderer/Renderer.h"

namespace obscura {

class FinishPassTimer : public PassTimer {
 public:
  void begin(const std::string& pass) override;
  void end(const std::string& pass) override;
  void clear();

  // The recorded milliseconds of a pass (by name; empty when it never ran).
  const std::vector<double>& samples(const std::string& pass) const;
  // Median of the recorded milliseconds (0 when the pass never ran): robust to the odd scheduler hiccup.
  double medianMs(const std::string& pass) const;

 private:
  std::chrono::steady_clock::time_point start_;
  std::map<std::string, std::vector<double>> samples_;
};

}  // namespace obscura
