#pragma once
// A symmetric perspective camera: right-handed, OpenGL conventions (looks down -z in view space), metres.
//
// JSON form (camera files, the page's URL state):
//   {"eye":[x,y,z], "target":[x,y,z], "up":[x,y,z], "fovy_deg":f, "near":n, "far":f, "width":W, "height":H}
// eye and target are required; the rest default to up (0,1,0), fovy 50, near 0.1, far 100, 1280 x 720. A physical
// camera may give "focal_length_mm" (and "sensor_height_mm", default 24: full frame) instead of fovy_deg: the field of
// view is then 2 atan(sensor / (2 focal)) (depth of field's lens, docs/depth-of-field.md). toJson writes fovy_deg.
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

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

  static constexpr int kMaxSize = 16384;
  static constexpr float kDefaultSensorHeightMm = 24.0f;

  float aspect() const { return static_cast<float>(width) / static_cast<float>(height); }
  float fovyRadians() const;
  glm::mat4 view() const;
  glm::mat4 projection() const;

  // Throws InputError("<source>: <field>: <problem>") on anything unusable.
  void validate(const std::string& source) const;
  static Camera fromJson(const std::string& text, const std::string& source);
  static Camera fromJsonFile(const std::string& path);
  std::string toJson() const;

  // Frames `bounds` from above and to the front-right, with near/far hugging the bounding sphere.
  static Camera fit(const Bounds& bounds, int width, int height, float fovyDegrees = 50.0f);
};

}  // namespace obscura
