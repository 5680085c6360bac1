#pragma once
// obscura-reference's command line: the ray-traced AO reference (reference/AoReferenceTracer.h) of the same scene and
// camera obscura-render draws, written as the same views. A library so the tests can drive it.
#include <string>
#include <vector>

#include "apps/SceneInput.h"
#include "reference/AoReferenceTracer.h"

namespace obscura {

enum class ReferenceView { Ao, Depth, Mask };

struct ReferenceOptions {
  SceneInput input;  // --scene, --scene-scale, --time, --animation, --camera, --fit, --size
  ReferenceSettings trace;
  // Whether --radius was given; if not, runReference takes the scene's default radius (chooseDefaultAoRadius: the
  // same as obscura-render's for the same scene).
  bool radiusGiven = false;
  ReferenceView view = ReferenceView::Ao;
  std::string outPath = "reference.png";
  std::string depthOutPath, maskOutPath;  // optional extra views from the same trace
  bool help = false;
};

ReferenceOptions parseReferenceCommandLine(const std::vector<std::string>& args);
std::string referenceUsage();
// Traces and writes the images; prints one summary line to stdout. Returns the exit status: 0 success, 2 bad input
// (one line on stderr), 1 a ray-tracing failure.
int runReference(const ReferenceOptions& options);

}  // namespace obscura
