#include "apps/SceneInput.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include <glm/gtc/matrix_transform.hpp>

#include "base/Error.h"
#include "base/Text.h"
#include "scene/BuiltinScene.h"
#include "scene/GltfLoader.h"
#include "scene/SceneScale.h"

namespace obscura {

void parseSize(const std::string& text, int* width, int* height) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X'))
    throw InputError("--size: expected WxH (e.g. 1280x720), got '" + text + "'");
  if (w < 1 || h < 1 || w > Camera::kMaxSize || h > Camera::kMaxSize)
    throw InputError("--size: " + text + " is out of range (1 .. " + std::to_string(Camera::kMaxSize) + " per side)");
  *width = w;
  *height = h;
}

int parseCount(const std::string& option, const std::string& text, int max) {
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0') throw InputError(option + ": expected a whole number, got '" + text + "'");
  if (value < 1 || value > max)
    throw InputError(option + ": " + text + " is out of range (1 .. " + std::to_string(max) + ")");
  return static_cast<int>(value);
}

namespace {
float parseScale(const std::string& text) { return parseNumber("--scene-scale", text, 1e-6, 1e6); }
}  // namespace

bool SceneInput::parseOption(const std::vector<std::string>& args, size_t& i) {
  const std::string& arg = args[i];
  auto value = [&]() -> const std::string& {
    if (i + 1 >= args.size()) throw InputError(arg + ": missing value");
    return args[++i];
  };
  if (arg == "--scene") scenePath = value();
  else if (arg == "--scene-scale") sceneScale = parseScale(value());
  else if (arg == "--camera") cameraPath = value();
  else if (arg == "--fit") fit = true;
  else if (arg == "--size") parseSize(value(), &width, &height);
  else return false;
  return true;
}

void SceneInput::check() const {
  if (fit && !cameraPath.empty()) throw InputError("--camera and --fit exclude each other");
}

SceneInput::Loaded SceneInput::load() const {
  Loaded loaded;
  if (!cameraPath.empty()) loaded.camera = Camera::fromJsonFile(cameraPath);
  GltfLoadReport report;
  loaded.scene = scenePath.empty() ? makeBuiltinScene() : loadGltfFile(scenePath, &report);
  loaded.warnings = std::move(report.warnings);
  if (sceneScale != 1.0f) scaleScene(loaded.scene, sceneScale);
  if (cameraPath.empty()) {
    // Fitted at the output size: the frustum's aspect decides how much room the bounds need.
    if (fit || !scenePath.empty())
      loaded.camera = Camera::fit(loaded.scene.worldBounds(), width > 0 ? width : 1280, height > 0 ? height : 720);
    else
      loaded.camera = builtinSceneCamera();
  }
  if (width > 0) {
    loaded.camera.width = width;
    loaded.camera.height = height;
  }
  return loaded;
}

void SceneInput::printWarnings(const char* tool, const std::vector<std::string>& warnings) const {
  for (const std::string& warning : warnings)
    std::cerr << tool << ": warning: " << scenePath << ": " << warning << "\n";
}

std::string sceneInputUsage() {
  return "  --scene FILE      .gltf or .glb; default: the built-in scene\n"
         "  --scene-scale S   multiply the scene's positions by S (e.g. 0.001 for a model in millimetres)\n"
         "  --camera FILE     camera JSON {eye, target, up, fovy_deg, near, far, width, height}\n"
         "  --fit             frame the scene's bounds (the default for --scene without --camera)\n"
         "  --size WxH        output size (overrides the camera's width and height; default 1280x720)\n";
}

float chooseDefaultAoRadius(const char* tool, const char* option, const Scene& scene) {
  const float radius = defaultAoRadius(scene);
  std::cerr << tool << ": AO radius " << formatShortest(radius) << " (" << defaultAoRadiusReason(scene) << "; set "
            << option << " to choose)\n";
  return radius;
}

std::string defaultAoRadiusUsage(const std::string& option) {
  return "AO radius: without " + option +
         ", 5 % of the scene's bounding-sphere diameter, to two significant figures (the\n"
         "built-in scene: 1, the metre it was designed for); it follows --scene-scale, and a note on stderr says\n"
         "which radius was chosen.\n";
}

void scaleScene(Scene& scene, float scale) {
  const glm::mat4 scaling = glm::scale(glm::mat4(1.0f), glm::vec3(scale));
  for (Instance& instance : scene.instances) instance.world = scaling * instance.world;
  scene.designedAoRadius *= scale;  // a radius the scene was designed for scales with it (scene/SceneScale.h)
}

}  // namespace obscura
