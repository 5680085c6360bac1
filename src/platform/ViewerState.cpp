#include "platform/ViewerState.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>

#include "base/Error.h"

namespace obscura {
namespace {

constexpr const char* kCameraKeys[] = {"eye", "target", "up", "fovy", "near", "far", "projection", "ymag", "camera"};

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Percent-encodes all but unreserved characters and the comma of vectors (an exponent's '+' would read as a space).
std::string encodeComponent(const std::string& text) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : text) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == ',') {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

std::string decodeComponent(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '+') {
      out += ' ';
    } else if (text[i] == '%' && i + 2 < text.size() && hexDigit(text[i + 1]) >= 0 && hexDigit(text[i + 2]) >= 0) {
      out += static_cast<char>(hexDigit(text[i + 1]) * 16 + hexDigit(text[i + 2]));
      i += 2;
    } else {
      out += text[i];
    }
  }
  return out;
}

float parseFloat(const std::string& key, const std::string& text) {
  char* end = nullptr;
  const float value = std::strtof(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value))
    throw InputError("state: " + key + ": expected a number, got '" + text + "'");
  return value;
}

glm::vec3 parseVector(const std::string& key, const std::string& text) {
  glm::vec3 v;
  size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t comma = text.find(',', start);
    if ((i < 2) != (comma != std::string::npos))
      throw InputError("state: " + key + ": expected x,y,z, got '" + text + "'");
    v[i] = parseFloat(key, text.substr(start, i < 2 ? comma - start : std::string::npos));
    start = comma + 1;
  }
  return v;
}

std::string formatVector(const glm::vec3& v) {
  return formatShortest(v.x) + "," + formatShortest(v.y) + "," + formatShortest(v.z);
}

}  // namespace

const std::vector<std::string>& ViewerState::viewModes() { return frameViewNames(); }

void ViewerState::setViewMode(const std::string& name) { view.name = parseView(name).name; }

void ViewerState::setDefault(const std::string& name, const std::string& value) {
  defaults.set(name, value);
  settings.set(name, value);
}

std::string ViewerState::cameraChoice() const {
  return sceneCamera < 0 ? "free" : sceneCameraKey(sceneCameras, sceneCamera);
}

void ViewerState::setCameraChoice(const std::string& text) {
  if (text == "free") {
    sceneCamera = -1;
    return;
  }
  if (sceneCameras.empty()) throw InputError("camera '" + text + "': the scene has no cameras of its own (only free)");
  sceneCamera = parseSceneCamera(sceneCameras, text, "camera");
}

void ViewerState::sceneLoaded(float radius) {
  defaultRadius = radius;
  if (!radiusGiven) settings.ao().radius = radius;
}

std::string ViewerState::toQuery() const {
  std::string query = "view=" + viewMode();
  auto add = [&](const std::string& key, const std::string& value) {
    query += "&" + key + "=" + encodeComponent(value);
  };
  if (view.compare != View().compare) add("compare", view.compare);
  // Presets first, as applyQuery applies them: the frame's preset when every effect holds one, else each effect's
  // remembered preset (which the AO also uses to pick its fitted estimator parameters) where it is not the default.
  // The parameters that follow are those differing from what those presets set.
  RenderSettings base = defaults;
  base.ao().radius = defaultRadius;  // the scene's default; AoSettings' own default (1) is the built-in scene's
  const std::string framePreset = settings.get("preset");
  if (!framePreset.empty() && framePreset != base.get("preset")) {
    add("preset", framePreset);
    base.set("preset", framePreset);
  }
  std::vector<std::string> presetNames;
  for (const EffectEntry& row : effectTable()) {
    if (!row.applyPreset) continue;
    const std::string name = row.info.name + ".preset";
    presetNames.push_back(name);
    const RenderSettings& current = settings;
    // The preset the effect's settings came from, even once some of its values changed.
    const std::string remembered = presetName(row.presetOf(current.row(row.info.name)));
    if (remembered != presetName(row.presetOf(base.row(row.info.name)))) {
      add(name, remembered);
      base.set(name, remembered);
    }
  }
  for (const ParameterInfo& p : RenderSettings::parameters()) {
    if (p.name == "preset" || std::find(presetNames.begin(), presetNames.end(), p.name) != presetNames.end()) continue;
    const std::string value = settings.get(p.name);
    // A radius a state text gave stays in the text, so that it keeps being given (kept across scenes) when applied.
    if (value != base.get(p.name) || (radiusGiven && p.name == "ao.radius")) add(p.name, value);
  }
  timeline.writeQuery(add);
  add("eye", formatVector(camera.eye));
  add("target", formatVector(camera.target));
  add("up", formatVector(camera.up));
  add("fovy", formatShortest(camera.fovyDegrees));
  add("near", formatShortest(camera.near));
  add("far", formatShortest(camera.far));
  if (camera.orthographic) {
    add("projection", "orthographic");
    add("ymag", formatShortest(camera.ymag));
  }
  if (sceneCamera >= 0) add("camera", cameraChoice());
  return query;
}

bool ViewerState::applyQuery(const std::string& query) {
  std::map<std::string, std::string> values;
  size_t start = !query.empty() && query[0] == '?' ? 1 : 0;
  while (start < query.size()) {
    size_t end = query.find('&', start);
    if (end == std::string::npos) end = query.size();
    const std::string item = query.substr(start, end - start);
    start = end + 1;
    if (item.empty()) continue;
    const size_t equals = item.find('=');
    if (equals == std::string::npos) throw InputError("state: '" + decodeComponent(item) + "' has no value");
    const std::string key = decodeComponent(item.substr(0, equals));
    if (!values.emplace(key, decodeComponent(item.substr(equals + 1))).second)
      throw InputError("state: " + key + " is given twice");
  }

  ViewerState next = *this;
  auto take = [&](const std::string& key, std::string* out) {
    auto it = values.find(key);
    if (it == values.end()) return false;
    *out = it->second;
    values.erase(it);
    return true;
  };
  std::string text;
  try {
    if (take("view", &text)) next.setViewMode(text);
    if (take("compare", &text)) next.view.compare = parseCompare(text);
    for (const ParameterInfo& p : RenderSettings::parameters()) {
      const bool byName = values.count(p.name) != 0, byAlias = !p.alias.empty() && values.count(p.alias) != 0;
      if (byName && byAlias) throw InputError(p.name + " is given twice (also as " + p.alias + ")");
      if (take(p.name, &text) || (!p.alias.empty() && take(p.alias, &text))) {
        next.settings.set(byName ? p.name : p.alias, text);
        if (p.name == "ao.radius") next.radiusGiven = true;
      }
    }
    for (const std::string& key : Timeline::queryKeys())
      if (take(key, &text)) next.timeline.applyQueryValue(key, text);
  } catch (const InputError& e) {
    throw InputError(std::string("state: ") + e.what());
  }

  // A free camera described without a projection is a perspective one, and one described without camera= is the one
  // looked through: what toQuery leaves out, so that any state comes back as it was.
  bool cameraGiven = false, freeCameraGiven = false;
  const bool projectionGiven = values.count("projection") != 0, choiceGiven = values.count("camera") != 0;
  for (const char* key : kCameraKeys) {
    if (!take(key, &text)) continue;
    cameraGiven = true;
    freeCameraGiven = freeCameraGiven || std::string(key) != "camera";
    const std::string name = key;
    if (name == "eye") next.camera.eye = parseVector(name, text);
    else if (name == "target") next.camera.target = parseVector(name, text);
    else if (name == "up") next.camera.up = parseVector(name, text);
    else if (name == "fovy") next.camera.fovyDegrees = parseFloat(name, text);
    else if (name == "near") next.camera.near = parseFloat(name, text);
    else if (name == "far") next.camera.far = parseFloat(name, text);
    else if (name == "ymag") next.camera.ymag = parseFloat(name, text);
    else if (name == "projection") {
      if (text != "perspective" && text != "orthographic")
        throw InputError("state: projection: expected perspective or orthographic, got '" + text + "'");
      next.camera.orthographic = text == "orthographic";
    } else {
      try {
        next.setCameraChoice(text);
      } catch (const InputError& e) {
        throw InputError(std::string("state: ") + e.what());
      }
    }
  }
  if (!values.empty()) throw InputError("state: unknown key '" + values.begin()->first + "'");
  if (freeCameraGiven && !projectionGiven) next.camera.orthographic = false;
  if (freeCameraGiven && !choiceGiven) next.sceneCamera = -1;
  if (cameraGiven) next.camera.validate("state");
  *this = next;
  return cameraGiven;
}

}  // namespace obscura
