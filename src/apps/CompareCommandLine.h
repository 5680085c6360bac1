#pragma once
// obscura-compare's command line: error figures between two AO images over geometry pixels (metrics/AoMetrics.h),
// and the difference and side-by-side pictures. A library so the tests can drive it.
#include <string>
#include <vector>

#include "metrics/AoMetrics.h"

namespace obscura {

struct CompareOptions {
  std::string referencePath, testPath;  // A (the reference) and B (the image measured against it)
  std::string maskPath;                 // geometry 255, background 0; empty: every pixel
  std::string depthPath;                // the depth view, for the halo figures; empty: none
  DiscontinuityOptions discontinuities;
  std::string diffPath, sideBySidePath;
  bool json = false;
  bool help = false;
};

CompareOptions parseCompareCommandLine(const std::vector<std::string>& args);
std::string compareUsage();
// Prints the figures (text, or one JSON object with --json). Returns the exit status: 0, or 2 on bad input.
int runCompare(const CompareOptions& options);

}  // namespace obscura
