// The page's C++ side (src/apps/obscura_web.cpp, the module web/obscura.js wraps, and platform/WebCanvas.cpp) built
// natively and driven as web/obscura.js drives it, with the browser's part played by tests/web/NativePage.h. The
// browser tests check the page end to end in Chromium; this runs the same C++ under the native test suite, so that
// the sanitizer leg (tools/test-sanitizers.sh: ASan, LSan, UBSan) covers it too. The canvas is the headless context's
// default framebuffer (OSMesa's is 4 x 4: the frame's targets are full size, its last pass is clipped).
// obscura_web_geometry.cpp (the public C++ API on the page's own context) is not here: natively api::Renderer needs
// a GetProcAddress the web build does without; the API itself runs natively in api.surface and the examples.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "web/NativePage.h"

using Json = nlohmann::json;
namespace page = obscura::test::page;

extern "C" {
int obscura_create(int checkGlErrors, int dynamicResolution, int quickStart, int prepare);
int obscura_prepare();
const char* obscura_error();
const char* obscura_describe();
int obscura_set(const char* name, const char* value);
const char* obscura_get(const char* name);
const char* obscura_get_effective(const char* name);
const char* obscura_set_hierarchy_storage(const char* name);
const char* obscura_set_environment_layout(const char* name);
int obscura_set_view(const char* mode);
const char* obscura_view();
int obscura_set_compare(const char* name);
const char* obscura_compare();
const char* obscura_state();
int obscura_set_state(const char* query);
void obscura_orbit(float dx, float dy, int viewportHeight);
void obscura_pan(float dx, float dy, int viewportHeight);
void obscura_zoom(float factor);
void obscura_reset_camera();
int obscura_handle_key(const char* key);
void obscura_add_side_file(const char* uri, const std::uint8_t* bytes, int size);
int obscura_load_scene(const char* name, const std::uint8_t* bytes, int size);
int obscura_load_builtin_scene();
const char* obscura_scene();
const char* obscura_default_radius();
const char* obscura_timeline();
double obscura_time();
int obscura_playing();
void obscura_play();
void obscura_pause();
int obscura_set_time(double seconds);
void obscura_step_frames(int frames);
int obscura_set_animation(const char* choice);
int obscura_set_speed(double factor);
void obscura_set_loop(int loop);
const char* obscura_stats();
void obscura_set_continuous(int continuous);
int obscura_draw();
const char* obscura_snapshot();
}

namespace {

std::vector<std::uint8_t> readBytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(file), {});
}

Json stats() { return Json::parse(obscura_stats()); }

// The module with GL error checks after every pass (as the browser tests create it), at the default display size.
void createModule() {
  page::setDisplaySize(160, 90);
  ASSERT_EQ(obscura_create(1, 0, 0, 0), 1) << obscura_error();
  page::loggedErrors();
}

// One animation frame at `ms`; returns whether it drew (the frame count moved) and checks that it did not fail.
bool frameAt(double ms) {
  const long before = stats()["frames"];
  EXPECT_TRUE(page::animationFrame(ms));
  const Json after = stats();
  EXPECT_EQ(after["error"], "") << after.dump();
  EXPECT_EQ(page::loggedErrors(), 0);
  return after["frames"].get<long>() > before;
}

int loadFile(const std::string& path, const std::string& name) {
  const std::vector<std::uint8_t> bytes = readBytes(path);
  EXPECT_FALSE(bytes.empty()) << path;
  return obscura_load_scene(name.c_str(), bytes.data(), static_cast<int>(bytes.size()));
}

}  // namespace

TEST(WebApi, TheModuleDescribesItselfAndDrawsOnAnimationFramesAfterAChange) {
  createModule();
  const Json description = Json::parse(obscura_describe());
  EXPECT_GT(description["parameters"].size(), 20u);
  EXPECT_GT(description["effects"].size(), 5u);
  EXPECT_FALSE(description["views"].empty());
  EXPECT_FALSE(description["keys"].empty());
  EXPECT_FALSE(description["context"]["renderer"].get<std::string>().empty());

  EXPECT_TRUE(frameAt(0.0));  // the first frame after creation
  // A change is drawn over framesPerChange() frames (temporal antialiasing's phases); then nothing is drawn.
  int drawn = 1;
  while (drawn < 64 && frameAt(drawn * 16.0)) ++drawn;
  EXPECT_LT(drawn, 64);
  EXPECT_FALSE(frameAt(400.0));
  EXPECT_EQ(stats()["width"], 160);
  EXPECT_EQ(stats()["height"], 90);
  page::setDisplaySize(64, 48);  // the canvas resized: drawn again at its new size
  EXPECT_TRUE(frameAt(416.0));
  EXPECT_EQ(stats()["width"], 64);
  EXPECT_EQ(stats()["height"], 48);
  obscura_set_continuous(1);  // every animation frame draws
  EXPECT_TRUE(frameAt(600.0));
  EXPECT_TRUE(frameAt(616.0));
  obscura_set_continuous(0);
  EXPECT_FALSE(stats()["passesRun"].empty());
  EXPECT_GT(stats()["glObjects"]["programs"].get<int>(), 0);
}

TEST(WebApi, ParametersViewsAndTheStateTextRoundTrip) {
  createModule();
  ASSERT_EQ(obscura_set("ao.radius", "0.5"), 1) << obscura_error();
  EXPECT_STREQ(obscura_get("ao.radius"), "0.5");
  EXPECT_NE(obscura_get_effective("ao.radius"), nullptr);
  EXPECT_EQ(obscura_set("ao.radius", "wide"), 0);
  EXPECT_NE(std::string(obscura_error()).find("ao.radius"), std::string::npos) << obscura_error();
  EXPECT_EQ(obscura_set("no.such-parameter", "1"), 0);
  EXPECT_EQ(obscura_get("no.such-parameter"), nullptr);
  EXPECT_TRUE(frameAt(0.0));

  const Json description = Json::parse(obscura_describe());
  double ms = 16.0;
  for (const Json& view : description["views"]) {
    const std::string mode = view.get<std::string>();
    ASSERT_EQ(obscura_set_view(mode.c_str()), 1) << mode << ": " << obscura_error();
    EXPECT_EQ(obscura_view(), mode);
    EXPECT_TRUE(frameAt(ms += 16.0)) << mode;
  }
  EXPECT_EQ(obscura_set_view("no such view"), 0);
  for (const Json& name : description["compareSwitches"]) {
    ASSERT_EQ(obscura_set_compare(name.get<std::string>().c_str()), 1) << obscura_error();
    EXPECT_EQ(obscura_compare(), name.get<std::string>());
  }

  const std::string state = obscura_state();
  obscura_orbit(30.0f, -10.0f, 90);
  obscura_pan(5.0f, 3.0f, 90);
  obscura_zoom(1.5f);
  EXPECT_NE(obscura_state(), state);
  EXPECT_TRUE(frameAt(ms += 16.0));
  ASSERT_EQ(obscura_set_state(state.c_str()), 1) << obscura_error();
  EXPECT_EQ(obscura_state(), state);
  EXPECT_EQ(obscura_set_state("ao.radius=wide"), 0);
  obscura_reset_camera();
  EXPECT_TRUE(frameAt(ms += 16.0));
}

TEST(WebApi, EveryBoundKeyActsAndAnUnboundOneIsNotAnError) {
  createModule();
  double ms = 0.0;
  // A range over a temporary's member would read freed memory (the sanitizer leg found it): the description is kept.
  const Json description = Json::parse(obscura_describe());
  for (const Json& binding : description["keys"]) {
    const std::string key = binding["key"];
    if (key == "v") {  // the next scene camera: the built-in scene has none, which the key says
      EXPECT_EQ(obscura_handle_key("v"), 0);
      EXPECT_NE(std::string(obscura_error()).find("the scene has no cameras"), std::string::npos) << obscura_error();
      continue;
    }
    EXPECT_EQ(obscura_handle_key(key.c_str()), 1) << key << ": " << obscura_error();
    frameAt(ms += 16.0);
  }
  EXPECT_EQ(obscura_handle_key("F13"), 0);
  EXPECT_STREQ(obscura_error(), "");
}

TEST(WebApi, ScenesLoadFromBytesWithTheirSideFilesAndARefusedOneKeepsTheScene) {
  createModule();
  const std::string box = obscura::test::assimpModels() + "/BoxTextured-glTF/";
  for (const char* side : {"BoxTextured0.bin", "CesiumLogoFlat.png"}) {
    const std::vector<std::uint8_t> bytes = readBytes(box + side);
    obscura_add_side_file(side, bytes.data(), static_cast<int>(bytes.size()));
  }
  ASSERT_EQ(loadFile(box + "BoxTextured.gltf", "BoxTextured.gltf"), 1) << obscura_error();
  Json scene = Json::parse(obscura_scene());
  EXPECT_EQ(scene["name"], "BoxTextured.gltf");
  EXPECT_EQ(scene["triangles"], 12);
  EXPECT_GT(std::stod(obscura_default_radius()), 0.0);
  EXPECT_TRUE(frameAt(0.0));

  // The side files went with that load: the same .gltf alone cannot find its buffer, and the box stays.
  EXPECT_EQ(loadFile(box + "BoxTextured.gltf", "again.gltf"), 0);
  EXPECT_NE(std::string(obscura_error()).find("again.gltf"), std::string::npos) << obscura_error();
  const std::string bad = obscura::test::assimpModels() + "/IndexOutOfRange/IndexOutOfRange.gltf";
  EXPECT_EQ(loadFile(bad, "IndexOutOfRange.gltf"), 0);
  EXPECT_EQ(Json::parse(obscura_scene())["name"], "BoxTextured.gltf");

  ASSERT_EQ(loadFile(obscura::test::assimpModels() + "/BoxTextured-glTF-Binary/BoxTextured.glb", "box.glb"), 1)
      << obscura_error();
  EXPECT_TRUE(frameAt(16.0));
  const std::vector<std::uint8_t> draco = readBytes(obscura::test::sourceDir() + "/tests/fuzz/seeds/draco-engine.glb");
  ASSERT_EQ(obscura_load_scene("draco-engine.glb", draco.data(), static_cast<int>(draco.size())), 1)
      << obscura_error();
  EXPECT_GT(Json::parse(obscura_scene())["triangles"].get<int>(), 1000);
  EXPECT_TRUE(frameAt(32.0));
  ASSERT_EQ(obscura_load_builtin_scene(), 1) << obscura_error();
  scene = Json::parse(obscura_scene());
  EXPECT_TRUE(scene["warnings"].empty());
  EXPECT_TRUE(frameAt(48.0));
}

TEST(WebApi, TheTimelinePlaysOnTheAnimationFramesClockPausesAndSteps) {
  createModule();
  ASSERT_EQ(loadFile(obscura::test::assimpModels() + "/simple_skin/simple_skin.gltf", "simple_skin.gltf"), 1)
      << obscura_error();
  const Json timeline = Json::parse(obscura_timeline());
  EXPECT_FALSE(timeline["animations"].empty());
  EXPECT_GT(timeline["duration"].get<double>(), 0.0);
  obscura_play();
  EXPECT_EQ(obscura_playing(), 1);
  EXPECT_TRUE(frameAt(1000.0));
  EXPECT_TRUE(frameAt(1250.0));  // a playing timeline draws every frame, and moves by the frames' clock
  EXPECT_GT(obscura_time(), 0.0);
  obscura_pause();
  EXPECT_EQ(obscura_playing(), 0);
  ASSERT_EQ(obscura_set_time(0.25), 1);
  EXPECT_DOUBLE_EQ(obscura_time(), 0.25);
  EXPECT_EQ(obscura_set_time(std::nan("")), 0);
  obscura_step_frames(3);
  EXPECT_NEAR(obscura_time(), 0.25 + 3.0 / 60.0, 1e-9);
  EXPECT_EQ(obscura_set_speed(2.0), 1);
  obscura_set_loop(0);
  EXPECT_EQ(Json::parse(obscura_timeline())["loop"], false);
  EXPECT_EQ(obscura_set_animation("none"), 1) << obscura_error();
  EXPECT_EQ(obscura_set_animation("no such animation"), 0);
  EXPECT_TRUE(frameAt(1500.0));
}

TEST(WebApi, TheDepthHierarchyStorageAndTheEnvironmentLayoutCanBeForced) {
  createModule();
  ASSERT_EQ(obscura_set("ao.hierarchy", "on"), 1) << obscura_error();  // auto builds none with one layer
  double ms = 0.0;
  for (const char* storage : {"separate", "atlas", "mipchain", "auto"}) {
    const char* used = obscura_set_hierarchy_storage(storage);
    ASSERT_NE(used, nullptr) << storage << ": " << obscura_error();
    EXPECT_TRUE(frameAt(ms += 16.0)) << storage;
  }
  EXPECT_EQ(obscura_set_hierarchy_storage("somewhere"), nullptr);
  for (const char* layout : {"atlas", "mipchain", "halffloat", "auto"}) {
    const char* used = obscura_set_environment_layout(layout);
    ASSERT_NE(used, nullptr) << layout << ": " << obscura_error();
    EXPECT_TRUE(frameAt(ms += 16.0)) << layout;
  }
  EXPECT_EQ(obscura_set_environment_layout("sideways"), nullptr);
}

TEST(WebApi, ALostContextStopsDrawingAndARestoredOneDrawsAgain) {
  createModule();
  EXPECT_TRUE(frameAt(0.0));
  page::loseContext();
  EXPECT_EQ(stats()["contextLost"], true);
  EXPECT_EQ(obscura_draw(), 0);
  EXPECT_STREQ(obscura_error(), "the WebGL context is lost");
  EXPECT_EQ(obscura_snapshot(), nullptr);
  EXPECT_FALSE(frameAt(16.0));  // frames are skipped while the context is lost
  ASSERT_EQ(obscura_set("ao.radius", "0.7"), 1);  // changes are kept for the restored context
  page::restoreContext();
  const Json restored = stats();
  EXPECT_EQ(restored["contextLost"], false);
  EXPECT_EQ(restored["contextRestores"], 1);
  EXPECT_TRUE(frameAt(32.0));
  EXPECT_EQ(obscura_draw(), 1) << obscura_error();
  const char* snapshot = obscura_snapshot();
  ASSERT_NE(snapshot, nullptr) << obscura_error();
  const Json read = Json::parse(snapshot);
  EXPECT_EQ(read["width"], 160);
  EXPECT_EQ(read["height"], 90);
  EXPECT_NE(read["pointer"].get<std::uintptr_t>(), 0u);
  EXPECT_STREQ(obscura_get("ao.radius"), "0.7");
}

TEST(WebApi, QuickStartDrawsACheapFirstFrameThenWarmsThePassesAndTheFullFrameFollowsByItself) {
  page::setDisplaySize(160, 90);
  ASSERT_EQ(obscura_create(1, 0, 1, 0), 1) << obscura_error();  // the page's quick start: on
  page::loggedErrors();
  EXPECT_STREQ(obscura_get("resolution.quick-start"), "on");
  auto ran = [](const Json& s, const std::string& pass) {
    const Json& passes = s["passesRun"];
    return std::find(passes.begin(), passes.end(), pass) != passes.end();
  };
  // Its programs begun before it (createObscura's prepare(), WebApp::prepare): none until asked.
  EXPECT_EQ(stats()["startup"]["programsPrepared"].get<int>(), 0);
  ASSERT_EQ(obscura_prepare(), 1) << obscura_error();
  const int prepared = stats()["startup"]["programsPrepared"].get<int>();
  EXPECT_GE(prepared, 2);  // the lighting's (it draws the scene, and the background), at least
  // The first frame: the lit scene (without the AO, the lighting draws the scene itself: one geometry pass), not the
  // AO or FXAA, and it warms nothing.
  EXPECT_TRUE(frameAt(0.0));
  Json s = stats();
  EXPECT_EQ(s["startup"]["programsPrepared"].get<int>(), prepared);
  EXPECT_EQ(s["cheapFrame"], true);
  EXPECT_TRUE(ran(s, "lighting")) << s["passesRun"].dump();
  EXPECT_FALSE(ran(s, "sao") || ran(s, "blur-h") || ran(s, "fxaa")) << s["passesRun"].dump();
  EXPECT_TRUE(s["startup"]["quickStart"]["warmed"].empty());
  EXPECT_EQ(s["startup"]["quickStart"]["firstFullFrame"], nullptr);
  // With nothing changed, frames follow by themselves, each cheap and warming up to four passes, until the full one.
  double ms = 0.0;
  int frames = 1;
  while (stats()["cheapFrame"] == true && frames < 20) {
    ASSERT_TRUE(frameAt(ms += 16.0)) << "a cheap frame is followed by another frame without a change";
    ++frames;
  }
  s = stats();
  EXPECT_EQ(s["cheapFrame"], false);
  EXPECT_TRUE(ran(s, "sao") && ran(s, "fxaa")) << s["passesRun"].dump();
  const Json& quick = s["startup"]["quickStart"];
  EXPECT_EQ(quick["cheapFrames"].get<int>(), frames - 1);
  EXPECT_GE(quick["cheapFrames"].get<int>(), 2);  // the first, and at least one that warmed
  EXPECT_LE(quick["cheapFrames"].get<int>(), 4);  // the default frame's passes, four a frame
  EXPECT_EQ(quick["firstFullFrame"].get<int>(), frames - 1);
  std::vector<std::string> warmed;
  for (const Json& w : quick["warmed"]) {
    warmed.push_back(w["pass"]);
    EXPECT_GE(w["frame"].get<int>(), 1);  // not by the first frame
    EXPECT_GE(w["cpuMs"].get<double>(), 0.0);
  }
  for (const char* pass : {"gbuffer", "sao", "lighting", "fxaa"})
    EXPECT_NE(std::find(warmed.begin(), warmed.end(), pass), warmed.end()) << pass;
  EXPECT_TRUE(s["startup"]["fullFrameMs"].is_null());  // taken at the animation frame after it
  frameAt(ms += 16.0);
  EXPECT_FALSE(stats()["startup"]["fullFrameMs"].is_null());
  // Later changes are full frames at once.
  ASSERT_EQ(obscura_set("ao.radius", "0.6"), 1);
  EXPECT_TRUE(frameAt(ms += 16.0));
  EXPECT_EQ(stats()["cheapFrame"], false);
}

TEST(WebApi, ASnapshotDuringQuickStartIsTheFullFrame) {
  page::setDisplaySize(160, 90);
  ASSERT_EQ(obscura_create(1, 0, 1, 0), 1) << obscura_error();
  page::loggedErrors();
  ASSERT_NE(obscura_snapshot(), nullptr) << obscura_error();
  const Json s = stats();
  EXPECT_EQ(s["cheapFrame"], false);
  const Json& passes = s["passesRun"];
  EXPECT_NE(std::find(passes.begin(), passes.end(), "sao"), passes.end()) << passes.dump();
  EXPECT_EQ(s["startup"]["quickStart"]["cheapFrames"], 0);
  EXPECT_EQ(s["startup"]["quickStart"]["firstFullFrame"], 0);
}
