#pragma once
// What every pass of one frame shares: the camera of this frame and of the previous one, the sub-pixel jitter, the
// frame's index, and its time and the time of the pose motion vectors measure from (the scene's pose of both is in
// GpuScene: setPose).
//
// "Previous" is history: it survives from one frame to the next and is dropped, together with the history targets
// (frame/RenderTargetPool.h), when the output size changes, the scene changes or the context is lost (a new
// Renderer). A frame that starts afresh has hasPrevious false and its previous camera equal to its own.
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "frame/ViewReconstruction.h"
#include "gl/Program.h"
#include "scene/Camera.h"

namespace obscura {

struct FrameCamera {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};  // jittered when the frame is (jitter below)
  glm::mat4 unjitteredProjection{1.0f};  // the same without the jitter (motion vectors)
  ViewReconstruction reconstruction;
  float near = 0.1f, far = 100.0f;
  bool orthographic = false;
  glm::vec2 halfExtent{1.0f};  // Camera::halfExtent at the output's aspect: tan of the half fields of view, or metres
  int width = 1, height = 1;   // the size the frame renders at (the output's, or less: frame/Resolution.h)
  glm::vec2 jitter{0.0f};      // sub-pixel offset of the projection, in pixels (x right, y up)

  // `shearPixelsPerMetre`: a shift of the image that grows by that many pixels per metre of view depth (x right, y
  // up; FrameOptions::projectionShear), for an orthographic camera only. `aspect` 0: width / height. A frame rendered
  // below the output's size (frame/Resolution.h) takes the output's, so that rounding its sides does not stretch the
  // image.
  static FrameCamera from(const Camera& camera, int width, int height, glm::vec2 jitterPixels = glm::vec2(0.0f),
                          glm::vec2 shearPixelsPerMetre = glm::vec2(0.0f), float aspect = 0.0f);
  // How many pixels of a target `targetHeight` pixels tall a length of 1 m spans, facing the camera at depth z
  // (metres in front of it): projScale.x / z + projScale.y. Perspective: (height / (2 tan(fovy / 2)), 0), the SAO
  // paper's projScale; orthographic: (0, height / (2 ymag)), the same at every depth.
  glm::vec2 projScale(int targetHeight) const;
  float pixelsPerMetre(int targetHeight, float depth) const {
    const glm::vec2 scale = projScale(targetHeight);
    return scale.x / depth + scale.y;
  }
};

struct FrameContext {
  FrameCamera camera;
  FrameCamera previousCamera;  // the previous frame's; equal to `camera` when !hasPrevious
  bool hasPrevious = false;
  std::uint64_t index = 0;     // frames this Renderer has drawn before this one
  int historyFrames = 0;       // consecutive earlier frames the history survived (0: this frame starts afresh)
  double time = 0.0;           // seconds (FrameOptions::time)
  // The time of the previous pose (FrameOptions::previousTime, else the previous frame's time, else `time`).
  double previousTime = 0.0;
  double deltaTime = 0.0;      // time - previousTime
  double frameInterval = 1.0 / 60.0;  // real seconds since the previous frame (FrameOptions::frameInterval)
  bool linesOrPoints = false;  // the scene has points or lines to draw (effects/lines/LinesEffect.h)
  // The scene has a transparent layer (Material::transparent: effects/transparency), and transmission in it.
  bool transparent = false;
  bool transmission = false;
  // The scene needs the forward lighting (GpuScene::needsForwardLighting): the G-buffer writes no base colour.
  bool forwardLighting = false;
  // The pixels of the frame the scene may cover, x, y, width, height (GL window coordinates): GpuScene::coveredRect
  // at this frame's camera and size, or the whole frame where the caller drew the G-buffer or
  // RendererOptions::limitToScene is off. Set once before the passes run (Renderer::boundScene); PassContext::sceneRect
  // maps it to a target.
  glm::ivec4 sceneBounds{0};
  // The output's size. The frame renders at camera.width x camera.height, which is less where the render scale is
  // below 1 (frame/Resolution.h): then one pass at the end upscales the result into the output.
  int outputWidth = 1, outputHeight = 1;
  // The output framebuffer has a depth buffer of its own (the CLI's, the window's and the canvas's: platform/): a
  // pass that depth-tests, the forward lighting, may then draw straight into it when it is the frame's last.
  bool outputDepth = false;
  // And a stencil buffer (FXAA's pass over the output skips the pixels with no edge by it).
  bool outputStencil = false;
  bool upscaled() const { return outputWidth != camera.width || outputHeight != camera.height; }
};

// Halton low-discrepancy sequence (radical inverse of `index` in `base`), index >= 1: the jitter of temporal
// antialiasing takes (halton(i, 2), halton(i, 3)) - 0.5.
float halton(std::uint32_t index, std::uint32_t base);

// Sets the uniforms of shaders_es2/lib/reconstruct.glsl on the program in use: the far-plane ray (fullscreen.vert's
// v_farRay; enough where only its direction is used), and with it the depth-to-ray scale of viewPositionOnRay. The
// far plane's depth and the perspective switch are set where the program has them (a pass that reads the far
// plane's depth; one that follows eye rays).
void setFarRay(const gl::Program& program, const ViewReconstruction& reconstruction);
void setReconstruction(const gl::Program& program, const ViewReconstruction& reconstruction);

}  // namespace obscura
