#pragma once
// The scene's timeline as a viewer plays it: which animation drives the pose, the time on it, whether it plays, how
// fast, and whether it loops. Part of what a viewer shows (ViewerState, so the page's URL and obscura-view's --state
// carry it), and what each frame is drawn with (applyTo: FrameOptions' time, animation and loop). No window and no
// clock of its own: the front ends pass their clock to tick(), so the tests drive it directly.
//
// Rules. The time stays on the timeline: within [0, duration) while looping (a time past the end wraps, as the
// renderer's own timeline does), else within [0, duration], where playing stops. A scene without animations (or the
// choice "none") has nothing to play: its time stays 0 and play() does nothing. A scene loaded starts at time 0 with
// its first animation ("none" where it has none); playing, speed and loop are the viewer's and stay.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "renderer/Renderer.h"
#include "scene/Animation.h"
#include "scene/Scene.h"

namespace obscura {

class Timeline {
 public:
  // One frame step (the keys, stepFrames): the frame interval at 60 frames per second. Frame n is at exactly
  // n / kFramesPerSecond (a division, not n times the interval, which can differ in the last bit).
  static constexpr double kFramesPerSecond = 60.0;
  static constexpr double kFrameInterval = 1.0 / kFramesPerSecond;
  // Playback speed: a factor on the clock, this range (a wider one gives nothing a viewer can watch).
  static constexpr double kMinSpeed = 0.01, kMaxSpeed = 100.0;

  // The scene now shown: its animations are kept (not its meshes); the first one is chosen, at time 0.
  void sceneLoaded(const Scene& scene);

  // --- The scene's animations.
  // Their names, in the scene's order ('' for an unnamed one; choose it by its index).
  const std::vector<std::string>& animationNames() const { return names_; }
  bool hasAnimations() const { return !names_.empty(); }
  const AnimationChoice& animation() const { return animation_; }
  // The choice as text: "none", "all", the animation's name, or its index where it has no name of its own.
  std::string animationName() const;
  // "none", "all", an index or a name (parseAnimationChoice); back to time 0. Throws InputError listing the choices.
  void setAnimation(const std::string& text);
  // The next choice, in the order of a key that cycles them: each animation, then "all" (where there are several),
  // then "none", then the first again; back to time 0.
  void nextAnimation();
  // The chosen animations' length in seconds (the longest, for "all"); 0 when nothing plays.
  double duration() const;

  // --- Time and playback.
  double time() const { return time_; }
  // Puts the time on the timeline (above: wrapped while looping, else clamped; 0 when nothing plays).
  void setTime(double seconds);
  bool playing() const { return playing_; }
  // Plays from the current time (from 0 where a timeline without loop has reached its end); does nothing where
  // nothing plays (duration 0).
  void play();
  void pause();
  // Pauses, then moves the time by frames * kFrameInterval (negative: back), wrapped or clamped as setTime.
  void stepFrames(int frames);
  double speed() const { return speed_; }
  void setSpeed(double factor);  // throws InputError outside kMinSpeed .. kMaxSpeed
  bool loop() const { return loop_; }
  void setLoop(bool loop);

  // The front end's clock in seconds (any origin, e.g. the window's or requestAnimationFrame's time) at the frame
  // about to be drawn: a playing timeline advances by the clock's change since the previous tick, times the speed.
  // The first tick after play(), setTime() or a pause only starts the count, so time spent paused (or between frames
  // drawn on change only) is never played.
  void tick(double clockSeconds);

  // The frame's time, animation and loop. previousTime is left unset: the renderer measures motion from the previous
  // frame's time, so a paused timeline has none.
  void applyTo(FrameOptions& options) const;

  // --- As state text (ViewerState): the keys time, animation, speed, play and loop.
  // Appends key=value pairs that differ from the defaults (the first animation, time 0, loop on, speed 1, paused).
  void writeQuery(const std::function<void(const std::string& key, const std::string& value)>& add) const;
  // The keys, in the order they are to be applied: animation, loop, time, speed, play (so that a time given with an
  // animation is a time on that animation, wrapped or clamped as the loop given with it says).
  static const std::vector<std::string>& queryKeys();
  // Applies one of queryKeys(). Throws InputError("key: ...") on a bad value.
  void applyQueryValue(const std::string& key, const std::string& value);

 private:
  // The time put on the timeline (setTime's rule).
  double onTimeline(double seconds) const;
  // What a scene starts with: its first animation, or "none" for a scene without (not index 0 of nothing).
  AnimationChoice defaultChoice() const;

  std::shared_ptr<const Scene> animations_;  // the shown scene's animations alone, shared by copies of the state
  std::vector<std::string> names_;
  AnimationChoice animation_ = AnimationChoice::none();  // no scene yet; then defaultChoice()
  double time_ = 0.0;
  bool playing_ = false;
  double speed_ = 1.0;
  bool loop_ = true;
  std::optional<double> clock_;  // the clock at the previous tick while playing
};

// Seconds as the shortest decimal text that reads back as exactly the same double ("1.5", "0.016666666666666666"),
// so a time written into a URL reproduces the same frame.
std::string formatSeconds(double seconds);

}  // namespace obscura
