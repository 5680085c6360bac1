#pragma once
// The default scene, generated in code (no file needed): a room rich in creases and contacts for judging AO —
// floor and walls, a skirting ledge, columns on plinths, an arch on piers, stairs, spheres resting on the floor and
// in a corner, and stacked boxes. Metres, +y up.
//
// By default (BuiltinSceneOptions::withMotion()) the room also holds what moves, so that motion (temporal filtering,
// motion vectors, skinning) can be seen without a file: a pendulum swinging under the arch (a rigid hierarchy: the
// bob's node is a child of the swinging pivot's) and a limb bending on a plinth left of the red sphere (a skin of
// three bones in a chain), both driven by one looping animation, "motion", kBuiltinMotionSeconds long. Its first keys
// are the rest pose, so at time 0 (where the viewers open, paused) or with no animation chosen they stand still:
// the pendulum hangs straight down, the limb stands upright.
//
// The still room (BuiltinSceneOptions::still()) is the scene as it was before anything moved, exactly: the AO
// accuracy figures, the tuned defaults (effects/ao/TunedDefaults.inc), the golden images and the benchmark figures were
// all measured on it, so the tools and tests that hold those figures ask for it by name.
#include "scene/Camera.h"
#include "scene/Scene.h"

namespace obscura {

struct BuiltinSceneOptions {
  // true: the room with the pendulum, the limb and their animation; false: the still room alone. The moving scene's
  // meshes, instances and materials begin with the still room's, unchanged, and add to them.
  bool moving = true;

  static BuiltinSceneOptions still() { return {false}; }
  static BuiltinSceneOptions withMotion() { return {true}; }
};

Scene makeBuiltinScene(const BuiltinSceneOptions& options = {});

// The moving scene's one animation: its name and its length (it loops: its last keys equal its first).
inline constexpr const char* kBuiltinMotionName = "motion";
inline constexpr float kBuiltinMotionSeconds = 4.0f;

// The camera the README image, the golden test and the benchmarks use for the built-in scene.
Camera builtinSceneCamera(int width = 1280, int height = 720);

}  // namespace obscura
