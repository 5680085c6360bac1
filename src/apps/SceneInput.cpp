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

// Seconds as a double: a time the tools compute (obscura-render --frames: T + k / F) and one given must be the same
// number, not the same float.
double parseTime(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value))
    throw InputError("--time: expected a number of seconds, got '" + text + "'");
  if (value < 0.0 || value > 1e6) throw InputError("--time: " + text + " is out of range (0 .. 1e+06 seconds)");
  return value;
}

}  // namespace

bool SceneInput::parseOption(const std::vector<std::string>& args, size_t& i) {
  const std::string& arg = args[i];
  auto value = [&]() -> const std::string& {
    if (i + 1 >= args.size()) throw InputError(arg + ": missing value");
    return args[++i];
  };
  if (arg == "--scene") scenePath = value();
  else if (arg == "--scene-scale") sceneScale = parseScale(value());
  else if (arg == "--time") time = parseTime(value());
  else if (arg == "--animation") {
    animation = value();
    if (animation.empty()) throw InputError("--animation: expected a name, an index, all or none, got ''");
  }
  else if (arg == "--camera") cameraPath = value();
  else if (arg == "--camera-node") {
    cameraNode = value();
    if (cameraNode.empty()) throw InputError("--camera-node: expected a camera's name or index, got ''");
  }
  else if (arg == "--fit") fit = true;
  else if (arg == "--orthographic") orthographic = true;
  else if (arg == "--size") parseSize(value(), &width, &height);
  else return false;
  return true;
}

void SceneInput::check() const {
  if (fit && !cameraPath.empty()) throw InputError("--camera and --fit exclude each other");
  if (!cameraNode.empty() && (fit || !cameraPath.empty()))
    throw InputError("--camera-node: the file's camera excludes --camera and --fit");
  if (!cameraNode.empty() && orthographic)
    throw InputError("--orthographic: the file's camera (--camera-node) has its own projection");
}

SceneInput::Loaded SceneInput::load() const {
  Loaded loaded;
  if (!cameraPath.empty()) loaded.camera = Camera::fromJsonFile(cameraPath);
  GltfLoadReport report;
  loaded.scene = scenePath.empty() ? makeBuiltinScene() : loadGltfFile(scenePath, &report);
  loaded.warnings = std::move(report.warnings);
  if (sceneScale != 1.0f) scaleScene(loaded.scene, sceneScale);
  if (!animation.empty()) {
    try {
      loaded.animation = parseAnimationChoice(loaded.scene, animation);
    } catch (const InputError& e) {
      throw InputError(std::string("--") + e.what());  // "--animation 'walk' is not in the scene; choices: ..."
    }
  }
  loaded.bounds = loaded.scene.worldBounds();
  if (!cameraNode.empty()) {
    try {
      loaded.sceneCamera = parseSceneCamera(loaded.scene, cameraNode, "--camera-node");
    } catch (const InputError& e) {
      throw InputError(scenePath.empty() ? std::string("--camera-node: the built-in scene has no cameras")
                                         : std::string(e.what()));
    }
    const SceneCamera& chosen = loaded.scene.cameras[static_cast<size_t>(loaded.sceneCamera)];
    const int w = width > 0 ? width : 1280, h = width > 0 ? height : heightForWidth(chosen, w);
    loaded.camera.width = w;
    loaded.camera.height = h;
    loaded.camera = loaded.cameraAt(time);
  } else if (cameraPath.empty()) {
    // Fitted at the output size: the frustum's aspect decides how much room the bounds need.
    if (fit || !scenePath.empty())
      loaded.camera = Camera::fit(loaded.bounds, width > 0 ? width : 1280, height > 0 ? height : 720);
    else
      loaded.camera = builtinSceneCamera();
  }
  if (width > 0) {
    loaded.camera.width = width;
    loaded.camera.height = height;
  }
  if (orthographic) loaded.camera = loaded.camera.asOrthographic();
  return loaded;
}

Camera SceneInput::Loaded::cameraAt(double seconds) const {
  if (sceneCamera < 0) return camera;
  PoseOptions options;
  options.animation = animation;
  options.loop = true;  // as FrameOptions' default
  return sceneCameraAt(scene, sceneCamera, evaluatePose(scene, seconds, options), bounds, camera.width,
                       camera.height);
}

Scene SceneInput::Loaded::posedAt(double seconds) const {
  if (!scene.animated()) return scene;
  PoseOptions options;
  options.animation = animation;
  options.loop = true;  // as FrameOptions' default, which obscura-render draws with
  return posedScene(scene, evaluatePose(scene, seconds, options));
}

void SceneInput::printWarnings(const char* tool, const std::vector<std::string>& warnings) const {
  for (const std::string& warning : warnings)
    std::cerr << tool << ": warning: " << scenePath << ": " << warning << "\n";
}

std::string sceneInputUsage() {
  return "  --scene FILE      .gltf or .glb; default: the built-in scene\n"
         "  --scene-scale S   multiply the scene's positions by S (e.g. 0.001 for a model in millimetres)\n"
         "  --time T          the moment of the scene's animation, in seconds (default 0; the timeline loops)\n"
         "  --animation A     which animation plays: its name, its index, all (together) or none (the rest pose);\n"
         "                    default: the first\n"
         "  --camera FILE     camera JSON {eye, target, up, fovy_deg, near, far, width, height}; an orthographic\n"
         "                    one: \"type\": \"orthographic\", \"ymag\": its half height in metres\n"
         "  --camera-node C   look through the file's camera C: its node's or its camera's name, or its index among\n"
         "                    the file's cameras (it moves with the animation; default size: its frame, 1280 wide)\n"
         "  --fit             frame the scene's bounds at rest (the default for --scene without --camera)\n"
         "  --orthographic    make the camera orthographic, keeping its view at its target\n"
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
  // The file's cameras see the scaled scene as they saw it: their depths and orthographic extents scale, and their
  // nodes (below) carry them to their scaled places.
  for (SceneCamera& camera : scene.cameras) {
    camera.world = scaling * camera.world;
    camera.znear *= scale;
    camera.zfar *= scale;
    camera.xmag *= scale;
    camera.ymag *= scale;
  }

  // A posed scene places its instances by the node hierarchy (scene/Animation.h), not by Instance::world: its roots
  // take the scale, and every node and skin joint below them follows. S * T * R * Sc = T(s t) * R * (s Sc) for a
  // uniform S, so a root's translation and scale are multiplied (a matrix root is premultiplied), and so are the
  // animation keys that set them, which would otherwise replace the scaled values.
  std::vector<bool> root(scene.nodes.size(), false);
  for (size_t n = 0; n < scene.nodes.size(); ++n) {
    Node& node = scene.nodes[n];
    if (node.parent >= 0) continue;
    root[n] = true;
    node.matrix = scaling * node.matrix;
    node.translation *= scale;
    node.scale *= scale;
  }
  for (Animation& animation : scene.animations) {
    auto scales = [&](const AnimationChannel& c) {
      return c.node >= 0 && static_cast<size_t>(c.node) < root.size() && root[static_cast<size_t>(c.node)] &&
             (c.path == AnimationPath::Translation || c.path == AnimationPath::Scale);
    };
    // A sampler shared with a channel that must stay as it is gets a scaled copy of its own.
    std::vector<bool> keptBySome(animation.samplers.size(), false);
    for (const AnimationChannel& channel : animation.channels)
      if (!scales(channel)) keptBySome[static_cast<size_t>(channel.sampler)] = true;
    std::vector<int> scaledSampler(animation.samplers.size(), -1);
    for (AnimationChannel& channel : animation.channels) {
      if (!scales(channel)) continue;
      const auto original = static_cast<size_t>(channel.sampler);
      if (scaledSampler[original] < 0) {
        size_t target = original;
        if (keptBySome[original]) {
          target = animation.samplers.size();
          animation.samplers.push_back(animation.samplers[original]);
        }
        // Values and CUBICSPLINE tangents alike: both are linear in the scaled quantity.
        for (float& value : animation.samplers[target].values) value *= scale;
        scaledSampler[original] = static_cast<int>(target);
      }
      channel.sampler = scaledSampler[original];
    }
  }
}

}  // namespace obscura
