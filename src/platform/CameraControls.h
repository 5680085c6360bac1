#pragma once
// Orbit, pan and zoom on a Camera, shared by obscura-view and the web page so the same gesture moves the camera the
// same way on both. Drags are in pixels of a viewport `viewportHeight` pixels tall: dragging across the full height
// turns the camera half a turn, and panning keeps the target point under the cursor.
//
// A camera handed to the viewers (the built-in view, one read from a shared URL) renders exactly as given; only a
// move refits its near and far planes to the scene (fitDepthRange).
#include "scene/Camera.h"
#include "scene/Scene.h"

namespace obscura {

// Turns the eye around the target: horizontal drags about the camera's up axis, vertical drags over the top (the
// view direction stays at least ~3 degrees away from straight up or down).
void orbitCamera(Camera& camera, float dxPixels, float dyPixels, int viewportHeight);
// Moves eye and target together in the view plane, at the target's depth.
void panCamera(Camera& camera, float dxPixels, float dyPixels, int viewportHeight);
// Scales the eye's distance to the target by `factor` (> 1 moves away), within 1e-3 .. 1e3 times `sceneRadius`; an
// orthographic camera's half height scales with it (its view grows as a perspective camera's would).
void zoomCamera(Camera& camera, float factor, float sceneRadius);
// Near and far hugging the scene's bounding sphere as seen from the eye, with far/near at most kMaxDepthRatio: the
// G-buffer's depth renderbuffer is 16-bit on WebGL 1, so a tiny near plane would cost depth precision far away.
void fitDepthRange(Camera& camera, const Bounds& scene);
constexpr float kMaxDepthRatio = 400.0f;  // the built-in camera's 40 m / 0.1 m

}  // namespace obscura
