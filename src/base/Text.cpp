#include "base/Text.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "base/Error.h"

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

float parseNumber(const std::string& option, const std::string& text, double min, double max) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value))
    throw InputError(option + ": expected a number, got '" + text + "'");
  if (value < min || value > max) {
    char message[160];
    std::snprintf(message, sizeof message, "%s: %s is out of range (%g .. %g)", option.c_str(), text.c_str(), min, max);
    throw InputError(message);
  }
  return static_cast<float>(value);
}

}  // namespace obscura
