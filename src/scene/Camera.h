#pragma once
// A symmetric perspective or orthographic camera: right-handed, OpenGL conventions (looks down -z in view space),
// metres.
//
// JSON form (camera files):
//   {"eye":[x,y,z], "target":[x,y,z], "up":[x,y,z], "fovy_deg":f, "near":n, "far":f, "width":W, "height":H}
// eye and target are required; the rest default to up (0,1,0), fovy 50, near 0.1, far 100, 1280 x 720. A physical
// camera may give "focal_length_mm" (and "sensor_height_mm", default 24: full frame) instead of fovy_deg: the field of
// view is then 2 atan(sensor / (2 focal)) (depth of field's lens, docs/depth-of-field.md). toJson writes fovy_deg.
// An orthographic camera says "type": "orthographic" and gives "ymag": the half height of its view in metres (glTF's
// ymag), and may give "xmag" (the half width) as glTF does, which then sets the frame's aspect ratio (below); near
// may be 0. "type": "perspective" is the default. A perspective camera may give "aspect_ratio" (glTF's aspectRatio).
//
// The frame's aspect ratio (glTF's aspectRatio, or xmag / ymag). The output's own aspect decides the projection's;
// a camera that names the aspect its view was framed for keeps that whole view in any output: an output narrower than
// it widens the view vertically until the frame's width fits, one wider shows more at the sides (Blender's "auto"
// sensor fit). glTF leaves a mismatch to the client; stretching the image, the alternative, distorts it.
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/Animation.h"
#include "scene/Scene.h"

namespace obscura {

struct Camera {
  glm::vec3 eye{0.0f, 1.6f, 6.0f};
  glm::vec3 target{0.0f, 1.0f, 0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovyDegrees = 50.0f;
  float near = 0.1f;
  float far = 100.0f;
  int width = 1280;
  int height = 720;
  bool orthographic = false;
  float ymag = 1.0f;         // orthographic: the half height of the view, metres
  float frameAspect = 0.0f;  // the aspect ratio the view was framed for (width / height); 0: none, the output's

  static constexpr int kMaxSize = 16384;
  static constexpr float kDefaultSensorHeightMm = 24.0f;

  float aspect() const { return static_cast<float>(width) / static_cast<float>(height); }
  float fovyRadians() const;
  glm::mat4 view() const;
  glm::mat4 projection() const { return projection(aspect()); }
  // The projection for an output of aspect ratio `aspect`: glm::frustum or glm::ortho over halfExtent(aspect).
  glm::mat4 projection(float aspect) const;
  // Half the view's width and height for an output of aspect ratio `aspect`, the frame fitted as above: perspective,
  // tan of the half fields of view (the half extent at 1 m); orthographic, in metres.
  glm::vec2 halfExtent(float aspect) const;
  // The vertical distance from the axis to the view's top edge at `distance` metres in front of the eye.
  float halfHeightAt(float distance, float aspect) const;

  // The same view as seen at the target: an orthographic camera whose half height is the perspective view's at the
  // target's distance, or a perspective one (of this field of view) moved along its axis until its view at the target
  // is the orthographic one's. Near and far are kept (a caller that moves the camera refits them).
  Camera asOrthographic() const;
  Camera asPerspective() const;

  // Throws InputError("<source>: <field>: <problem>") on anything unusable.
  void validate(const std::string& source) const;
  static Camera fromJson(const std::string& text, const std::string& source);
  static Camera fromJsonFile(const std::string& path);
  std::string toJson() const;

  // Frames `bounds` from above and to the front-right, with near/far hugging the bounding sphere.
  static Camera fit(const Bounds& bounds, int width, int height, float fovyDegrees = 50.0f);
};

// A camera of the scene (Scene::cameras) where `world` (its node's world matrix, posed) places it: the eye at the
// node's origin, looking down its -z with its +y up (glTF 2.0, "Cameras"; the node's scale is ignored), seen at
// `width` x `height`. The target lies on the axis, level with the centre of `sceneBounds` (the view an orbit starts
// from). Its near and far planes hug the scene's bounding sphere within the file's znear and zfar (zfar absent:
// infinite), with far / near at most 1e6, so that the G-buffer's 16-bit linear depth spans what is there.
Camera cameraOfScene(const SceneCamera& camera, const glm::mat4& world, const Bounds& sceneBounds, int width,
                     int height);
// The world matrix that places scene camera `index` (Scene::cameras) in `pose`: its node's, or its fixed one.
glm::mat4 sceneCameraWorld(const Scene& scene, int index, const ScenePose& pose);
// Scene camera `index` at `pose`, seen at width x height (cameraOfScene with the scene's rest bounds `bounds`).
Camera sceneCameraAt(const Scene& scene, int index, const ScenePose& pose, const Bounds& bounds, int width,
                     int height);
// A scene camera by its index in Scene::cameras ("0", "1", ...) or the name of its node or of its camera (names
// before indices: a node named "2" is found by its name). Throws InputError("<what> '<text>' is not ...; the scene's
// cameras: 0 'Front', 1 'Top'") listing them, or saying the scene has none.
int parseSceneCamera(const std::vector<SceneCamera>& cameras, const std::string& text,
                     const std::string& what = "camera node");
inline int parseSceneCamera(const Scene& scene, const std::string& text, const std::string& what = "camera node") {
  return parseSceneCamera(scene.cameras, text, what);
}
// How state text names scene camera `index`: its label (SceneCamera::label) where that finds it again, else its index.
std::string sceneCameraKey(const std::vector<SceneCamera>& cameras, int index);
// The output size that shows a scene camera's frame at `width` pixels wide: height = width / the frame's aspect
// ratio, or 720 / 1280 of the width when it names none.
int heightForWidth(const SceneCamera& camera, int width);

}  // namespace obscura
