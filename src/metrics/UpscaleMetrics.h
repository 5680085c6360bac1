#pragma once
// How close an upscaled frame (rendered at a render scale below 1, then upscaled: frame/Resolution.h) comes to the
// frame rendered at the full size, its reference. Both are display images of one size (RGBA8, the colour channels
// compared; values in 0 .. 255):
//   MAE        mean |B - A| over every pixel and channel;
//   edge MAE   the same over the reference's edge pixels: those whose luma (Rec. 601, FXAA's) differs from one of
//              their four neighbours by more than kEdgeStep, where an upscale loses or keeps sharpness;
//   flat MAE   over the rest.
// No GL: the GPU tests (tests/test_upscale.cpp) and obscura-bench's resolution section read the frames back and
// compare them here.
#include <cstddef>

#include "scene/Scene.h"

namespace obscura {

struct UpscaleError {
  double mae = 0.0, edgeMae = 0.0, flatMae = 0.0;
  std::size_t edgePixels = 0, pixels = 0;
};

constexpr int kEdgeStep = 24;  // of 255: a luma step an eye sees as an edge, not a gradient's

// Throws InputError when the sizes differ.
UpscaleError upscaleError(const Image& reference, const Image& upscaled);

}  // namespace obscura
