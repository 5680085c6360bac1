#pragma once
// obscura-render's command line: parsing (every failure an InputError with one line saying what and where) and
// the run itself. A library so the tests can drive it.
#include <string>
#include <vector>

#include "apps/SceneInput.h"
#include "platform/HeadlessContext.h"
#include "renderer/RenderSettings.h"
#include "renderer/Renderer.h"

namespace obscura {

struct RenderOptions {
  SceneInput input;  // --scene, --scene-scale, --time, --animation, --camera, --fit, --size
  View view = View::Final;
  std::string outPath = "obscura.png";
  RenderSettings settings;
  // Whether the command line gave the AO radius (--ao.radius or --radius); if not, runRender takes the scene's
  // default (chooseDefaultAoRadius, scene/SceneScale.h) once the scene is loaded.
  bool radiusGiven = false;
  // --fps: the frame interval is 1 / fps; each frame's previous one is that much earlier (FrameOptions::previousTime,
  // from which motion vectors measure). --frames: how many frames are drawn, at time, time + 1 / fps, ..., through
  // one Renderer so that the history carries from frame to frame; the last is written.
  double fps = 60.0;
  int frames = 1;
  // --at K NAME=VALUE: from frame K of the sequence on (0 is the first), the parameter takes that value: a change
  // within the sequence, for what adapts over frames (auto exposure stepping through a light change). Repeatable.
  struct Change {
    int frame = 0;
    std::string name, value;
  };
  std::vector<Change> changes;
  // --accumulate N: write the brute-force reference of renderer/AccumulationReference.h instead (N sub-frames over the
  // --shutter interval, each --supersample times the size), for the final view only.
  int accumulate = 0;
  double shutter = 0.5;
  int supersample = 1;
  // --aperture N: write depth of field's reference of renderer/AccumulationReference.h instead (N pinhole renders from
  // points on the lens of the dof.* settings, each --supersample times the size), for the final view only.
  int aperture = 0;
  int benchFrames = 0;
  HeadlessBackend backend = HeadlessBackend::OSMesa;
  bool help = false;
};

RenderOptions parseRenderCommandLine(const std::vector<std::string>& args);
std::string renderUsage();
// Runs with the given options, writing the image (and bench figures to stdout). Returns the process exit status:
// 0 success, 2 bad input (message on stderr), 1 a GL failure.
int runRender(const RenderOptions& options);

}  // namespace obscura
