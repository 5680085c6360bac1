#include "base/Text.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace obscura {

std::string formatShortest(float value) {
  char text[48];
  if (std::fabs(value) < 1e7f) {
    for (int decimals = 0; decimals <= 9; ++decimals) {
      std::snprintf(text, sizeof text, "%.*f", decimals, static_cast<double>(value));
      if (std::strtof(text, nullptr) == value) return text;
    }
  }
  for (int digits = 1; digits <= 9; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, static_cast<double>(value));
    if (std::strtof(text, nullptr) == value) break;
  }
  return text;
}

}  // namespace obscura
