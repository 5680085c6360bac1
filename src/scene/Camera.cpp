#include "scene/Camera.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "base/Error.h"

namespace obscura {

float Camera::fovyRadians() const { return glm::radians(fovyDegrees); }

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, up); }

glm::mat4 Camera::projection() const { return glm::perspective(fovyRadians(), aspect(), near, far); }

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
  if (!(near > 0.0f && std::isfinite(near))) fail("near", "must be > 0");
  if (!(far > near && std::isfinite(far))) fail("far", "must be greater than near");
  if (far / near > 1e6f) fail("far", "far/near must be at most 1e6 (16-bit linear depth)");
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
                                "near", "far",    "width", "height"};
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

}  // namespace obscura
