#pragma once
// Error figures between two AO images (a reference and a test image, e.g. the ray-traced reference and SAO), over
// geometry pixels only, plus the pictures the report shows. Plain C++ on grey images; no GL, no Embree.
//
// AO values are the images' red channel / 255 (1 = unoccluded). Over the pixels the mask marks as geometry:
//   MAE   mean |B - A|
//   RMSE  sqrt(mean (B - A)^2)
//   bias  mean (B - A): negative when B is darker than A
//   Pearson correlation  cov(A, B) / (sd(A) sd(B)): how well B's variation follows A's, whatever B's scale and
//         offset (an AO that darkens the right places too weakly still correlates). 0 where either image is
//         constant over the mask (an all-white AO explains none of the reference's variation).
//   SSIM  mean of the SSIM map (Wang, Bovik, Sheikh, Simoncelli, "Image Quality Assessment: From Error Visibility to
//         Structural Similarity", IEEE TIP 2004, eq. 13) with their constants: an 11x11 Gaussian window of
//         sigma 1.5 (renormalised where it leaves the image), C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 1. The map is
//         computed on the whole images and averaged over geometry pixels.
//   halo  MAE over geometry pixels within `haloWidth` pixels (Chebyshev distance) of a depth discontinuity, where
//         screen-space AO goes wrong: it darkens the far side of a silhouette with occluders that are far in front
//         (halos) and misses what the near side hides. A discontinuity lies between 4-neighbours whose linear depths
//         (the depth view: (-z - near)/(far - near), background 1) differ by more than
//         `relativeJump * min(d1, d2) + quantisationSlack` (the slack absorbs the depth view's 8-bit steps, so a
//         slanted plane is not mistaken for one). Reported alongside: the MAE over the remaining geometry pixels.
#include <cstdint>
#include <string>
#include <vector>

#include "scene/Scene.h"

namespace obscura {

// One channel as floats in [0, 1], rows top to bottom.
struct GreyImage {
  int width = 0, height = 0;
  std::vector<float> values;

  float at(int x, int y) const { return values[static_cast<size_t>(y) * width + x]; }
  static GreyImage fromRed(const Image& image);  // red / 255
};

struct DiscontinuityOptions {
  int haloWidth = 3;                // pixels
  float relativeJump = 0.1f;        // of the nearer linear depth
  float quantisationSlack = 2.0f / 255.0f;
};

// Pixels next to a depth discontinuity of `depth`, dilated by options.haloWidth (a square neighbourhood), by side:
// kNearSide on the nearer surface (where occlusion from behind the silhouette is missed), kFarSide on the farther one
// (where the nearer object's halo falls); 0 elsewhere.
constexpr std::uint8_t kNearSide = 1, kFarSide = 2;
std::vector<std::uint8_t> discontinuityBand(const GreyImage& depth, const DiscontinuityOptions& options);

// The SSIM map of two same-sized images (Wang et al. 2004), one value per pixel.
std::vector<float> ssimMap(const GreyImage& a, const GreyImage& b);

struct AoComparison {
  std::size_t pixels = 0;          // geometry pixels compared
  std::size_t haloPixels = 0;      // of which within the discontinuity band (0 when no depth was given)
  double mae = 0, rmse = 0, bias = 0, ssim = 0;
  double pearson = 0;
  double haloMae = 0, interiorMae = 0;  // MAE inside / outside the band
  double haloBias = 0;                  // mean B - A inside the band (negative: B darker there, a halo)
  std::size_t farSidePixels = 0;        // of the band's, those on the far side (kFarSide)
  double nearSideMae = 0, farSideMae = 0;
};

// Compares B against A over mask pixels (mask: 1 geometry; empty: every pixel). `haloBand` (discontinuityBand of
// the depth view) may be empty: no halo figures. `computeSsim` false leaves ssim 0 and saves most of the time (the
// fit's objective does not always need it). Throws InputError if the sizes differ or no pixel is selected.
AoComparison compareAo(const GreyImage& a, const GreyImage& b, const std::vector<std::uint8_t>& mask,
                       const std::vector<std::uint8_t>& haloBand = {}, bool computeSsim = true);

// Pixels whose red channel is at least 128 (the mask view: geometry 255, background 0).
std::vector<std::uint8_t> maskFromImage(const Image& image);

// Signed difference B - A as colour: white where equal, red where B is darker, blue where B is lighter, full
// strength at |B - A| >= fullScale; background (mask 0) mid grey.
Image differenceImage(const GreyImage& a, const GreyImage& b, const std::vector<std::uint8_t>& mask,
                      float fullScale = 0.25f);

// Images of equal height side by side, separated by `gap` black columns.
Image sideBySide(const std::vector<Image>& panels, int gap = 4);

// Checks that two images have the same size; throws InputError("<what>: WxH differs from WxH").
void requireSameSize(const Image& a, const Image& b, const std::string& what);

}  // namespace obscura
