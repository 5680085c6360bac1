// Measures the candidate two-channel normal encodings (src/encoding/NormalEncoding.h) over a dense set of directions,
// back-facing ones included, and prints max / mean / 99th-percentile angular error. The G-buffer uses the winner;
// its figures are recorded in NormalEncoding.h and the README.
//
//   obscura-normal-study [directions]      (default 200000)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "encoding/NormalEncoding.h"

using namespace obscura;

int main(int argc, char** argv) {
  const int count = argc > 1 ? std::atoi(argv[1]) : 200000;
  if (count < 1000) {
    std::fprintf(stderr, "obscura-normal-study: need at least 1000 directions\n");
    return 2;
  }
  const std::vector<glm::vec3> dirs = encodingTestDirections(count);
  struct Candidate {
    const char* name;
    NormalEncodingKind kind;
  };
  const Candidate candidates[] = {{"octahedral-254", NormalEncodingKind::Octahedral254},
                                  {"octahedral-255", NormalEncodingKind::Octahedral255},
                                  {"lambert-azimuthal", NormalEncodingKind::LambertAzimuthal}};
  std::printf("%zu directions (incl. poles, axes and a back-facing band), 8 bits per channel\n", dirs.size());
  std::printf("%-20s %12s %12s %12s %16s\n", "encoding", "max (deg)", "mean (deg)", "p99 (deg)", "back-facing max");
  for (const Candidate& c : candidates) {
    std::vector<double> errors;
    errors.reserve(dirs.size());
    double backMax = 0.0, sum = 0.0;
    for (const glm::vec3& n : dirs) {
      const auto bytes = encodeNormal(n, c.kind);
      const double e = angleBetweenDegrees(n, decodeNormal(bytes[0], bytes[1], c.kind));
      errors.push_back(e);
      sum += e;
      if (n.z < 0.0f) backMax = std::max(backMax, e);
    }
    std::sort(errors.begin(), errors.end());
    std::printf("%-20s %12.3f %12.3f %12.3f %16.3f%s\n", c.name, errors.back(), sum / static_cast<double>(errors.size()),
                errors[errors.size() * 99 / 100], backMax, c.kind == kGBufferNormalEncoding ? "   <- G-buffer" : "");
  }
  return 0;
}
