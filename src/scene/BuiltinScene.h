#pragma once
// The default scene, generated in code (no file needed): a room rich in creases and contacts for judging AO —
// floor and walls, a skirting ledge, columns on plinths, an arch on piers, stairs, spheres resting on the floor and
// in a corner, and stacked boxes. Metres, +y up.
#include "scene/Camera.h"
#include "scene/Scene.h"

namespace obscura {

Scene makeBuiltinScene();

// The camera the README image, the golden test and the benchmarks use for the built-in scene.
Camera builtinSceneCamera(int width = 1280, int height = 720);

}  // namespace obscura
