#pragma once
// obscura-render's command line: parsing (every failure an InputError with one line saying what and where) and
// the run itself. A library so the tests can drive it.
#include <string>
#include <vector>

#include "core/AoSettings.h"
#include "core/Renderer.h"
#include "platform/HeadlessContext.h"

namespace obscura {

struct RenderOptions {
  std::string scenePath;   // empty: the built-in scene
  std::string cameraPath;  // empty: the built-in scene's camera, or --fit for a file
  bool fit = false;
  int width = 0, height = 0;  // 0: from the camera (default 1280 x 720)
  View view = View::Final;
  std::string outPath = "obscura.png";
  AoSettings ao;
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
