#pragma once
// What the command-line tools (obscura-render, obscura-reference, obscura-tune) share: the scene and the camera they
// are asked for, so every tool reads the same options the same way and sees the same pixels, and the AO radius they
// choose for a scene when none is given.
//
//   --scene FILE       glTF 2.0 (.gltf or .glb); default: the built-in scene
//   --scene-scale S    multiplies the scene's world positions (a model authored in millimetres: 0.001)
//   --camera FILE      camera JSON (scene/Camera.h)
//   --fit              frame the scene's bounds (the default for --scene without --camera)
//   --size WxH         output size, overriding the camera's
#include <string>
#include <vector>

#include "scene/Camera.h"
#include "scene/Scene.h"

namespace obscura {

struct SceneInput {
  std::string scenePath;   // empty: the built-in scene
  std::string cameraPath;  // empty: the built-in scene's camera, or --fit for a file
  bool fit = false;
  float sceneScale = 1.0f;
  int width = 0, height = 0;  // 0: from the camera (default 1280 x 720)

  // If args[i] is one of the options above, consumes it (and its value, advancing i) and returns true.
  // Throws InputError("--option: problem") on a bad value.
  bool parseOption(const std::vector<std::string>& args, size_t& i);
  // Throws InputError if the options contradict each other (--camera with --fit).
  void check() const;

  // What load() returns: the scene (scaled), its camera (the JSON file's, the one fitted to the scene at the
  // output size, or the built-in scene's; --size applied) and the loader's warnings, not yet printed.
  struct Loaded {
    Scene scene;
    Camera camera;
    std::vector<std::string> warnings;
  };
  // Reads the camera file, then the scene. Throws InputError naming the file on a bad one. The warnings are left to
  // the caller to print (printWarnings) once every input has been checked, so that a refusal stays one line.
  Loaded load() const;
  // Prints `warnings` to stderr as "<tool>: warning: <file>: ...".
  void printWarnings(const char* tool, const std::vector<std::string>& warnings) const;
};

// The usage lines of the options above, for --help texts.
std::string sceneInputUsage();

// The AO radius when the command line gives none: defaultAoRadius(scene) (scene/SceneScale.h: 5 % of the scene's
// bounding-sphere diameter to two significant figures; the built-in scene's own 1 m), with a one-line note on stderr,
// e.g. "obscura-render: AO radius 42 (5 % of the scene's bounding-sphere diameter, 836.05; set --ao.radius to
// choose)". `option` is the tool's radius option. obscura-render and obscura-reference call it alike, so that they
// pick the same radius for the same scene.
float chooseDefaultAoRadius(const char* tool, const char* option, const Scene& scene);
// The --help lines saying so, for the tool's radius option.
std::string defaultAoRadiusUsage(const std::string& option);

// Multiplies every instance's world transform by a uniform scale.
void scaleScene(Scene& scene, float scale);

// "WxH" with both sides in 1 .. Camera::kMaxSize. Throws InputError("--size: ...").
void parseSize(const std::string& text, int* width, int* height);
// A whole number in 1 .. max. Throws InputError("<option>: ...").
int parseCount(const std::string& option, const std::string& text, int max);

}  // namespace obscura
