#include "scene/Camera.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "base/Error.h"

namespace obscura {

float Camera::fovyRadians() const { return glm::radians(fovyDegrees); }

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, up); }

glm::vec2 Camera::halfExtent(float outputAspect) const {
  float halfHeight = orthographic ? ymag : std::tan(fovyRadians() * 0.5f);
  // A frame wider than the output: the view grows vertically until the frame's width fits.
  if (frameAspect > 0.0f && outputAspect < frameAspect) halfHeight *= frameAspect / outputAspect;
  return glm::vec2(halfHeight * outputAspect, halfHeight);
}

float Camera::halfHeightAt(float distance, float outputAspect) const {
  const float halfHeight = halfExtent(outputAspect).y;
  return orthographic ? halfHeight : halfHeight * distance;
}

glm::mat4 Camera::projection(float outputAspect) const {
  const glm::vec2 half = halfExtent(outputAspect);
  if (orthographic) return glm::ortho(-half.x, half.x, -half.y, half.y, near, far);
  // glm::perspective over the fitted field of view (the same matrix as the unfitted one when nothing is fitted).
  const float fovy = frameAspect > 0.0f && outputAspect < frameAspect ? 2.0f * std::atan(half.y) : fovyRadians();
  return glm::perspective(fovy, outputAspect, near, far);
}

Camera Camera::asOrthographic() const {
  if (orthographic) return *this;
  Camera out = *this;
  out.orthographic = true;
  out.ymag = glm::length(target - eye) * std::tan(fovyRadians() * 0.5f);
  return out;
}

Camera Camera::asPerspective() const {
  if (!orthographic) return *this;
  Camera out = *this;
  out.orthographic = false;
  const glm::vec3 forward = glm::normalize(target - eye);
  out.eye = target - forward * (ymag / std::tan(fovyRadians() * 0.5f));
  return out;
}

void Camera::validate(const std::string& source) const {
  auto fail = [&](const char* field, const std::string& problem) {
    throw InputError(source + ": " + field + ": " + problem);
  };
  auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite(eye)) fail("eye", "must be finite");
  if (!finite(target)) fail("target", "must be finite");
  if (!finite(up)) fail("up", "must be finite");
  const glm::vec3 forward = target - eye;
  if (glm::length(forward) < 1e-6f) fail("target", "must differ from eye");
  if (glm::length(glm::cross(glm::normalize(forward), up)) < 1e-4f)
    fail("up", "must not be parallel to the viewing direction (or zero)");
  if (!(fovyDegrees >= 1.0f && fovyDegrees <= 170.0f)) fail("fovy_deg", "must be in 1 .. 170 degrees");
  if (orthographic) {
    if (!(ymag > 0.0f && ymag <= 1e9f)) fail("ymag", "must be in 0 .. 1e9 (the view's half height)");
    // Orthographic depth is linear: a near plane at the eye costs no precision.
    if (!(near >= 0.0f && std::isfinite(near))) fail("near", "must be >= 0");
    if (!(far > near && std::isfinite(far))) fail("far", "must be greater than near");
  } else {
    if (!(near > 0.0f && std::isfinite(near))) fail("near", "must be > 0");
    if (!(far > near && std::isfinite(far))) fail("far", "must be greater than near");
    if (far / near > 1e6f) fail("far", "far/near must be at most 1e6 (16-bit linear depth)");
  }
  if (!(frameAspect >= 0.0f && frameAspect <= 1e3f))
    fail(orthographic ? "xmag" : "aspect_ratio", "the frame's aspect ratio must be in 0 .. 1000");
  if (width < 1 || width > kMaxSize) fail("width", "must be in 1 .. " + std::to_string(kMaxSize));
  if (height < 1 || height > kMaxSize) fail("height", "must be in 1 .. " + std::to_string(kMaxSize));
}

Camera Camera::fromJson(const std::string& text, const std::string& source) {
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(source + ": malformed JSON at byte " + std::to_string(e.byte) + ": " +
                     std::string(e.what()).substr(std::string(e.what()).find(':') + 2));
  }
  if (!json.is_object()) throw InputError(source + ": expected a JSON object");
  Camera camera;
  auto vec3Field = [&](const char* key, glm::vec3& out, bool required) {
    if (!json.contains(key)) {
      if (required) throw InputError(source + ": " + key + ": missing (expected [x, y, z])");
      return;
    }
    const auto& v = json[key];
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
      throw InputError(source + ": " + key + ": expected an array of three numbers");
    out = glm::vec3(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
  };
  auto numberField = [&](const char* key, float& out) {
    if (!json.contains(key)) return;
    if (!json[key].is_number()) throw InputError(source + ": " + key + ": expected a number");
    out = json[key].get<float>();
  };
  auto intField = [&](const char* key, int& out) {
    if (!json.contains(key)) return;
    const auto& v = json[key];
    if (!v.is_number_integer() && !(v.is_number() && v.get<double>() == std::floor(v.get<double>())))
      throw InputError(source + ": " + key + ": expected a whole number");
    const double value = v.get<double>();
    if (value < 1 || value > kMaxSize)
      throw InputError(source + ": " + key + ": must be in 1 .. " + std::to_string(kMaxSize));
    out = static_cast<int>(value);
  };
  static const char* known[] = {"eye",  "target", "up",    "fovy_deg", "focal_length_mm", "sensor_height_mm",
                                "near", "far",    "width", "height",   "type",            "ymag",
                                "xmag", "aspect_ratio"};
  for (const auto& item : json.items()) {
    bool ok = false;
    for (const char* k : known) ok = ok || item.key() == k;
    if (!ok) throw InputError(source + ": unknown field '" + item.key() + "'");
  }
  vec3Field("eye", camera.eye, true);
  vec3Field("target", camera.target, true);
  vec3Field("up", camera.up, false);
  numberField("fovy_deg", camera.fovyDegrees);
  // A physical camera's lens: the field of view a sensor `h` tall sees through focal length F, 2 atan(h / (2 F)).
  if (json.contains("focal_length_mm") || json.contains("sensor_height_mm")) {
    if (json.contains("fovy_deg"))
      throw InputError(source + ": fovy_deg: give either it or focal_length_mm (with sensor_height_mm), not both");
    if (!json.contains("focal_length_mm"))
      throw InputError(source + ": sensor_height_mm: needs focal_length_mm");
    float focal = 0.0f, sensor = kDefaultSensorHeightMm;
    numberField("focal_length_mm", focal);
    numberField("sensor_height_mm", sensor);
    if (!(focal > 0.0f && focal <= 1e5f)) throw InputError(source + ": focal_length_mm: must be in 0 .. 100000");
    if (!(sensor > 0.0f && sensor <= 1e3f)) throw InputError(source + ": sensor_height_mm: must be in 0 .. 1000");
    camera.fovyDegrees = glm::degrees(2.0f * std::atan(sensor / (2.0f * focal)));
  }
  numberField("near", camera.near);
  numberField("far", camera.far);
  intField("width", camera.width);
  intField("height", camera.height);
  if (json.contains("type")) {
    const auto& type = json["type"];
    if (!type.is_string() || (type != "perspective" && type != "orthographic"))
      throw InputError(source + ": type: expected \"perspective\" or \"orthographic\"");
    camera.orthographic = type == "orthographic";
  }
  if (camera.orthographic) {
    if (!json.contains("ymag")) throw InputError(source + ": ymag: missing (an orthographic camera's half height)");
    if (json.contains("aspect_ratio"))
      throw InputError(source + ": aspect_ratio: an orthographic camera's frame is xmag / ymag");
    numberField("ymag", camera.ymag);
    if (json.contains("xmag")) {
      float xmag = 0.0f;
      numberField("xmag", xmag);
      if (!(xmag > 0.0f && std::isfinite(xmag))) throw InputError(source + ": xmag: must be > 0");
      if (camera.ymag > 0.0f) camera.frameAspect = xmag / camera.ymag;
    }
  } else {
    for (const char* key : {"ymag", "xmag"})
      if (json.contains(key)) throw InputError(source + ": " + key + ": only an orthographic camera has it");
    numberField("aspect_ratio", camera.frameAspect);
    if (json.contains("aspect_ratio") && !(camera.frameAspect > 0.0f))
      throw InputError(source + ": aspect_ratio: must be > 0");
  }
  camera.validate(source);
  return camera;
}

Camera Camera::fromJsonFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open camera file");
  std::ostringstream text;
  text << file.rdbuf();
  return fromJson(text.str(), path);
}

std::string Camera::toJson() const {
  nlohmann::json json = {{"eye", {eye.x, eye.y, eye.z}},
                         {"target", {target.x, target.y, target.z}},
                         {"up", {up.x, up.y, up.z}},
                         {"fovy_deg", fovyDegrees},
                         {"near", near},
                         {"far", far},
                         {"width", width},
                         {"height", height}};
  if (orthographic) {
    json["type"] = "orthographic";
    json["ymag"] = ymag;
    if (frameAspect > 0.0f) json["xmag"] = ymag * frameAspect;
  } else if (frameAspect > 0.0f) {
    json["aspect_ratio"] = frameAspect;
  }
  return json.dump();
}

Camera Camera::fit(const Bounds& bounds, int width, int height, float fovyDegrees) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fovyDegrees = fovyDegrees;
  const float radius = std::max(bounds.empty() ? 1.0f : bounds.radius(), 1e-3f);
  const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
  // The bounding sphere fits the narrower of the two fields of view.
  const float halfY = camera.fovyRadians() * 0.5f;
  const float halfX = std::atan(std::tan(halfY) * camera.aspect());
  const float distance = radius / std::sin(std::min(halfX, halfY));
  const glm::vec3 direction = glm::normalize(glm::vec3(0.55f, 0.45f, 1.0f));
  camera.target = center;
  camera.eye = center + direction * distance;
  camera.near = std::max(distance - radius * 1.05f, distance * 1e-3f);
  camera.far = distance + radius * 1.05f;
  return camera;
}

Camera cameraOfScene(const SceneCamera& source, const glm::mat4& world, const Bounds& sceneBounds, int width,
                     int height) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.eye = glm::vec3(world[3]);
  // The node's axes without its scale (glTF: the camera looks down the node's -z, +y up).
  const glm::vec3 back(world[2]), up(world[1]);
  const glm::vec3 forward = glm::length(back) > 0.0f ? -glm::normalize(back) : glm::vec3(0.0f, 0.0f, -1.0f);
  camera.up = glm::length(up) > 0.0f ? glm::normalize(up) : glm::vec3(0.0f, 1.0f, 0.0f);
  const float radius = std::max(sceneBounds.empty() ? 1.0f : sceneBounds.radius(), 1e-3f);
  const glm::vec3 center = sceneBounds.empty() ? camera.eye + forward : sceneBounds.center();
  camera.target = camera.eye + forward * std::max(glm::dot(center - camera.eye, forward), radius * 1e-2f);
  camera.orthographic = source.orthographic;
  camera.frameAspect = source.frameAspect();
  if (source.orthographic) camera.ymag = source.ymag;
  else camera.fovyDegrees = glm::degrees(source.yfov);
  // The planes hug the scene's bounding sphere within the file's (an infinite far plane: the sphere's far side), as
  // fitted cameras' do: the 16-bit linear depth spans what is there (2CylinderEngine's camera gives 0.05 .. 1e6 for a
  // model 1000 units across, a depth step of 15 units).
  const float distance = glm::length(center - camera.eye), reach = radius * 1.05f;
  const float fileFar = source.zfar > 0.0f ? source.zfar : std::numeric_limits<float>::infinity();
  camera.near = std::max(source.znear, distance - reach);
  camera.far = std::min(fileFar, distance + reach);
  if (!(camera.near < camera.far)) {  // nothing of the scene between the file's planes: keep them
    camera.near = source.znear;
    camera.far = source.zfar > 0.0f ? source.zfar : std::max(distance + reach, source.znear * 2.0f + 1e-3f);
  }
  if (!camera.orthographic) camera.near = std::max(camera.near, camera.far * 1e-6f);
  return camera;
}

glm::mat4 sceneCameraWorld(const Scene& scene, int index, const ScenePose& pose) {
  const SceneCamera& camera = scene.cameras.at(static_cast<size_t>(index));
  if (camera.node >= 0 && static_cast<size_t>(camera.node) < pose.nodeWorld.size())
    return pose.nodeWorld[static_cast<size_t>(camera.node)];
  return camera.world;
}

Camera sceneCameraAt(const Scene& scene, int index, const ScenePose& pose, const Bounds& bounds, int width,
                     int height) {
  return cameraOfScene(scene.cameras.at(static_cast<size_t>(index)), sceneCameraWorld(scene, index, pose), bounds,
                       width, height);
}

int parseSceneCamera(const std::vector<SceneCamera>& cameras, const std::string& text, const std::string& what) {
  for (size_t i = 0; i < cameras.size(); ++i)
    if (!text.empty() && (cameras[i].nodeName == text || cameras[i].name == text)) return static_cast<int>(i);
  char* end = nullptr;
  const long index = std::strtol(text.c_str(), &end, 10);
  if (!text.empty() && *end == '\0' && index >= 0 && static_cast<size_t>(index) < cameras.size())
    return static_cast<int>(index);
  std::string choices;
  for (size_t i = 0; i < cameras.size(); ++i)
    choices += (i ? ", " : "") + std::to_string(i) + " '" + cameras[i].label(i) + "'";
  if (choices.empty()) throw InputError(what + " '" + text + "': the scene has no cameras");
  throw InputError(what + " '" + text + "' is not one of the scene's cameras: " + choices);
}

std::string sceneCameraKey(const std::vector<SceneCamera>& cameras, int index) {
  const std::string label = cameras.at(static_cast<size_t>(index)).label(static_cast<size_t>(index));
  try {
    if (parseSceneCamera(cameras, label) == index) return label;
  } catch (const InputError&) {
  }
  return std::to_string(index);
}

int heightForWidth(const SceneCamera& camera, int width) {
  const float aspect = camera.frameAspect() > 0.0f ? camera.frameAspect() : 1280.0f / 720.0f;
  return std::clamp(static_cast<int>(std::lround(static_cast<float>(width) / aspect)), 1, Camera::kMaxSize);
}

}  // namespace obscura
