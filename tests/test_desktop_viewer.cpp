// obscura-view end to end under Xvfb: a real window with an OpenGL ES context renders the built-in scene, the AO
// view (and a moment of an animation) matches the headless renderer's, and AO visibly darkens the final image. The
// viewer's --screenshot option reads its own back buffer after the last frame.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "TestSupport.h"
#include "scene/BuiltinScene.h"
#include "scene/ImageIo.h"

using namespace obscura;

namespace {

constexpr const char* kSize = "320x180";

struct Result {
  int status = -1;
  std::string output;
};

// Runs a command line under its own Xvfb server (xvfb-run -a picks a free display number). Where xvfb-run itself
// fails ("xvfb-run: error: ...", its exit status then hides the command's: a clean run once failed to remove its
// temporary directory, status 5), the command runs again, up to three times.
Result runUnderXvfb(const std::string& command) {
  // A log of this process's own: ctest runs the tests of this file as separate processes side by side, and one
  // shared log let a test read another's output.
  static int runs = 0;
  Result result;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const std::string log = ::testing::TempDir() + "obscura-view-" + std::to_string(getpid()) + "-" +
                            std::to_string(++runs) + ".log";
    const std::string full = "xvfb-run -a -s '-screen 0 640x480x24' " + command + " >" + log + " 2>&1";
    const int raw = std::system(full.c_str());
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    std::ifstream file(log);
    std::stringstream text;
    text << file.rdbuf();
    result.output = text.str();
    std::remove(log.c_str());
    if (result.output.find("xvfb-run: error:") == std::string::npos) break;
  }
  return result;
}

Image viewerScreenshot(const std::string& name, const std::string& state, const std::string& scene = "") {
  const std::string path = ::testing::TempDir() + name;
  std::remove(path.c_str());
  const Result r = runUnderXvfb(std::string(OBSCURA_VIEW_BINARY) + " " + scene + " --size " + kSize + " --state '" +
                                state + "' --screenshot " + path);
  EXPECT_EQ(r.status, 0) << r.output;
  return readPng(path);
}

Image headlessRender(const std::string& name, const std::string& args) {
  const std::string path = ::testing::TempDir() + name;
  const std::string command = std::string(OBSCURA_RENDER_BINARY) + " --size " + kSize + " " + args + " --out " + path;
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return readPng(path);
}

double luminance(const Image& image, size_t pixel) {
  const std::uint8_t* p = &image.rgba[pixel * 4];
  return (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0;
}

}  // namespace

TEST(DesktopViewer, OpensAnOpenGlEsWindow) {
  const Result r = runUnderXvfb(std::string(OBSCURA_VIEW_BINARY) + " --size " + kSize + " --screenshot " +
                                ::testing::TempDir() + "view-context.png --frames 1");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("obscura-view: OpenGL ES "), std::string::npos) << r.output;
}

TEST(DesktopViewer, AoViewMatchesTheHeadlessRenderer) {
  const Image window = viewerScreenshot("view-ao.png", "view=ao");
  const Image headless = headlessRender("render-ao.png", "--view ao");
  ASSERT_EQ(window.width, 320);
  ASSERT_EQ(window.height, 180);
  ASSERT_EQ(window.rgba.size(), headless.rgba.size());
  double sum = 0.0;
  int largest = 0;
  for (size_t i = 0; i < window.rgba.size(); ++i) {
    const int diff = std::abs(window.rgba[i] - headless.rgba[i]);
    sum += diff;
    largest = std::max(largest, diff);
  }
  // The same shaders on the same rasteriser (llvmpipe), in a window's back buffer instead of an offscreen target:
  // the full-screen AO view may differ only by rounding.
  EXPECT_LE(sum / static_cast<double>(window.rgba.size()), 0.5) << "mean absolute difference (of 255)";
  EXPECT_LE(largest, 8);
}

// The timeline in --state: a paused frame of Debian's simple_skin (a skinned strip) at 2.25 s is obscura-render's
// --time 2.25, and differs from the frame at 0 s.
TEST(DesktopViewer, ATimeInTheStateMatchesTheHeadlessRenderersTime) {
  const std::string skin = test::assimpModels() + "/simple_skin/simple_skin.gltf";
  const Image window = viewerScreenshot("view-time.png", "view=normals&time=2.25", skin);
  const Image headless = headlessRender("render-time.png", "--scene " + skin + " --view normals --time 2.25");
  const Image start = headlessRender("render-time-0.png", "--scene " + skin + " --view normals");
  ASSERT_EQ(window.rgba.size(), headless.rgba.size());
  auto meanDifference = [](const Image& a, const Image& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.rgba.size(); ++i) sum += std::abs(a.rgba[i] - b.rgba[i]);
    return sum / static_cast<double>(a.rgba.size());
  };
  EXPECT_LE(meanDifference(window, headless), 0.1) << "mean absolute difference (of 255)";
  EXPECT_GT(meanDifference(window, start), 10.0 * meanDifference(window, headless)) << "not the frame at 0 s";
}

// The cameras in --state: a file's own orthographic camera (Debian's Cameras.gltf, camera=1) is obscura-render's
// --camera-node 1, and the built-in view made orthographic (projection=orthographic) is its --orthographic.
TEST(DesktopViewer, CamerasInTheStateMatchTheHeadlessRenderersCameras) {
  const std::string cameras = test::assimpModels() + "/cameras/Cameras.gltf";
  auto meanDifference = [](const Image& a, const Image& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.rgba.size(); ++i) sum += std::abs(a.rgba[i] - b.rgba[i]);
    return sum / static_cast<double>(a.rgba.size());
  };
  const Image node = viewerScreenshot("view-camera-node.png", "view=normals&camera=1", cameras);
  const Image nodeHeadless =
      headlessRender("render-camera-node.png", "--scene " + cameras + " --camera-node 1 --view normals");
  ASSERT_EQ(node.rgba.size(), nodeHeadless.rgba.size());
  EXPECT_LE(meanDifference(node, nodeHeadless), 0.1) << "mean absolute difference (of 255)";
  // The built-in camera made orthographic, as the viewer's x key makes it (the same view at the target).
  const Camera ortho = builtinSceneCamera(320, 180).asOrthographic();
  char state[160];
  std::snprintf(state, sizeof state, "view=normals&projection=orthographic&ymag=%.9g", static_cast<double>(ortho.ymag));
  const Image window = viewerScreenshot("view-orthographic.png", state);
  const Image headless = headlessRender("render-orthographic.png", "--orthographic --view normals");
  EXPECT_LE(meanDifference(window, headless), 0.5) << "mean absolute difference (of 255)";
}

TEST(DesktopViewer, FinalFrameIsNotBlankAndShowsAo) {
  // FXAA off: it resamples edges, and where the AO changes their contrast an edge pixel may brighten; the lit image
  // itself is never brighter with AO.
  const Image withAo = viewerScreenshot("view-final.png", "view=final&fxaa=off");
  const Image withoutAo = viewerScreenshot("view-final-no-ao.png", "view=final&ao=off&fxaa=off");
  ASSERT_EQ(withAo.rgba.size(), withoutAo.rgba.size());
  const size_t pixels = withAo.rgba.size() / 4;

  // Not blank: the frame is not one colour, and most of it is scene rather than the clear colour of the sky.
  double mean = 0.0, squares = 0.0;
  for (size_t i = 0; i < pixels; ++i) {
    const double l = luminance(withAo, i);
    mean += l;
    squares += l * l;
  }
  mean /= static_cast<double>(pixels);
  const double deviation = std::sqrt(squares / static_cast<double>(pixels) - mean * mean);
  EXPECT_GT(deviation, 0.05) << "luminance standard deviation";

  // Visible AO: never brighter than without it, clearly darker in the creases.
  size_t darker = 0, brighter = 0;
  double darkening = 0.0;
  for (size_t i = 0; i < pixels; ++i) {
    const double d = luminance(withoutAo, i) - luminance(withAo, i);
    darker += d > 0.02;
    brighter += d < -0.02;
    darkening += d;
  }
  EXPECT_GT(darker, pixels / 20) << "pixels darkened by AO";
  EXPECT_EQ(brighter, 0u) << "AO only ever darkens";
  EXPECT_GT(darkening / static_cast<double>(pixels), 0.01) << "mean darkening";
}

TEST(DesktopViewer, ABadSceneFileExitsWithStatusTwoAndSaysWhy) {
  const Result r = runUnderXvfb(std::string(OBSCURA_VIEW_BINARY) + " " + test::assimpModels() +
                                "/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb --screenshot " +
                                ::testing::TempDir() + "never.png");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("BoxWithInfinites.glb: mesh 0 primitive 0 POSITION 0 is not finite"), std::string::npos)
      << r.output;
}

// A scene file opened in the viewer gets the default AO radius obscura-render gives it (scene/SceneScale.h: 42 for
// the engine, in centimetres), so the two draw the same AO; a radius in --state is used instead.
TEST(DesktopViewer, AFileGetsTheSameDefaultRadiusAsTheHeadlessRenderer) {
  const std::string engine = test::assimpModels() + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  auto shot = [&](const std::string& name, const std::string& state) {
    const std::string path = ::testing::TempDir() + name;
    std::remove(path.c_str());
    const Result r = runUnderXvfb(std::string(OBSCURA_VIEW_BINARY) + " " + engine + " --size " + kSize +
                                  " --state '" + state + "' --screenshot " + path);
    EXPECT_EQ(r.status, 0) << r.output;
    return readPng(path);
  };
  const Image window = shot("view-engine-ao.png", "view=ao");
  const Image headless = headlessRender("render-engine-ao.png", "--scene " + engine + " --view ao");
  ASSERT_EQ(window.rgba.size(), headless.rgba.size());
  auto meanDifference = [](const Image& a, const Image& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.rgba.size(); ++i) sum += std::abs(a.rgba[i] - b.rgba[i]);
    return sum / static_cast<double>(a.rgba.size());
  };
  EXPECT_LE(meanDifference(window, headless), 0.5) << "mean absolute difference (of 255)";
  const Image small = shot("view-engine-ao-r1.png", "view=ao&radius=1");
  ASSERT_EQ(small.rgba.size(), headless.rgba.size());
  EXPECT_GT(meanDifference(small, headless), 1.0) << "radius 1 (a hundredth of a cylinder) draws other AO";
}
