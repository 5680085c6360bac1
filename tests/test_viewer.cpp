// The interactive session both viewers share (platform/Viewer): key bindings, scene loading that keeps the previous
// scene on failure, split screen, and context loss (every GL object dropped without deletion, then rebuilt from the
// CPU scene to the same image).
#include <fstream>
#include <set>
#include <iterator>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "TestSupport.h"
#include "base/Error.h"
#include "gl/GlObjects.h"
#include "platform/Viewer.h"

using namespace obscura;

namespace {

constexpr int kWidth = 160, kHeight = 90;

// `clockSeconds`: the front end's clock, which a playing timeline advances by.
test::RenderedImage renderViewer(Viewer& viewer, double clockSeconds = 0.0) {
  const gl::RenderTarget output("viewer output", kWidth, kHeight, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                test::context().caps().depth24);
  viewer.render(output.framebuffer(), kWidth, kHeight, nullptr, clockSeconds);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  test::RenderedImage image;
  image.width = kWidth;
  image.height = kHeight;
  image.rgba = output.readRgba();
  return image;
}

std::vector<std::uint8_t> readBytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(file), {});
}

bool sameLiveObjects(const gl::LiveObjects& a, const gl::LiveObjects& b) {
  return a.textures == b.textures && a.buffers == b.buffers && a.framebuffers == b.framebuffers &&
         a.renderbuffers == b.renderbuffers && a.shaders == b.shaders && a.programs == b.programs &&
         a.vertexArrays == b.vertexArrays;
}

}  // namespace

TEST(GlObjects, AbandonedNamesAreForgottenNotDeleted) {
  test::context();
  const int textures = gl::liveObjects().textures;
  gl::TextureHandle old = gl::TextureHandle::create();
  const GLuint name = old.id();
  glBindTexture(GL_TEXTURE_2D, name);  // a name becomes a texture object when first bound
  glBindTexture(GL_TEXTURE_2D, 0);
  gl::abandonContextObjects();
  gl::TextureHandle fresh = gl::TextureHandle::create();
  glBindTexture(GL_TEXTURE_2D, fresh.id());
  glBindTexture(GL_TEXTURE_2D, 0);
  const GLuint freshName = fresh.id();
  EXPECT_EQ(gl::liveObjects().textures, textures + 2);

  old.reset();
  EXPECT_EQ(gl::liveObjects().textures, textures + 1) << "the counter goes down";
  EXPECT_TRUE(glIsTexture(name)) << "but the name of the abandoned context is never passed to glDeleteTextures";
  fresh.reset();
  EXPECT_FALSE(glIsTexture(freshName)) << "names created after the loss are deleted as usual";
  EXPECT_EQ(gl::liveObjects().textures, textures);
  glDeleteTextures(1, &name);  // this context was not really lost: free the name the test leaked on purpose
}

TEST(Viewer, ContextLossRebuildsEveryObjectAndTheSameImage) {
  const gl::LiveObjects baseline = gl::liveObjects();
  Viewer viewer(test::context().caps());
  viewer.state().applyQuery("view=split&radius=1.5");
  const test::RenderedImage before = renderViewer(viewer);
  const gl::LiveObjects running = gl::liveObjects();
  ASSERT_GT(running.total(), baseline.total());

  viewer.contextLost();
  EXPECT_FALSE(viewer.hasContext());
  EXPECT_TRUE(sameLiveObjects(gl::liveObjects(), baseline)) << "every GL object of the lost context was dropped";
  viewer.render(0, kWidth, kHeight);  // while lost: nothing to draw with, and no GL call on dead names

  viewer.contextRestored(test::context().caps());
  const test::RenderedImage after = renderViewer(viewer);
  EXPECT_TRUE(sameLiveObjects(gl::liveObjects(), running)) << "the rebuild holds as many objects as before";
  EXPECT_EQ(after.rgba, before.rgba) << "the restored context renders the same image";
}

TEST(Viewer, SplitScreenShowsAoOffLeftAndOnRight) {
  Viewer viewer(test::context().caps());
  viewer.state().settings.set("ao", "off");
  const test::RenderedImage off = renderViewer(viewer);
  viewer.state().settings.set("ao", "on");
  const test::RenderedImage on = renderViewer(viewer);
  viewer.state().settings.set("ao", "off");  // split shows AO on its right half whatever the switch says
  viewer.state().setViewMode("split");
  const test::RenderedImage split = renderViewer(viewer);
  ASSERT_NE(off.rgba, on.rgba);
  size_t leftDiffers = 0, rightDiffers = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      for (int c = 0; c < 3; ++c) {
        if (x < kWidth / 2 - 1) leftDiffers += split.channel(x, y, c) != off.channel(x, y, c);
        if (x > kWidth / 2) rightDiffers += split.channel(x, y, c) != on.channel(x, y, c);
      }
    }
  }
  EXPECT_EQ(leftDiffers, 0u);
  EXPECT_EQ(rightDiffers, 0u);
}

// The split view compares any switch: with "fxaa", FXAA off on the left and on on the right, whatever the AO does;
// the key c steps through the switches.
TEST(Viewer, SplitScreenComparesTheChosenSwitch) {
  Viewer viewer(test::context().caps());
  viewer.state().settings.set("fxaa", "off");
  const test::RenderedImage off = renderViewer(viewer);
  viewer.state().settings.set("fxaa", "on");
  const test::RenderedImage on = renderViewer(viewer);
  viewer.state().applyQuery("view=split&compare=fxaa");
  const test::RenderedImage split = renderViewer(viewer);
  ASSERT_NE(off.rgba, on.rgba);
  size_t leftDiffers = 0, rightDiffers = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c) {
        // FXAA reads a pixel's neighbours: the columns next to the middle see the other half.
        if (x < kWidth / 2 - 2) leftDiffers += split.channel(x, y, c) != off.channel(x, y, c);
        if (x > kWidth / 2 + 1) rightDiffers += split.channel(x, y, c) != on.channel(x, y, c);
      }
  EXPECT_EQ(leftDiffers, 0u);
  EXPECT_EQ(rightDiffers, 0u);

  const std::vector<std::string>& switches = splitSwitches();
  ASSERT_GT(switches.size(), 3u);
  EXPECT_EQ(switches.front(), "ao");
  viewer.state().view.compare = switches.back();
  viewer.state().setViewMode("final");
  EXPECT_TRUE(viewer.handleKey("c"));
  EXPECT_EQ(viewer.state().viewMode(), "split");
  EXPECT_EQ(viewer.state().view.compare, "ao") << "c wraps around to the first switch";
  EXPECT_TRUE(viewer.handleKey("c"));
  EXPECT_EQ(viewer.state().view.compare, switches[1]);
}

TEST(Viewer, KeysActThroughTheParameterTable) {
  Viewer viewer(test::context().caps());
  ViewerState& state = viewer.state();
  EXPECT_TRUE(viewer.handleKey("]"));
  EXPECT_FLOAT_EQ(state.settings.ao().radius, 1.25f);
  for (int i = 0; i < 100; ++i) viewer.handleKey("]");
  EXPECT_FLOAT_EQ(state.settings.ao().radius, 1e6f) << "clamped to the parameter's range";
  for (int i = 0; i < 100; ++i) viewer.handleKey(",");
  EXPECT_EQ(state.settings.ao().samples, 1);
  EXPECT_TRUE(viewer.handleKey("p"));
  EXPECT_EQ(state.settings.get("preset"), "high") << "p goes on from the preset the changed values came from";
  viewer.handleKey("p");
  viewer.handleKey("p");
  EXPECT_EQ(state.settings.get("preset"), "low") << "and wraps around";

  // The estimator's keys start from the value in use ("auto": the fitted one), clamp to the ranges, and "0" returns
  // all three to their fitted values.
  const EstimatorParameters fitted = state.settings.ao().estimatorAt();
  viewer.handleKey("}");
  EXPECT_FLOAT_EQ(*state.settings.ao().bias, fitted.bias + 0.01f);
  viewer.handleKey("'");
  EXPECT_FLOAT_EQ(*state.settings.ao().contrast, fitted.contrast + 0.5f);
  for (int i = 0; i < 100; ++i) viewer.handleKey("{");
  EXPECT_FLOAT_EQ(*state.settings.ao().bias, 0.0f) << "clamped to the parameter's range";
  for (int i = 0; i < 100; ++i) viewer.handleKey(";");
  EXPECT_FLOAT_EQ(*state.settings.ao().contrast, 0.1f);
  viewer.handleKey("=");
  EXPECT_TRUE(viewer.handleKey("0"));
  EXPECT_EQ(state.settings.get("bias"), "auto");
  EXPECT_EQ(state.settings.get("intensity"), "auto");
  EXPECT_EQ(state.settings.get("contrast"), "auto");
  const int blurRadius = state.settings.ao().blurRadius;
  viewer.handleKey(">");
  EXPECT_EQ(state.settings.ao().blurRadius, blurRadius + 1);
  for (int i = 0; i < 20; ++i) viewer.handleKey("<");
  EXPECT_EQ(state.settings.ao().blurRadius, 0) << "clamped to the parameter's range";
  viewer.handleKey("a");
  EXPECT_FALSE(state.settings.ao().enabled);
  viewer.handleKey("6");
  EXPECT_EQ(state.viewMode(), "split");
  // The other effects' keys: tone mapping and FXAA on / off, exposure in half stops.
  EXPECT_EQ(state.settings.get("fxaa"), "off") << "the low preset above turned FXAA off";
  viewer.handleKey("t");
  viewer.handleKey("f");
  EXPECT_EQ(state.settings.get("tonemap"), "off");
  EXPECT_EQ(state.settings.get("fxaa"), "on");
  viewer.handleKey(")");
  viewer.handleKey(")");
  viewer.handleKey("(");
  EXPECT_EQ(state.settings.get("tonemap.exposure"), "0.5");
  EXPECT_FALSE(viewer.handleKey("?"));

  const Camera original = state.camera;
  viewer.orbit(40.0f, 10.0f, kHeight);
  EXPECT_NE(state.camera.eye, original.eye);
  viewer.handleKey("r");
  EXPECT_EQ(state.camera.eye, original.eye);

  std::set<std::string> keys;
  for (const Viewer::KeyBinding& binding : Viewer::keyBindings()) {
    EXPECT_TRUE(keys.insert(binding.key).second) << "key " << binding.key << " bound twice";
    // A character, or the KeyboardEvent.key name of a key that types none.
    EXPECT_TRUE(binding.key.size() == 1u || binding.key == "ArrowLeft" || binding.key == "ArrowRight" ||
                binding.key == "Home")
        << binding.key;
    EXPECT_FALSE(binding.label.empty());
    EXPECT_FALSE(binding.description.empty());
  }
}

// The cameras through the Viewer, on Debian's Cameras.gltf (a perspective and an orthographic camera): `v` cycles the
// free camera and the file's, each drawn as the Renderer draws it; a move takes the view over as the free camera;
// `x` switches the free camera's projection from the view shown; loading a scene starts on the free camera.
TEST(Viewer, CyclesTheFilesCamerasAndTakesTheViewOverOnAMove) {
  Viewer viewer(test::context().caps());
  ViewerState& state = viewer.state();
  EXPECT_THROW(viewer.handleKey("v"), InputError) << "the built-in scene has no cameras of its own";
  viewer.loadGltfFile(test::assimpModels() + "/cameras/Cameras.gltf");
  ASSERT_EQ(state.sceneCameras.size(), 2u);
  const test::RenderedImage free = renderViewer(viewer);
  viewer.handleKey("v");
  EXPECT_EQ(state.cameraChoice(), "0");
  const test::RenderedImage first = renderViewer(viewer);
  EXPECT_FALSE(viewer.cameraShown().orthographic);
  viewer.handleKey("v");
  EXPECT_EQ(state.cameraChoice(), "1");
  EXPECT_TRUE(viewer.cameraShown().orthographic);
  const test::RenderedImage second = renderViewer(viewer);
  EXPECT_NE(first.rgba, free.rgba);
  EXPECT_NE(second.rgba, first.rgba);
  // The state text brings the same view back in another viewer.
  Viewer other(test::context().caps());
  other.loadGltfFile(test::assimpModels() + "/cameras/Cameras.gltf");
  other.state().applyQuery(state.toQuery());
  EXPECT_EQ(renderViewer(other).rgba, second.rgba);
  viewer.handleKey("v");
  EXPECT_EQ(state.cameraChoice(), "free");
  EXPECT_EQ(renderViewer(viewer).rgba, free.rgba);

  // A move from the orthographic file camera: the free camera takes its view, then moves.
  viewer.setCamera("1");
  const Camera shown = viewer.cameraShown();
  viewer.zoom(1.0f);
  EXPECT_EQ(state.cameraChoice(), "free");
  EXPECT_TRUE(state.camera.orthographic);
  EXPECT_NEAR(glm::length(state.camera.eye - shown.eye), 0.0f, 1e-5f);
  EXPECT_NEAR(state.camera.ymag, shown.ymag, 1e-6f);
  viewer.handleKey("x");
  EXPECT_FALSE(state.camera.orthographic);
  viewer.handleKey("x");
  EXPECT_TRUE(state.camera.orthographic);
  EXPECT_NEAR(state.camera.ymag, shown.ymag, 1e-4f) << "perspective and back keep the view at the target";
  viewer.setCamera("0");
  viewer.loadGltfFile(test::assimpModels() + "/cameras/Cameras.gltf");
  EXPECT_EQ(state.cameraChoice(), "free");
  EXPECT_THROW(viewer.setCamera("2"), InputError);
}

// The timeline through the Viewer, on Debian's simple_skin (a skinned strip, one 5.5 s animation): paused, the clock
// changes nothing; space plays by the clock given to render(); the arrows step frames and pause; the state text
// reproduces the frame in another viewer, and the frame survives context loss.
TEST(Viewer, PlaysTheAnimationByTheClockAndStepsFramesByKeys) {
  const std::string skin = test::assimpModels() + "/simple_skin/simple_skin.gltf";
  Viewer viewer(test::context().caps());
  viewer.loadGltfFile(skin);
  const Timeline& timeline = viewer.state().timeline;
  ASSERT_EQ(timeline.duration(), 5.5);
  viewer.state().setViewMode("normals");
  const test::RenderedImage start = renderViewer(viewer, 10.0);
  EXPECT_EQ(renderViewer(viewer, 11.0).rgba, start.rgba) << "paused";
  EXPECT_EQ(timeline.time(), 0.0);

  EXPECT_TRUE(viewer.handleKey(" "));
  EXPECT_TRUE(viewer.playing());
  renderViewer(viewer, 20.0);  // the first frame only starts the count
  const test::RenderedImage played = renderViewer(viewer, 21.0);
  EXPECT_DOUBLE_EQ(timeline.time(), 1.0);
  EXPECT_NE(played.rgba, start.rgba) << "the scene moved";
  viewer.handleKey(" ");
  EXPECT_FALSE(viewer.playing());
  EXPECT_EQ(renderViewer(viewer, 30.0).rgba, played.rgba) << "paused again: the same frame";

  viewer.handleKey("ArrowRight");
  EXPECT_DOUBLE_EQ(timeline.time(), 61 * Timeline::kFrameInterval);
  viewer.handleKey("ArrowLeft");
  viewer.handleKey("ArrowLeft");
  EXPECT_DOUBLE_EQ(timeline.time(), 59 * Timeline::kFrameInterval);
  const test::RenderedImage stepped = renderViewer(viewer, 31.0);
  EXPECT_NE(stepped.rgba, played.rgba);

  // Speed, loop and the animation by keys (the page has controls for them; the desktop window has only keys).
  viewer.handleKey("*");
  EXPECT_EQ(timeline.speed(), 2.0);
  viewer.handleKey("/");
  viewer.handleKey("/");
  EXPECT_EQ(timeline.speed(), 0.5);
  viewer.handleKey("/");
  viewer.handleKey("*");
  viewer.handleKey("*");
  viewer.handleKey("l");
  EXPECT_FALSE(timeline.loop());
  viewer.handleKey("l");
  viewer.handleKey("n");
  EXPECT_EQ(timeline.animationName(), "none") << "one animation: each, then none";
  EXPECT_THROW(viewer.handleKey(" "), InputError) << "nothing to play at rest";
  viewer.handleKey("n");
  EXPECT_EQ(timeline.animationName(), "0");
  EXPECT_EQ(timeline.time(), 0.0);
  viewer.handleKey("ArrowRight");
  viewer.handleKey("Home");
  EXPECT_EQ(timeline.time(), 0.0);
  EXPECT_EQ(timeline.speed(), 1.0);
  viewer.state().applyQuery("time=" + formatSeconds(59 * Timeline::kFrameInterval));

  // The link's time is the same double, so another viewer draws the same pixels.
  Viewer other(test::context().caps());
  other.loadGltfFile(skin);
  other.state().applyQuery(viewer.state().toQuery());
  EXPECT_EQ(other.state().timeline.time(), timeline.time());
  EXPECT_EQ(renderViewer(other, 5.0).rgba, stepped.rgba);

  // Context loss keeps the timeline, and the restored context draws the same frame.
  viewer.contextLost();
  viewer.contextRestored(test::context().caps());
  EXPECT_EQ(renderViewer(viewer, 40.0).rgba, stepped.rgba);

  // A scene without animations: the keys say why nothing happens.
  const std::string box = test::assimpModels() + "/BoxTextured-glTF-Binary/BoxTextured.glb";
  viewer.loadGltf(readBytes(box), "BoxTextured.glb");
  EXPECT_FALSE(viewer.state().timeline.hasAnimations());
  try {
    viewer.handleKey(" ");
    ADD_FAILURE() << "space on a still scene";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "nothing to play: the scene has no animations");
  }
  EXPECT_THROW(viewer.handleKey("ArrowRight"), InputError);
}

TEST(Viewer, ABadFileLeavesThePreviousSceneOnScreen) {
  Viewer viewer(test::context().caps());
  const test::RenderedImage builtin = renderViewer(viewer);
  const std::string bad = test::assimpModels() + "/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb";
  EXPECT_THROW(viewer.loadGltf(readBytes(bad), "BoxWithInfinites.glb"), InputError);
  EXPECT_EQ(viewer.sceneName(), "built-in scene");
  EXPECT_EQ(renderViewer(viewer).rgba, builtin.rgba);

  // A .gltf whose buffer comes as a side file, as the page passes files dropped together.
  const std::string dir = test::assimpModels() + "/BoxTextured-glTF/";
  EXPECT_THROW(viewer.loadGltf(readBytes(dir + "BoxTextured.gltf"), "BoxTextured.gltf"), InputError);
  viewer.loadGltf(readBytes(dir + "BoxTextured.gltf"), "BoxTextured.gltf",
                  {{"BoxTextured0.bin", readBytes(dir + "BoxTextured0.bin")},
                   {"CesiumLogoFlat.png", readBytes(dir + "CesiumLogoFlat.png")}});
  EXPECT_EQ(viewer.sceneName(), "BoxTextured.gltf");
  EXPECT_EQ(viewer.sceneTriangles(), 12u);
  EXPECT_NE(renderViewer(viewer).rgba, builtin.rgba);
}
