// The viewers' timeline (platform/Timeline): playing by a clock, pausing, frame steps, looping or stopping at the
// end, the animation choice, and its keys in the shared state text (the page's URL, obscura-view --state). No GL.
#include <cmath>

#include <gtest/gtest.h>

#include "base/Error.h"
#include "platform/Timeline.h"
#include "platform/ViewerState.h"

using namespace obscura;

namespace {

// Two animations on one node: "slide" (2 s, a translation) and "spin" (3 s, a rotation), and one unnamed (1 s).
Scene movingScene() {
  Scene scene;
  Mesh triangle;
  triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangle.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  triangle.indices = {0, 1, 2};
  scene.meshes.push_back(triangle);
  scene.nodes.push_back(Node{});
  Instance instance;
  instance.node = 0;
  scene.instances.push_back(instance);
  auto animation = [](const char* name, float duration, AnimationPath path, int components) {
    Animation a;
    a.name = name;
    AnimationSampler sampler;
    sampler.times = {0.0f, duration};
    sampler.components = components;
    sampler.values.assign(static_cast<size_t>(2 * components), 0.0f);
    if (components == 4) sampler.values[3] = sampler.values[7] = 1.0f;  // identity quaternions (x, y, z, w)
    sampler.values[static_cast<size_t>(components)] = 1.0f;
    a.samplers.push_back(sampler);
    a.channels.push_back({0, 0, path});
    return a;
  };
  scene.animations = {animation("slide", 2.0f, AnimationPath::Translation, 3),
                      animation("spin", 3.0f, AnimationPath::Rotation, 4),
                      animation("", 1.0f, AnimationPath::Scale, 3)};
  return scene;
}

Timeline movingTimeline() {
  Timeline timeline;
  timeline.sceneLoaded(movingScene());
  return timeline;
}

}  // namespace

TEST(Timeline, StartsPausedAtZeroOnTheFirstAnimation) {
  const Timeline timeline = movingTimeline();
  EXPECT_FALSE(timeline.playing());
  EXPECT_EQ(timeline.time(), 0.0);
  EXPECT_EQ(timeline.animation(), AnimationChoice::one(0));
  EXPECT_EQ(timeline.animationName(), "slide");
  EXPECT_EQ(timeline.duration(), 2.0);
  EXPECT_EQ(timeline.speed(), 1.0);
  EXPECT_TRUE(timeline.loop());
  EXPECT_EQ(timeline.animationNames(), (std::vector<std::string>{"slide", "spin", ""}));
  FrameOptions options;
  options.animation = AnimationChoice::all();
  options.time = 5.0;
  timeline.applyTo(options);
  EXPECT_EQ(options.time, 0.0);
  EXPECT_EQ(options.animation, AnimationChoice::one(0));
  EXPECT_TRUE(options.loop);
  EXPECT_FALSE(options.previousTime.has_value()) << "the renderer measures motion from the frame before";
}

// The clock's change since the previous tick, times the speed; the first tick after play() only starts the count, so
// the time spent paused is never played.
TEST(Timeline, PlaysByTheClockAndWrapsWhileLooping) {
  Timeline timeline = movingTimeline();
  timeline.tick(100.0);
  EXPECT_EQ(timeline.time(), 0.0) << "paused";
  timeline.play();
  timeline.tick(100.0);
  EXPECT_EQ(timeline.time(), 0.0) << "the first tick starts the count";
  timeline.tick(100.5);
  EXPECT_DOUBLE_EQ(timeline.time(), 0.5);
  timeline.setSpeed(2.0);
  timeline.tick(101.0);
  EXPECT_DOUBLE_EQ(timeline.time(), 1.5);
  timeline.tick(101.5);
  EXPECT_DOUBLE_EQ(timeline.time(), 0.5) << "2.5 s wraps at slide's 2 s";
  timeline.tick(101.4);
  EXPECT_DOUBLE_EQ(timeline.time(), 0.5) << "a clock going back plays nothing";

  timeline.pause();
  timeline.tick(200.0);
  EXPECT_DOUBLE_EQ(timeline.time(), 0.5);
  timeline.play();
  timeline.tick(300.0);
  EXPECT_DOUBLE_EQ(timeline.time(), 0.5) << "the pause is not played";
  timeline.tick(300.25);
  EXPECT_DOUBLE_EQ(timeline.time(), 1.0);
  timeline.setTime(0.25);
  timeline.tick(300.5);
  EXPECT_DOUBLE_EQ(timeline.time(), 0.25) << "a time set restarts the count";
  EXPECT_TRUE(timeline.playing());
}

TEST(Timeline, WithoutLoopStopsAtTheEndAndPlaysAgainFromTheStart) {
  Timeline timeline = movingTimeline();
  timeline.setLoop(false);
  timeline.setTime(1.5);
  timeline.play();
  timeline.tick(0.0);
  timeline.tick(0.25);
  EXPECT_DOUBLE_EQ(timeline.time(), 1.75);
  timeline.tick(1.0);
  EXPECT_EQ(timeline.time(), 2.0) << "the last frame stays";
  EXPECT_FALSE(timeline.playing());
  timeline.play();
  EXPECT_EQ(timeline.time(), 0.0) << "play at the end starts again";
  EXPECT_TRUE(timeline.playing());

  timeline.setTime(7.0);
  EXPECT_EQ(timeline.time(), 2.0) << "clamped without loop";
  timeline.setTime(-1.0);
  EXPECT_EQ(timeline.time(), 0.0);
  timeline.setTime(2.0);
  timeline.setLoop(true);
  EXPECT_EQ(timeline.time(), 0.0) << "the end of a looping timeline is its start";
  timeline.setTime(4.5);
  EXPECT_DOUBLE_EQ(timeline.time(), 0.5);
  timeline.setTime(-0.5);
  EXPECT_DOUBLE_EQ(timeline.time(), 1.5) << "wrapped from the end";
}

TEST(Timeline, FrameStepsPauseAndMoveOneSixtiethOfASecond) {
  Timeline timeline = movingTimeline();
  timeline.play();
  timeline.stepFrames(1);
  EXPECT_FALSE(timeline.playing());
  EXPECT_EQ(timeline.time(), Timeline::kFrameInterval);
  timeline.stepFrames(-2);
  EXPECT_DOUBLE_EQ(timeline.time(), 2.0 - Timeline::kFrameInterval) << "back from 0 wraps to the last frame";
  timeline.stepFrames(1);
  EXPECT_EQ(timeline.time(), 0.0) << "and on from the last frame to the first";
  // A time between frames (reached by playing, or given) steps from its nearest frame.
  timeline.setTime(0.51);
  timeline.stepFrames(1);
  EXPECT_DOUBLE_EQ(timeline.time(), 32 * Timeline::kFrameInterval);
  // Every step lands exactly on frame n / 60, the value a page computes as (n + 1) / 60 (46 x (1/60) is one bit
  // below 46 / 60: the page's timeline test caught it).
  for (int n = 0; n < 119; ++n) {
    timeline.setTime(n / 60.0 + 0.004);
    timeline.stepFrames(1);
    EXPECT_EQ(timeline.time(), (n + 1) / 60.0) << n;
  }
  timeline.setLoop(false);
  timeline.setTime(0.0);
  timeline.stepFrames(-1);
  EXPECT_EQ(timeline.time(), 0.0) << "clamped without loop";
}

TEST(Timeline, ChoosesAnimationsByNameIndexAllOrNone) {
  Timeline timeline = movingTimeline();
  timeline.setTime(1.0);
  timeline.setAnimation("spin");
  EXPECT_EQ(timeline.animation(), AnimationChoice::one(1));
  EXPECT_EQ(timeline.time(), 0.0) << "another animation starts at its beginning";
  EXPECT_EQ(timeline.duration(), 3.0);
  timeline.setAnimation("2");
  EXPECT_EQ(timeline.animationName(), "2") << "an unnamed animation goes by its index";
  EXPECT_EQ(timeline.duration(), 1.0);
  timeline.setAnimation("all");
  EXPECT_EQ(timeline.duration(), 3.0) << "the longest";
  timeline.play();
  timeline.setAnimation("none");
  EXPECT_EQ(timeline.duration(), 0.0);
  EXPECT_FALSE(timeline.playing()) << "nothing plays";
  timeline.play();
  EXPECT_FALSE(timeline.playing());
  timeline.setTime(1.0);
  EXPECT_EQ(timeline.time(), 0.0);
  try {
    timeline.setAnimation("walk");
    ADD_FAILURE() << "an animation the scene does not have was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'walk' is not in the scene; choices: none, all, 0 'slide', 1 'spin', 2"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(timeline.animationName(), "none") << "unchanged";
  EXPECT_THROW(timeline.setSpeed(0.0), InputError);
  EXPECT_THROW(timeline.setSpeed(1000.0), InputError);
}

// The key "n" cycles: each animation, all together (where there are several), none, the first again.
TEST(Timeline, NextAnimationCyclesThroughEveryChoice) {
  Timeline timeline = movingTimeline();
  std::vector<std::string> seen;
  for (int i = 0; i < 6; ++i) {
    timeline.setTime(0.5);
    timeline.nextAnimation();
    EXPECT_EQ(timeline.time(), 0.0);
    seen.push_back(timeline.animationName());
  }
  EXPECT_EQ(seen, (std::vector<std::string>{"spin", "2", "all", "none", "slide", "spin"}));
  Scene one = movingScene();
  one.animations.resize(1);
  timeline.sceneLoaded(one);
  timeline.nextAnimation();
  EXPECT_EQ(timeline.animationName(), "none") << "no 'all' for a single animation";
  timeline.nextAnimation();
  EXPECT_EQ(timeline.animationName(), "slide");
}

// A still scene: nothing to choose or play, the time stays 0 and the state text holds no timeline key.
TEST(Timeline, AStillSceneHasNothingToPlay) {
  Timeline timeline;
  timeline.sceneLoaded(Scene{});
  EXPECT_FALSE(timeline.hasAnimations());
  EXPECT_EQ(timeline.animationName(), "none");
  EXPECT_EQ(timeline.duration(), 0.0);
  timeline.play();
  EXPECT_FALSE(timeline.playing());
  timeline.stepFrames(3);
  EXPECT_EQ(timeline.time(), 0.0);
  ViewerState state;
  state.timeline = timeline;
  const std::string text = state.toQuery();
  for (const std::string& key : Timeline::queryKeys())
    EXPECT_EQ(text.find("&" + key + "="), std::string::npos) << text;
  EXPECT_THROW(state.applyQuery("animation=0"), InputError);
}

// Loading another scene starts it at 0 on its first animation; playing, speed and loop are the viewer's and stay.
TEST(Timeline, ASceneLoadedStartsAtZeroAndKeepsTheViewersChoices) {
  Timeline timeline = movingTimeline();
  timeline.setAnimation("spin");
  timeline.setTime(1.25);
  timeline.setSpeed(0.5);
  timeline.setLoop(false);
  timeline.play();
  timeline.sceneLoaded(movingScene());
  EXPECT_EQ(timeline.animationName(), "slide");
  EXPECT_EQ(timeline.time(), 0.0);
  EXPECT_TRUE(timeline.playing());
  EXPECT_EQ(timeline.speed(), 0.5);
  EXPECT_FALSE(timeline.loop());
  timeline.sceneLoaded(Scene{});
  EXPECT_FALSE(timeline.playing()) << "a still scene does not play";
}

// The timeline in the state text: written only where it differs from the defaults, read back exactly (the time to
// the last bit, so a link reproduces the frame), the keys in any order.
TEST(Timeline, RoundTripsThroughTheStateTextExactly) {
  ViewerState original;
  original.timeline = movingTimeline();
  EXPECT_EQ(original.toQuery().find("time="), std::string::npos) << "defaults are left out";
  EXPECT_EQ(original.toQuery().find("animation="), std::string::npos);
  original.timeline.setAnimation("spin");
  original.timeline.setLoop(false);
  original.timeline.setTime(1.0 / 3.0);
  original.timeline.setSpeed(0.25);
  original.timeline.play();
  const std::string text = original.toQuery();
  EXPECT_NE(text.find("&animation=spin&loop=off&time=0.3333333333333333&speed=0.25&play=on&eye="),
            std::string::npos)
      << text;

  ViewerState copy;
  copy.timeline = movingTimeline();
  copy.applyQuery(text);
  EXPECT_EQ(copy.toQuery(), text);
  EXPECT_EQ(copy.timeline.time(), 1.0 / 3.0);
  EXPECT_EQ(copy.timeline.animation(), AnimationChoice::one(1));
  EXPECT_EQ(copy.timeline.speed(), 0.25);
  EXPECT_FALSE(copy.timeline.loop());
  EXPECT_TRUE(copy.timeline.playing());

  // In any order: the time is on the animation given with it, clamped or wrapped as the loop given with it says.
  ViewerState reordered;
  reordered.timeline = movingTimeline();
  reordered.applyQuery("time=2&play=off&loop=off&animation=slide");
  EXPECT_EQ(reordered.timeline.time(), 2.0) << "the end, not wrapped to 0";
  reordered.applyQuery("time=2.5&animation=spin");
  EXPECT_EQ(reordered.timeline.time(), 2.5) << "on spin, not on slide";
  reordered.applyQuery("animation=2&play=on");
  EXPECT_EQ(reordered.timeline.animationName(), "2");
  EXPECT_TRUE(reordered.timeline.playing());
}

TEST(Timeline, RefusesBadStateTextAndKeepsTheState) {
  const std::pair<const char*, const char*> cases[] = {
      {"time=soon", "state: time: expected a number, got 'soon'"},
      {"time=inf", "state: time: expected a number"},
      {"speed=0", "state: speed: 0 is out of range (0.01 .. 100)"},
      {"play=yes", "state: play: expected on or off, got 'yes'"},
      {"loop=1", "state: loop: expected on or off"},
      {"animation=walk", "state: animation 'walk' is not in the scene; choices: none, all, 0 'slide'"},
      {"animation=7", "state: animation 7 is not in the scene"},
      {"time=1&time=2", "time is given twice"},
  };
  ViewerState state;
  state.timeline = movingTimeline();
  state.timeline.setTime(0.5);
  const std::string before = state.toQuery();
  for (const auto& [text, expect] : cases) {
    try {
      state.applyQuery(std::string("view=ao&") + text);  // a valid key with it changes nothing either
      ADD_FAILURE() << text << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << text << ": " << e.what();
    }
    EXPECT_EQ(state.toQuery(), before) << text;
  }
}

TEST(Timeline, SecondsAreWrittenShortAndReadBackExactly) {
  EXPECT_EQ(formatSeconds(0.0), "0");
  EXPECT_EQ(formatSeconds(1.5), "1.5");
  EXPECT_EQ(formatSeconds(0.1), "0.1");
  EXPECT_EQ(formatSeconds(2.0 / 60.0), "0.03333333333333333");
  for (double seconds : {1.0 / 60.0, 1.0 / 3.0, 123.456789012345, 1e-9, 3e7, 2.0 - 1.0 / 60.0})
    EXPECT_EQ(std::strtod(formatSeconds(seconds).c_str(), nullptr), seconds) << formatSeconds(seconds);
}
