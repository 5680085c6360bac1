#include "metrics/AoMetrics.h"

#include <algorithm>
#include <cmath>

#include "base/Error.h"

namespace obscura {
namespace {

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

// Separable convolution with a normalised kernel, renormalised where it leaves the image (no padding values).
// Double precision: SSIM takes variances as E[x^2] - E[x]^2, which cancels badly in float.
std::vector<double> gaussianFilter(const std::vector<double>& values, int width, int height,
                                   const std::vector<double>& kernel) {
  const int half = static_cast<int>(kernel.size() / 2);
  std::vector<double> rows(values.size()), out(values.size());
  auto filter = [&](const std::vector<double>& in, std::vector<double>& result, bool horizontal) {
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        double sum = 0.0, weight = 0.0;
        for (int k = -half; k <= half; ++k) {
          const int sx = horizontal ? x + k : x, sy = horizontal ? y : y + k;
          if (sx < 0 || sy < 0 || sx >= width || sy >= height) continue;
          const double w = kernel[static_cast<size_t>(k + half)];
          sum += w * in[static_cast<size_t>(sy) * width + sx];
          weight += w;
        }
        result[static_cast<size_t>(y) * width + x] = sum / weight;
      }
    }
  };
  filter(values, rows, true);
  filter(rows, out, false);
  return out;
}

}  // namespace

GreyImage GreyImage::fromRed(const Image& image) {
  GreyImage grey;
  grey.width = image.width;
  grey.height = image.height;
  grey.values.resize(static_cast<size_t>(image.width) * image.height);
  for (size_t i = 0; i < grey.values.size(); ++i) grey.values[i] = image.rgba[4 * i] / 255.0f;
  return grey;
}

void requireSameSize(const Image& a, const Image& b, const std::string& what) {
  if (a.width != b.width || a.height != b.height)
    throw InputError(what + ": " + sizeText(b.width, b.height) + " differs from " + sizeText(a.width, a.height));
}

std::vector<std::uint8_t> maskFromImage(const Image& image) {
  std::vector<std::uint8_t> mask(static_cast<size_t>(image.width) * image.height);
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = image.rgba[4 * i] >= 128;
  return mask;
}

std::vector<std::uint8_t> discontinuityBand(const GreyImage& depth, const DiscontinuityOptions& options) {
  const int w = depth.width, h = depth.height;
  auto at = [w](int x, int y) { return static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x); };
  // Both pixels of a jumping pair are marked, by side: the halo lives on the far side, the missed occlusion on the
  // near side.
  enum : std::uint8_t { kNearEdge = 1, kFarEdge = 2 };
  std::vector<std::uint8_t> edge(static_cast<size_t>(w) * h, 0);
  auto mark = [&](size_t i, size_t j) {
    if (!(std::abs(depth.values[i] - depth.values[j]) >
          options.relativeJump * std::min(depth.values[i], depth.values[j]) + options.quantisationSlack))
      return;
    const bool iNearer = depth.values[i] < depth.values[j];
    edge[i] |= iNearer ? kNearEdge : kFarEdge;
    edge[j] |= iNearer ? kFarEdge : kNearEdge;
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) mark(at(x, y), at(x + 1, y));
      if (y + 1 < h) mark(at(x, y), at(x, y + 1));
    }
  // Within haloWidth (a square neighbourhood) of an edge pixel; the side is that of the nearest edge pixel (the far
  // side where a far-side edge pixel is at least as near as any near-side one). The distance is the square
  // neighbourhood's (Chebyshev), k + 1 for none, found separably per side: the nearest edge pixel along each row,
  // then over the rows within k, max(that, the rows' distance).
  const int k = std::max(0, options.haloWidth);
  auto nearest = [&](std::uint8_t side) {
    std::vector<int> rows(edge.size(), k + 1), distance(edge.size(), k + 1);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int sx = std::max(0, x - k); sx <= std::min(w - 1, x + k); ++sx)
          if (edge[at(sx, y)] & side) rows[at(x, y)] = std::min(rows[at(x, y)], std::abs(sx - x));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int sy = std::max(0, y - k); sy <= std::min(h - 1, y + k); ++sy)
          distance[at(x, y)] = std::min(distance[at(x, y)], std::max(rows[at(x, sy)], std::abs(sy - y)));
    return distance;
  };
  const std::vector<int> nearestNear = nearest(kNearEdge), nearestFar = nearest(kFarEdge);
  std::vector<std::uint8_t> band(edge.size(), 0);
  for (size_t i = 0; i < band.size(); ++i) {
    if (nearestFar[i] <= k && nearestFar[i] <= nearestNear[i]) band[i] = kFarSide;
    else if (nearestNear[i] <= k) band[i] = kNearSide;
  }
  return band;
}

std::vector<float> ssimMap(const GreyImage& a, const GreyImage& b) {
  // Wang et al. 2004, sec. III-C: 11x11 circular-symmetric Gaussian, standard deviation 1.5 samples.
  std::vector<double> kernel(11);
  for (int i = 0; i < 11; ++i) kernel[static_cast<size_t>(i)] = std::exp(-0.5 * (i - 5) * (i - 5) / (1.5 * 1.5));
  const int w = a.width, h = a.height;
  const size_t n = a.values.size();
  std::vector<double> va(a.values.begin(), a.values.end()), vb(b.values.begin(), b.values.end()), aa(n), bb(n), ab(n);
  for (size_t i = 0; i < n; ++i) {
    aa[i] = va[i] * va[i];
    bb[i] = vb[i] * vb[i];
    ab[i] = va[i] * vb[i];
  }
  const std::vector<double> muA = gaussianFilter(va, w, h, kernel), muB = gaussianFilter(vb, w, h, kernel);
  const std::vector<double> meanAA = gaussianFilter(aa, w, h, kernel), meanBB = gaussianFilter(bb, w, h, kernel),
                            meanAB = gaussianFilter(ab, w, h, kernel);
  constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;  // K1 = 0.01, K2 = 0.03, L = 1
  std::vector<float> map(n);
  for (size_t i = 0; i < n; ++i) {
    const double ma = muA[i], mb = muB[i];
    const double varA = meanAA[i] - ma * ma, varB = meanBB[i] - mb * mb;
    const double cov = meanAB[i] - ma * mb;
    const double numerator = (2 * ma * mb + c1) * (2 * cov + c2);
    map[i] = static_cast<float>(numerator / ((ma * ma + mb * mb + c1) * (varA + varB + c2)));
  }
  return map;
}

AoComparison compareAo(const GreyImage& a, const GreyImage& b, const std::vector<std::uint8_t>& mask,
                       const std::vector<std::uint8_t>& haloBand, bool computeSsim) {
  if (b.width != a.width || b.height != a.height)
    throw InputError("second image: " + sizeText(b.width, b.height) + " differs from " + sizeText(a.width, a.height));
  const size_t n = a.values.size();
  if (!mask.empty() && mask.size() != n) throw InputError("mask: size differs from the images");
  if (!haloBand.empty() && haloBand.size() != n) throw InputError("halo band: size differs from the images");

  const std::vector<float> ssim = computeSsim ? ssimMap(a, b) : std::vector<float>(n, 0.0f);
  AoComparison result;
  double sumAbs = 0, sumSq = 0, sumSigned = 0, sumSsim = 0, haloAbs = 0, haloSigned = 0, farAbs = 0;
  double sumA = 0, sumB = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!mask.empty() && !mask[i]) continue;
    const double d = static_cast<double>(b.values[i]) - a.values[i];
    ++result.pixels;
    sumA += a.values[i];
    sumB += b.values[i];
    sumAbs += std::abs(d);
    sumSq += d * d;
    sumSigned += d;
    sumSsim += ssim[i];
    if (!haloBand.empty() && haloBand[i]) {
      ++result.haloPixels;
      haloAbs += std::abs(d);
      haloSigned += d;
      if (haloBand[i] == kFarSide) {
        ++result.farSidePixels;
        farAbs += std::abs(d);
      }
    }
  }
  if (result.pixels == 0) throw InputError("mask: selects no pixel (no geometry in view?)");
  const double count = static_cast<double>(result.pixels);
  result.mae = sumAbs / count;
  result.rmse = std::sqrt(sumSq / count);
  result.bias = sumSigned / count;
  result.ssim = sumSsim / count;
  // Pearson's r from centred sums (a second pass: one-pass sums of squares lose the small variances AO has).
  const double meanA = sumA / count, meanB = sumB / count;
  double covAB = 0, varA = 0, varB = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!mask.empty() && !mask[i]) continue;
    const double da = a.values[i] - meanA, db = b.values[i] - meanB;
    covAB += da * db;
    varA += da * da;
    varB += db * db;
  }
  result.pearson = varA > 0 && varB > 0 ? covAB / std::sqrt(varA * varB) : 0.0;
  result.haloMae = result.haloPixels ? haloAbs / static_cast<double>(result.haloPixels) : 0.0;
  result.haloBias = result.haloPixels ? haloSigned / static_cast<double>(result.haloPixels) : 0.0;
  result.farSideMae = result.farSidePixels ? farAbs / static_cast<double>(result.farSidePixels) : 0.0;
  const size_t nearSide = result.haloPixels - result.farSidePixels;
  result.nearSideMae = nearSide ? (haloAbs - farAbs) / static_cast<double>(nearSide) : 0.0;
  const size_t interior = result.pixels - result.haloPixels;
  result.interiorMae = interior ? (sumAbs - haloAbs) / static_cast<double>(interior) : 0.0;
  return result;
}

Image differenceImage(const GreyImage& a, const GreyImage& b, const std::vector<std::uint8_t>& mask,
                      float fullScale) {
  Image image;
  image.width = a.width;
  image.height = a.height;
  image.rgba.resize(a.values.size() * 4);
  for (size_t i = 0; i < a.values.size(); ++i) {
    std::uint8_t* p = &image.rgba[4 * i];
    p[3] = 255;
    if (!mask.empty() && !mask[i]) {
      p[0] = p[1] = p[2] = 128;
      continue;
    }
    const float d = b.values[i] - a.values[i];
    const auto fade = static_cast<std::uint8_t>(std::lround(255.0f * (1.0f - std::min(1.0f, std::abs(d) / fullScale))));
    p[0] = d < 0.0f ? 255 : fade;  // darker than A: red
    p[1] = fade;
    p[2] = d < 0.0f ? fade : 255;  // lighter than A: blue
  }
  return image;
}

Image sideBySide(const std::vector<Image>& panels, int gap) {
  Image out;
  if (panels.empty()) return out;
  out.height = panels.front().height;
  for (const Image& panel : panels) {
    if (panel.height != out.height) throw InputError("side by side: panels differ in height");
    out.width += panel.width;
  }
  out.width += gap * static_cast<int>(panels.size() - 1);
  out.rgba.assign(static_cast<size_t>(out.width) * out.height * 4, 0);
  for (size_t i = 3; i < out.rgba.size(); i += 4) out.rgba[i] = 255;
  int left = 0;
  for (const Image& panel : panels) {
    for (int y = 0; y < panel.height; ++y)
      std::copy_n(&panel.rgba[static_cast<size_t>(y) * panel.width * 4], static_cast<size_t>(panel.width) * 4,
                  &out.rgba[(static_cast<size_t>(y) * out.width + left) * 4]);
    left += panel.width + gap;
  }
  return out;
}

}  // namespace obscura
