#include "apps/CompareCommandLine.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "base/Error.h"
#include "base/Text.h"
#include "scene/ImageIo.h"

namespace obscura {

std::string compareUsage() {
  return "usage: obscura-compare A.png B.png [--mask M.png] [--depth D.png] [--halo-width K] [--halo-jump J]\n"
         "                       [--diff OUT.png] [--side-by-side OUT.png] [--json]\n"
         "\n"
         "Error of AO image B against AO image A (e.g. A: obscura-reference, B: obscura-render --view ao), over the\n"
         "pixels the mask marks as geometry: MAE, RMSE, bias (mean B - A), SSIM, Pearson correlation, and the MAE\n"
         "within K pixels of the depth view's discontinuities (where screen-space AO's halos live) and elsewhere.\n"
         "  --mask M.png          mask view (geometry 255, background 0); default: every pixel\n"
         "  --depth D.png         depth view (obscura-render or obscura-reference --view depth): halo figures\n"
         "  --halo-width K        pixels around a discontinuity (0 .. 64, default 3)\n"
         "  --halo-jump J         relative linear-depth jump that makes a discontinuity (0 .. 10, default 0.1)\n"
         "  --diff OUT.png        signed difference: red where B is darker, blue where lighter (full at 0.25)\n"
         "  --side-by-side OUT    A | B | difference in one image\n"
         "  --json                print the figures as one JSON object\n";
}

CompareOptions parseCompareCommandLine(const std::vector<std::string>& args) {
  CompareOptions options;
  std::vector<std::string> positional;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw InputError(arg + ": missing value");
      return args[++i];
    };
    if (arg == "--help" || arg == "-h") options.help = true;
    else if (arg == "--mask") options.maskPath = value();
    else if (arg == "--depth") options.depthPath = value();
    else if (arg == "--halo-width") {
      const float width = parseNumber(arg, value(), 0, 64);
      if (width != std::floor(width)) throw InputError("--halo-width: expected a whole number, got '" + args[i] + "'");
      options.discontinuities.haloWidth = static_cast<int>(width);
    }
    else if (arg == "--halo-jump") options.discontinuities.relativeJump = parseNumber(arg, value(), 0, 10);
    else if (arg == "--diff") options.diffPath = value();
    else if (arg == "--side-by-side") options.sideBySidePath = value();
    else if (arg == "--json") options.json = true;
    else if (arg.rfind("--", 0) == 0) throw InputError("unknown option '" + arg + "' (see --help)");
    else positional.push_back(arg);
  }
  if (options.help) return options;
  if (positional.size() != 2)
    throw InputError("expected two images A.png B.png, got " + std::to_string(positional.size()) + " (see --help)");
  options.referencePath = positional[0];
  options.testPath = positional[1];
  return options;
}

int runCompare(const CompareOptions& options) {
  if (options.help) {
    std::cout << compareUsage();
    return 0;
  }
  try {
    const Image a = readPng(options.referencePath), b = readPng(options.testPath);
    requireSameSize(a, b, options.testPath);
    std::vector<std::uint8_t> mask;
    if (!options.maskPath.empty()) {
      const Image maskImage = readPng(options.maskPath);
      requireSameSize(a, maskImage, options.maskPath);
      mask = maskFromImage(maskImage);
    }
    GreyImage depth;
    if (!options.depthPath.empty()) {
      const Image depthImage = readPng(options.depthPath);
      requireSameSize(a, depthImage, options.depthPath);
      depth = GreyImage::fromRed(depthImage);
    }
    const GreyImage greyA = GreyImage::fromRed(a), greyB = GreyImage::fromRed(b);
    const std::vector<std::uint8_t> band =
        options.depthPath.empty() ? std::vector<std::uint8_t>() : discontinuityBand(depth, options.discontinuities);
    const AoComparison c = compareAo(greyA, greyB, mask, band);

    if (!options.diffPath.empty() || !options.sideBySidePath.empty()) {
      const Image diff = differenceImage(greyA, greyB, mask);
      if (!options.diffPath.empty()) writePng(options.diffPath, diff);
      if (!options.sideBySidePath.empty()) writePng(options.sideBySidePath, sideBySide({a, b, diff}));
    }

    const double share = 100.0 * static_cast<double>(c.pixels) / (static_cast<double>(a.width) * a.height);
    const bool halo = !options.depthPath.empty();
    if (options.json) {
      std::printf("{\"pixels\": %zu, \"mae\": %.6f, \"rmse\": %.6f, \"bias\": %.6f, \"ssim\": %.6f, \"pearson\": %.6f",
                  c.pixels, c.mae, c.rmse, c.bias, c.ssim, c.pearson);
      if (halo)
        std::printf(", \"halo_pixels\": %zu, \"halo_mae\": %.6f, \"interior_mae\": %.6f, \"halo_bias\": %.6f, "
                    "\"near_side_mae\": %.6f, \"far_side_mae\": %.6f, \"far_side_pixels\": %zu",
                    c.haloPixels, c.haloMae, c.interiorMae, c.haloBias, c.nearSideMae, c.farSideMae, c.farSidePixels);
      std::printf("}\n");
    } else {
      std::printf("pixels   %zu (%.1f%% of the image)\n", c.pixels, share);
      std::printf("MAE      %.4f\nRMSE     %.4f\nbias     %+.4f (mean B - A)\nSSIM     %.4f\nPearson  %.4f\n", c.mae,
                  c.rmse, c.bias, c.ssim, c.pearson);
      if (halo) {
        std::printf("halo     MAE %.4f over %zu pixels (%.1f%%) within %d px of depth jumps > %g relative\n",
                    c.haloMae, c.haloPixels, 100.0 * static_cast<double>(c.haloPixels) / static_cast<double>(c.pixels),
                    options.discontinuities.haloWidth, static_cast<double>(options.discontinuities.relativeJump));
        std::printf("         near side MAE %.4f, far side MAE %.4f over %zu pixels; bias %+.4f\n", c.nearSideMae,
                    c.farSideMae, c.farSidePixels, c.haloBias);
        std::printf("interior MAE %.4f\n", c.interiorMae);
      }
    }
    return 0;
  } catch (const InputError& e) {
    std::cerr << "obscura-compare: " << e.what() << "\n";
    return 2;
  }
}

}  // namespace obscura
