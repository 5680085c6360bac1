#include "metrics/UpscaleMetrics.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "base/Error.h"

namespace obscura {

UpscaleError upscaleError(const Image& reference, const Image& upscaled) {
  if (reference.width != upscaled.width || reference.height != upscaled.height)
    throw InputError("upscale error: the images are " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height) + " and " + std::to_string(upscaled.width) + "x" +
                     std::to_string(upscaled.height));
  const int w = reference.width, h = reference.height;
  std::vector<int> luma(static_cast<size_t>(w) * h);
  for (size_t i = 0; i < luma.size(); ++i) {
    const std::uint8_t* p = &reference.rgba[i * 4];
    luma[i] = (299 * p[0] + 587 * p[1] + 114 * p[2] + 500) / 1000;
  }
  UpscaleError error;
  double edgeSum = 0.0, flatSum = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      int step = 0;
      if (x > 0) step = std::max(step, std::abs(luma[i] - luma[i - 1]));
      if (x + 1 < w) step = std::max(step, std::abs(luma[i] - luma[i + 1]));
      if (y > 0) step = std::max(step, std::abs(luma[i] - luma[i - static_cast<size_t>(w)]));
      if (y + 1 < h) step = std::max(step, std::abs(luma[i] - luma[i + static_cast<size_t>(w)]));
      double sum = 0.0;
      for (int c = 0; c < 3; ++c) sum += std::abs(reference.rgba[i * 4 + c] - upscaled.rgba[i * 4 + c]);
      if (step > kEdgeStep) {
        edgeSum += sum;
        ++error.edgePixels;
      } else {
        flatSum += sum;
      }
    }
  error.pixels = static_cast<size_t>(w) * h;
  const size_t flatPixels = error.pixels - error.edgePixels;
  error.mae = (edgeSum + flatSum) / (3.0 * static_cast<double>(std::max<size_t>(error.pixels, 1)));
  error.edgeMae = edgeSum / (3.0 * static_cast<double>(std::max<size_t>(error.edgePixels, 1)));
  error.flatMae = flatSum / (3.0 * static_cast<double>(std::max<size_t>(flatPixels, 1)));
  return error;
}

}  // namespace obscura
