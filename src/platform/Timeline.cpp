#include "platform/Timeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "base/Error.h"
#include "base/Text.h"

namespace obscura {

void Timeline::sceneLoaded(const Scene& scene) {
  auto animations = std::make_shared<Scene>();
  animations->animations = scene.animations;  // the choice's parsing, naming and duration read nothing else
  animations_ = std::move(animations);
  names_.clear();
  for (const Animation& animation : scene.animations) names_.push_back(animation.name);
  animation_ = defaultChoice();
  time_ = 0.0;
  clock_.reset();
  if (duration() <= 0.0) playing_ = false;
}

AnimationChoice Timeline::defaultChoice() const {
  return names_.empty() ? AnimationChoice::none() : AnimationChoice::one(0);
}

std::string Timeline::animationName() const {
  return animations_ ? animationChoiceName(*animations_, animation_) : animationChoiceName(Scene{}, animation_);
}

void Timeline::setAnimation(const std::string& text) {
  animation_ = parseAnimationChoice(animations_ ? *animations_ : Scene{}, text);
  time_ = 0.0;
  clock_.reset();
  if (duration() <= 0.0) playing_ = false;
}

void Timeline::nextAnimation() {
  const int count = static_cast<int>(names_.size());
  std::string next = "none";
  if (animation_.kind == AnimationChoice::Kind::None) next = count > 0 ? "0" : "none";
  else if (animation_.kind == AnimationChoice::Kind::One && animation_.index + 1 < count)
    next = std::to_string(animation_.index + 1);
  else if (animation_.kind == AnimationChoice::Kind::One && count > 1) next = "all";
  setAnimation(next);
}

double Timeline::duration() const { return animations_ ? animationDuration(*animations_, animation_) : 0.0; }

double Timeline::onTimeline(double seconds) const {
  const double length = duration();
  if (!(length > 0.0) || !std::isfinite(seconds)) return 0.0;
  if (!loop_) return std::clamp(seconds, 0.0, length);
  double wrapped = std::fmod(seconds, length);
  if (wrapped < 0.0) wrapped += length;
  return wrapped < length ? wrapped : 0.0;  // -tiny + length can round up to length
}

void Timeline::setTime(double seconds) {
  time_ = onTimeline(seconds);
  clock_.reset();
}

void Timeline::play() {
  const double length = duration();
  if (!(length > 0.0)) return;
  if (!loop_ && time_ >= length) time_ = 0.0;  // as a player does at the end: play again from the start
  if (!playing_) clock_.reset();
  playing_ = true;
}

void Timeline::pause() {
  playing_ = false;
  clock_.reset();
}

void Timeline::stepFrames(int frames) {
  pause();
  // From the nearest frame boundary rather than the exact time, so that a time reached by playing steps onto the
  // 1/60 s grid instead of carrying its fraction along.
  const double frame = std::round(time_ * kFramesPerSecond);
  setTime((frame + frames) / kFramesPerSecond);
}

void Timeline::setSpeed(double factor) {
  if (!(factor >= kMinSpeed && factor <= kMaxSpeed)) {
    char message[120];
    std::snprintf(message, sizeof message, "speed: %g is out of range (%g .. %g)", factor, kMinSpeed, kMaxSpeed);
    throw InputError(message);
  }
  speed_ = factor;
}

void Timeline::setLoop(bool loop) {
  loop_ = loop;
  time_ = onTimeline(time_);
}

void Timeline::tick(double clockSeconds) {
  if (!playing_) {
    clock_.reset();
    return;
  }
  if (clock_ && clockSeconds > *clock_) {
    const double next = time_ + (clockSeconds - *clock_) * speed_;
    if (!loop_ && next >= duration()) {
      time_ = duration();  // the last frame stays on screen
      playing_ = false;
      clock_.reset();
      return;
    }
    time_ = onTimeline(next);
  }
  clock_ = clockSeconds;
}

void Timeline::applyTo(FrameOptions& options) const {
  options.time = time_;
  options.animation = animation_;
  options.loop = loop_;
}

const std::vector<std::string>& Timeline::queryKeys() {
  static const std::vector<std::string> keys = {"animation", "loop", "time", "speed", "play"};
  return keys;
}

void Timeline::writeQuery(const std::function<void(const std::string&, const std::string&)>& add) const {
  if (!(animation_ == defaultChoice())) add("animation", animationName());
  if (!loop_) add("loop", "off");
  if (time_ != 0.0) add("time", formatSeconds(time_));
  if (speed_ != 1.0) add("speed", formatSeconds(speed_));
  if (playing_) add("play", "on");
}

namespace {

bool parseOnOff(const std::string& key, const std::string& text) {
  if (text == "on") return true;
  if (text == "off") return false;
  throw InputError(key + ": expected on or off, got '" + text + "'");
}

double parseSeconds(const std::string& key, const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value))
    throw InputError(key + ": expected a number, got '" + text + "'");
  return value;
}

}  // namespace

void Timeline::applyQueryValue(const std::string& key, const std::string& value) {
  if (key == "animation") setAnimation(value);
  else if (key == "loop") setLoop(parseOnOff(key, value));
  else if (key == "time") setTime(parseSeconds(key, value));
  else if (key == "speed") setSpeed(parseSeconds(key, value));
  else if (key == "play") parseOnOff(key, value) ? play() : pause();
  else throw InputError("unknown key '" + key + "'");
}

std::string formatSeconds(double seconds) {
  char text[64];
  if (std::fabs(seconds) < 1e9) {
    for (int decimals = 0; decimals <= 20; ++decimals) {
      std::snprintf(text, sizeof text, "%.*f", decimals, seconds);
      if (std::strtod(text, nullptr) == seconds) return text;
    }
  }
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, seconds);
    if (std::strtod(text, nullptr) == seconds) break;
  }
  return text;
}

}  // namespace obscura
