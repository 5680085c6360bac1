#pragma once
// What the command-line tools (obscura-render, obscura-reference, obscura-tune) share: the scene, the moment of its
// animation and the camera they are asked for, so every tool reads the same options the same way and sees the same
// pixels, and the AO radius they choose for a scene when none is given.
//
//   --scene FILE       glTF 2.0 (.gltf or .glb); default: the built-in scene
//   --scene-scale S    multiplies the scene's world positions (a model authored in millimetres: 0.001)
//   --time T           the moment drawn, in seconds on the scene's timeline (default 0; looping)
//   --animation A      which animation plays: a name, an index, all or none (the rest pose); default: the first
//   --camera FILE      camera JSON (scene/Camera.h)
//   --camera-node C    one of the file's cameras: its node's or its camera's name, or its index among them; it moves
//                      with the animation (FrameOptions::sceneCamera)
//   --fit              frame the scene's bounds at rest (the default for --scene without --camera)
//   --orthographic     the camera (the built-in, the fitted or --camera's) made orthographic, with the view it had at
//                      its target (Camera::asOrthographic)
//   --size WxH         output size, overriding the camera's
#include <string>
#include <vector>

#include "scene/Animation.h"
#include "scene/Camera.h"
#include "scene/Scene.h"

namespace obscura {

struct SceneInput {
  std::string scenePath;   // empty: the built-in scene
  std::string cameraPath;  // empty: the built-in scene's camera, or --fit for a file
  std::string cameraNode;  // --camera-node as given (read once the scene is)
  bool fit = false;
  bool orthographic = false;
  float sceneScale = 1.0f;
  double time = 0.0;      // seconds on the scene's timeline (scene/Animation.h: looping, as the renderer's default)
  std::string animation;  // as given (it names one of the scene's animations, so it is read once the scene is)
  int width = 0, height = 0;  // 0: from the camera (default 1280 x 720)

  // If args[i] is one of the options above, consumes it (and its value, advancing i) and returns true.
  // Throws InputError("--option: problem") on a bad value.
  bool parseOption(const std::vector<std::string>& args, size_t& i);
  // Throws InputError if the options contradict each other (--camera, --fit and --camera-node; --orthographic with
  // --camera-node, whose camera has its own projection).
  void check() const;

  // What load() returns: the scene (scaled, at rest), the animation chosen (--animation read against the scene's
  // animations; the first by default), its camera (the JSON file's, the one fitted to the scene's bounds at rest at
  // the output size, the built-in scene's, or the scene camera's posed at --time; --size applied, else a scene
  // camera's frame at 1280 pixels wide) and the loader's warnings, not yet printed.
  struct Loaded {
    Scene scene;
    AnimationChoice animation;
    Camera camera;
    int sceneCamera = -1;  // --camera-node's index in Scene::cameras, for FrameOptions::sceneCamera; -1: none
    Bounds bounds;         // the scene's at rest (a scene camera's planes hug them, as the Renderer's do)
    std::vector<std::string> warnings;
    // The scene as posed at `seconds` (evaluatePose, posedScene: skinned and morphed meshes baked), for a tool that
    // draws the scene itself rather than through the renderer (the ray-traced reference); a scene with nothing to
    // pose comes back as it is.
    Scene posedAt(double seconds) const;
    // The camera at `seconds`: the scene camera's where the animation puts it then, else `camera` (which does not move).
    Camera cameraAt(double seconds) const;
  };
  // Reads the camera file, then the scene. Throws InputError naming the file on a bad one, and one listing the
  // scene's animations for an --animation it does not have. The warnings are left to the caller to print
  // (printWarnings) once every input has been checked, so that a refusal stays one line.
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

// Scales the scene's world uniformly: every instance's rest transform, and the node hierarchy's roots with the
// animation keys that move or scale them, so that a posed (animated, skinned) scene scales alike.
void scaleScene(Scene& scene, float scale);

// "WxH" with both sides in 1 .. Camera::kMaxSize. Throws InputError("--size: ...").
void parseSize(const std::string& text, int* width, int* height);
// A whole number in 1 .. max. Throws InputError("<option>: ...").
int parseCount(const std::string& option, const std::string& text, int max);

}  // namespace obscura
