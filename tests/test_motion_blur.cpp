// Motion blur (effects/motion_blur/MotionBlurEffect.h) against its brute-force reference
// (renderer/AccumulationReference.h: the mean of 64 renders with the blur off, spread over the exposure [T - s/(2F), T
// + s/(2F)]): a turning object, a skinned limb and a camera pan move towards the reference; a still scene is unchanged;
// a still foreground object over a moving background keeps its silhouette; a thin fast object does not vanish. The AO
// and FXAA are off in these frames, so the figures are the blur's alone. Every figure is the mean absolute difference
// of the RGB channels, 0 .. 255.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "TestSupport.h"
#include "effects/motion_blur/MotionBlurEffect.h"
#include "encoding/VelocityPacking.h"
#include "renderer/AccumulationReference.h"
#include "scene/BuiltinScene.h"
#include "scene/ImageIo.h"
#include "scene/Primitives.h"
#include "scene/SkinnedTube.h"

namespace obscura {
namespace {

constexpr int kWidth = 960, kHeight = 540;  // motions of 5 to 40 pixels a frame
constexpr double kFps = 30.0;

RenderSettings blurSettings(bool blur) {
  RenderSettings settings;
  settings.set("ao", "off");
  settings.set("fxaa", "off");
  settings.set("motion-blur", blur ? "on" : "off");
  return settings;
}

// A mesh on a node of its own at `at`, which `sampler` drives along `path` (in animation 0).
void addAnimated(Scene& scene, Mesh mesh, const glm::vec3& color, const glm::vec3& at, AnimationSampler sampler,
                 AnimationPath path) {
  Node node;
  node.translation = at;
  scene.nodes.push_back(node);
  const int index = static_cast<int>(scene.nodes.size()) - 1;
  mesh.material = test::addMaterial(scene, color);
  scene.meshes.push_back(std::move(mesh));
  scene.instances.push_back(
      {static_cast<int>(scene.meshes.size()) - 1, glm::translate(glm::mat4(1.0f), at), index, -1});
  if (scene.animations.empty()) scene.animations.push_back(Animation{"motion", {}, {}});
  Animation& animation = scene.animations.front();
  animation.channels.push_back({static_cast<int>(animation.samplers.size()), index, path});
  animation.samplers.push_back(std::move(sampler));
}

// LINEAR rotation keys about y, every quarter turn (slerp takes the shorter arc), at `turnsPerSecond` for 2 s.
AnimationSampler spinAboutY(float turnsPerSecond) {
  AnimationSampler sampler;
  sampler.components = 4;
  const int keys = static_cast<int>(std::ceil(8.0f * turnsPerSecond)) + 1;  // quarter turns over 2 s
  for (int k = 0; k < keys; ++k) {
    const float t = 2.0f * static_cast<float>(k) / static_cast<float>(keys - 1);
    const glm::quat q = glm::angleAxis(6.2831853f * turnsPerSecond * t, glm::vec3(0.0f, 1.0f, 0.0f));
    sampler.times.push_back(t);
    sampler.values.insert(sampler.values.end(), {q.x, q.y, q.z, q.w});
  }
  return sampler;
}

// LINEAR translation keys from `from` to `to` over 2 s.
AnimationSampler slide(const glm::vec3& from, const glm::vec3& to) {
  AnimationSampler sampler;
  sampler.components = 3;
  sampler.times = {0.0f, 2.0f};
  sampler.values = {from.x, from.y, from.z, to.x, to.y, to.z};
  return sampler;
}

// `start` turning about its eye (about y) at `radiansPerSecond`: a camera pan, as a camera at each time.
std::function<Camera(double)> turning(const Camera& start, double radiansPerSecond) {
  return [start, radiansPerSecond](double t) {
    Camera camera = start;
    const glm::vec3 forward = camera.target - camera.eye;
    camera.target = camera.eye + glm::vec3(glm::rotate(glm::mat4(1.0f), static_cast<float>(radiansPerSecond * t),
                                                       glm::vec3(0.0f, 1.0f, 0.0f)) *
                                           glm::vec4(forward, 0.0f));
    return camera;
  };
}

Scene floorScene() {
  Scene scene;
  test::addStill(scene, makeBox({-20.0f, -0.1f, -20.0f}, {20.0f, 0.0f, 20.0f}, 1.0f), {0.8f, 0.8f, 0.8f});
  return scene;
}

struct Frames {
  test::RenderedImage blurred, sharp;
  LinearImage reference;
};

// The frame at `time` with the blur on and off (each after its previous frame, 1/F earlier, through the camera of
// that time, so the velocity sees the camera's motion too), and the reference over the default shutter.
Frames renderFrames(Renderer& renderer, const std::function<Camera(double)>& cameraAt, double time,
                    double shutter = 0.5) {
  Frames frames;
  AccumulationOptions accumulation;
  accumulation.time = time;
  accumulation.fps = kFps;
  accumulation.shutter = shutter;
  accumulation.samples = 64;
  RenderSettings blur = blurSettings(true);
  blur.set("motion-blur.shutter", std::to_string(shutter));
  frames.reference = accumulateShutter(renderer, cameraAt, blurSettings(false), accumulation);
  for (bool on : {true, false}) {
    const RenderSettings settings = on ? blur : blurSettings(false);
    FrameOptions previous;
    previous.time = time - 1.0 / kFps;
    test::render(renderer, cameraAt(previous.time), settings, View::Final, previous);
    FrameOptions frame;
    frame.time = time;
    frame.previousTime = previous.time;
    (on ? frames.blurred : frames.sharp) = test::render(renderer, cameraAt(time), settings, View::Final, frame);
  }
  return frames;
}

// Mean |a - reference| over the RGB channels of the pixels `where` holds (all by default), 0 .. 255.
double meanError(const test::RenderedImage& a, const LinearImage& reference,
                 const std::function<bool(int, int)>& where = {}) {
  double sum = 0.0;
  size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (where && !where(x, y)) continue;
      for (int c = 0; c < 3; ++c) sum += std::abs(a.channel(x, y, c) - 255.0 * reference.at(x, y, c));
      ++n;
    }
  return n ? sum / (3.0 * static_cast<double>(n)) : 0.0;
}

// The pixels that move: where the reference, the sharp frame or the blurred one differ from another by more than
// 2/255. Elsewhere the frames differ by at most 1/255 (AStillSceneIsUnchanged: a rounding difference of the frame
// drawn through the blur's passes), which would add the same small error to both figures and hide their ratio.
std::function<bool(int, int)> moving(const Frames& frames) {
  return [&frames](int x, int y) {
    for (int c = 0; c < 3; ++c) {
      const double reference = 255.0 * frames.reference.at(x, y, c);
      const int blurred = frames.blurred.channel(x, y, c), sharp = frames.sharp.channel(x, y, c);
      if (std::abs(reference - blurred) > 2.0 || std::abs(reference - sharp) > 2.0 || std::abs(blurred - sharp) > 2)
        return true;
    }
    return false;
  };
}

// The blurred frame is at most half as far from the reference as the sharp one (the target), over the
// pixels that move.
void expectTowardsReference(const Frames& frames, const char* what) {
  // OBSCURA_TEST_DUMP=DIR writes the three frames and each one's difference from the reference (x 8), to look at.
  if (const char* dir = std::getenv("OBSCURA_TEST_DUMP")) {
    std::string name = what;
    std::replace(name.begin(), name.end(), ' ', '-');
    const std::string base = std::string(dir) + "/" + name;
    writePng(base + "-blurred.png", Image{frames.blurred.width, frames.blurred.height, frames.blurred.rgba});
    writePng(base + "-sharp.png", Image{frames.sharp.width, frames.sharp.height, frames.sharp.rgba});
    writePng(base + "-reference.png", frames.reference.toImage());
    for (const auto* image : {&frames.blurred, &frames.sharp}) {
      Image diff{image->width, image->height, image->rgba};
      for (int y = 0; y < image->height; ++y)
        for (int x = 0; x < image->width; ++x)
          for (int c = 0; c < 3; ++c)
            diff.rgba[(y * image->width + x) * 4 + c] = static_cast<std::uint8_t>(std::min(
                255.0, 8.0 * std::abs(image->channel(x, y, c) - 255.0 * frames.reference.at(x, y, c))));
      writePng(base + (image == &frames.blurred ? "-diff-blurred.png" : "-diff-sharp.png"), diff);
    }
  }
  const auto where = moving(frames);
  size_t pixels = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) pixels += where(x, y);
  const double blurred = meanError(frames.blurred, frames.reference, where);
  const double sharp = meanError(frames.sharp, frames.reference, where);
  std::printf("[ motion blur ] %s: MAE against the 64-render reference over the %zu pixels that move: sharp %.3f, "
              "blurred %.3f (ratio %.2f)\n",
              what, pixels, sharp, blurred, blurred / sharp);
  EXPECT_GT(pixels, static_cast<size_t>(kWidth * kHeight / 200)) << what << ": the scene should move enough to blur";
  EXPECT_LE(blurred, 0.5 * sharp) << what;
}

TEST(MotionBlur, ATurningObjectMovesTowardsTheReference) {
  Scene scene = floorScene();
  // A box turning two turns a second about its vertical axis: at 30 fps its corners move 7 to 8 pixels a frame here.
  addAnimated(scene, makeBox({-1.0f, 0.0f, -0.6f}, {1.0f, 1.2f, 0.6f}), {0.8f, 0.3f, 0.2f}, {0.0f, 0.0f, 0.0f},
              spinAboutY(2.0f), AnimationPath::Rotation);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  const Camera camera = test::makeCamera({0.0f, 3.0f, 6.0f}, {0.0f, 0.6f, 0.0f}, kWidth, kHeight);
  expectTowardsReference(renderFrames(renderer, [&](double) { return camera; }, 0.6), "turning box");
}

TEST(MotionBlur, ASkinnedLimbMovesTowardsTheReference) {
  Scene scene = floorScene();
  SkinnedTubeShape shape;
  shape.joints = 6;
  shape.radius = 0.5f;
  shape.bendRadians = 2.0f;  // bends 2 radians and slides 0.5 m in a second
  addSkinnedTube(scene, shape, {0.0f, 0.0f, 0.0f});
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  const Camera camera = test::makeCamera({0.3f, 2.0f, 5.0f}, {0.3f, 2.0f, 0.0f}, kWidth, kHeight);
  expectTowardsReference(renderFrames(renderer, [&](double) { return camera; }, 0.5), "skinned limb");
}

TEST(MotionBlur, ACameraPanMovesTowardsTheReference) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  // The camera turns about its eye at 1.5 radians a second: the room sweeps across the frame.
  expectTowardsReference(renderFrames(renderer, turning(builtinSceneCamera(kWidth, kHeight), 1.5), 0.2),
                         "camera pan");
}

// The file's camera on an animated node (issue 31): perspective, and orthographic with the view it has at the target,
// sliding sideways across the room at 3 m/s. Each frame looks through the scene camera (FrameOptions::sceneCamera),
// so the velocity pass sees the camera move from where the pose put it at the previous time; the reference averages
// 64 renders through the camera wherever the animation put it at each instant of the shutter.
TEST(MotionBlur, AnAnimatedSceneCameraMovesTowardsTheReference) {
  const Camera view = builtinSceneCamera(kWidth, kHeight);
  for (bool orthographic : {false, true}) {
    Scene scene = makeBuiltinScene(BuiltinSceneOptions::still());
    Node node;
    node.rotation = glm::quat_cast(glm::mat3(glm::inverse(view.view())));
    scene.nodes.push_back(node);
    const glm::vec3 side = glm::normalize(glm::cross(view.target - view.eye, view.up));
    AnimationSampler slide;
    slide.times = {0.0f, 2.0f};
    const glm::vec3 from = view.eye - side * 3.0f, to = view.eye + side * 3.0f;
    slide.values = {from.x, from.y, from.z, to.x, to.y, to.z};
    slide.components = 3;
    scene.animations.push_back(Animation{"dolly", {slide}, {{0, 0, AnimationPath::Translation}}});
    SceneCamera camera;
    camera.orthographic = orthographic;
    camera.yfov = view.fovyRadians();
    camera.ymag = view.asOrthographic().ymag;
    camera.xmag = camera.ymag * view.aspect();
    camera.znear = view.near;
    camera.zfar = view.far;
    camera.node = 0;
    scene.cameras.push_back(camera);
    Renderer renderer = test::makeRenderer();
    renderer.setScene(scene);

    const double time = 1.0;
    const auto cameraAt = [&](double t) {
      FrameOptions options;
      options.time = t;
      options.sceneCamera = 0;
      return renderer.frameCamera(view, kWidth, kHeight, options);
    };
    Frames frames;
    AccumulationOptions accumulation;
    accumulation.time = time;
    accumulation.fps = kFps;
    accumulation.samples = 64;
    frames.reference = accumulateShutter(renderer, cameraAt, blurSettings(false), accumulation);
    for (bool on : {true, false}) {
      FrameOptions previous;
      previous.time = time - 1.0 / kFps;
      previous.sceneCamera = 0;
      test::render(renderer, view, blurSettings(on), View::Final, previous);
      FrameOptions frame = previous;
      frame.time = time;
      frame.previousTime = previous.time;
      (on ? frames.blurred : frames.sharp) = test::render(renderer, view, blurSettings(on), View::Final, frame);
    }
    expectTowardsReference(frames, orthographic ? "orthographic scene camera" : "perspective scene camera");
  }
}

// Where nothing moves, nothing changes: every tile's neighbourhood moves less than half a pixel, and the early exit
// copies the pixel.
TEST(MotionBlur, AStillSceneIsUnchanged) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const Camera camera = builtinSceneCamera(kWidth, kHeight);
  RenderSettings blur = blurSettings(true), sharp = blurSettings(false);
  for (RenderSettings* s : {&blur, &sharp}) s->set("ao", "on"), s->set("fxaa", "on");
  test::render(renderer, camera, blur, View::Final);
  const test::RenderedImage blurred = test::render(renderer, camera, blur, View::Final);
  const test::RenderedImage still = test::render(renderer, camera, sharp, View::Final);
  int largest = 0;
  for (size_t i = 0; i < still.rgba.size(); ++i) largest = std::max(largest, std::abs(blurred.rgba[i] - still.rgba[i]));
  EXPECT_LE(largest, 1) << "no pixel of a still frame changes by more than 1/255";
}

// Pixels within `band` pixels of the edge of `mask` (a RenderedImage of the mask view: geometry white).
std::function<bool(int, int)> silhouetteBand(const test::RenderedImage& mask, int band, bool inside) {
  return [&mask, band, inside](int x, int y) {
    const bool here = mask.channel(x, y, 0) > 127;
    if (here != inside) return false;
    for (int dy = -band; dy <= band; ++dy)
      for (int dx = -band; dx <= band; ++dx) {
        const int u = x + dx, v = y + dy;
        if (u < 0 || v < 0 || u >= mask.width || v >= mask.height) continue;
        if ((mask.channel(u, v, 0) > 127) != here) return true;
      }
    return false;
  };
}

// The classic failure of gather filters: a still object in front of a moving background smeared over it, or the
// background's blur stopping short of it. Measured in a 3-pixel band on each side of the object's silhouette.
TEST(MotionBlur, AStillForegroundOverAMovingBackgroundKeepsItsSilhouette) {
  Scene scene;
  // Background: a row of coloured posts sliding left to right, 6 m a second, 4 m behind a still box, close enough
  // (0.7 m apart, 0.35 m wide) that their edges pass behind both sides of the box.
  for (int i = 0; i < 24; ++i) {
    const float x = -10.0f + 0.7f * static_cast<float>(i);
    const glm::vec3 color = i % 2 ? glm::vec3(0.9f, 0.2f, 0.2f) : glm::vec3(0.2f, 0.3f, 0.9f);
    addAnimated(scene, makeBox({-0.175f, 0.0f, -0.3f}, {0.175f, 3.0f, 0.3f}), color, {x, 0.0f, -4.0f},
                slide({x, 0.0f, -4.0f}, {x + 12.0f, 0.0f, -4.0f}), AnimationPath::Translation);
  }
  Scene foreground;
  test::addStill(foreground, makeBox({-0.8f, 0.5f, -0.5f}, {0.8f, 2.0f, 0.5f}), {0.9f, 0.8f, 0.3f});
  test::addStill(scene, foreground.meshes.front(), {0.9f, 0.8f, 0.3f});
  const Camera camera = test::makeCamera({0.0f, 1.5f, 6.0f}, {0.0f, 1.5f, 0.0f}, kWidth, kHeight);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(foreground);
  const test::RenderedImage mask = test::render(renderer, camera, blurSettings(false), View::Mask);
  renderer.setScene(scene);
  const Frames frames = renderFrames(renderer, [&](double) { return camera; }, 1.0);

  const auto isMoving = moving(frames);
  for (bool inside : {true, false}) {
    const auto inBand = silhouetteBand(mask, 3, inside);
    // Inside, every pixel of the band counts (none moves, in the reference either: a blur smeared over the box would
    // show); outside, the moving ones, as in expectTowardsReference.
    const auto band = [&](int x, int y) { return inBand(x, y) && (inside || isMoving(x, y)); };
    size_t pixels = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) pixels += band(x, y);
    const double blurred = meanError(frames.blurred, frames.reference, band);
    const double sharp = meanError(frames.sharp, frames.reference, band);
    std::printf("[ motion blur ] silhouette band %s the still box (%zu pixels): MAE sharp %.3f, blurred %.3f\n",
                inside ? "inside" : "outside", pixels, sharp, blurred);
    EXPECT_GT(pixels, static_cast<size_t>(500)) << "the band is measured";
    if (inside) {
      // The box is still and in front: it is sharp in the reference, and stays so (no background smeared over it).
      EXPECT_LE(blurred, 1.0) << "the still box's own pixels stay as they were";
    } else {
      // The background beside it blurs as the reference does, up to the silhouette.
      EXPECT_LE(blurred, 0.6 * sharp);
    }
  }
  expectTowardsReference(frames, "sliding posts behind a still box");
}

// A thin pole crossing the frame fast: its streak carries as much of its colour as the reference's (a gather filter
// whose taps step over it, or whose tiles miss it, would lose it).
TEST(MotionBlur, AThinFastObjectDoesNotVanish) {
  Scene background = floorScene();
  test::addStill(background, makeBox({-6.0f, 0.0f, -3.2f}, {6.0f, 4.0f, -3.0f}), {0.7f, 0.7f, 0.7f});
  Scene scene = background;
  // 4 cm wide, 6 m a second across: 20 times its width per frame at 30 fps.
  addAnimated(scene, makeBox({-0.02f, 0.0f, -0.02f}, {0.02f, 3.0f, 0.02f}), {0.05f, 0.05f, 0.05f},
              {-6.0f, 0.0f, 0.0f}, slide({-6.0f, 0.0f, 0.0f}, {6.0f, 0.0f, 0.0f}), AnimationPath::Translation);
  const Camera camera = test::makeCamera({0.0f, 1.5f, 6.0f}, {0.0f, 1.5f, 0.0f}, kWidth, kHeight);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(background);
  // The frame without the pole, drawn the way each frame compared with it was (see moving()): with the blur on
  // (nothing moves: the early exit's copy) for the blurred frame, off for the others.
  const test::RenderedImage empty = test::render(renderer, camera, blurSettings(false), View::Final);
  const test::RenderedImage emptyBlurPath = test::render(renderer, camera, blurSettings(true), View::Final);
  renderer.setScene(scene);
  const Frames frames = renderFrames(renderer, [&](double) { return camera; }, 1.0);
  // "Ink": how much the pole darkens the frame, summed over the columns it reaches in any of the three frames (where
  // one is more than 8 steps darker than the frame without it), and 8 more each side. Not over the whole frame: on
  // NVIDIA's driver (an H200, 2026-11-30) the frames without the pole differ from the reference's sub-frames by a
  // step in a share of the pixels everywhere (a 0.08-step mean, a quarter of the pole's ink over the whole frame;
  // they are drawn into an output without depth, the sub-frames into one with it); on Mesa not at all.
  int firstColumn = kWidth, lastColumn = -1;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c)
        if (empty.channel(x, y, c) - frames.sharp.channel(x, y, c) > 8 ||
            emptyBlurPath.channel(x, y, c) - frames.blurred.channel(x, y, c) > 8 ||
            empty.channel(x, y, c) - 255.0 * frames.reference.at(x, y, c) > 8.0) {
          firstColumn = std::min(firstColumn, x);
          lastColumn = std::max(lastColumn, x);
        }
  ASSERT_GE(lastColumn, 0) << "the pole is seen";
  double blurredInk = 0.0, referenceInk = 0.0, sharpInk = 0.0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = std::max(firstColumn - 8, 0); x <= std::min(lastColumn + 8, kWidth - 1); ++x)
      for (int c = 0; c < 3; ++c) {
        blurredInk += emptyBlurPath.channel(x, y, c) - frames.blurred.channel(x, y, c);
        sharpInk += empty.channel(x, y, c) - frames.sharp.channel(x, y, c);
        referenceInk += empty.channel(x, y, c) - 255.0 * frames.reference.at(x, y, c);
      }
  std::printf("[ motion blur ] thin pole: ink (sum of darkening over columns %d to %d) sharp %.0f, blurred %.0f, "
              "reference %.0f\n",
              firstColumn - 8, lastColumn + 8, sharpInk, blurredInk, referenceInk);
  EXPECT_GT(referenceInk, 1000.0) << "the pole is seen";
  EXPECT_NEAR(blurredInk / referenceInk, 1.0, 0.25) << "the streak keeps the pole's share of the frame";
  expectTowardsReference(frames, "thin fast pole");
}

// TileMax and NeighborMax against their CPU mirror, on a frame where the camera pans fast and the built-in scene's
// pendulum and limb move: from the velocity target the GPU wrote, the mirror computes each pixel's half-vector V
// (velocity x shutter/2 x frame size, its length clamped to K), the largest V by length of each K x K tile (the
// two passes, each result quantised through VelocityPacking as the targets are), then the largest of each 3 x 3 tiles
// (the edge tile repeated outside the frame). 650 x 370 leaves partial tiles on the right and top edges.
TEST(MotionBlur, TheTileAndNeighbourMaximaAgreeWithTheCpuMirror) {
  constexpr int width = 650, height = 370;
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::withMotion()));
  const auto cameraAt = turning(builtinSceneCamera(width, height), 3.0);
  const RenderSettings settings = blurSettings(true);
  const MotionBlurSettings blur = settings.of<MotionBlurSettings>();
  FrameOptions previous;
  previous.time = 1.0 - 1.0 / kFps;
  test::render(renderer, cameraAt(previous.time), settings, View::Final, previous);
  FrameOptions frame = test::retaining({"velocity", "motion-tiles", "motion-neighbors"});
  frame.time = 1.0;
  frame.previousTime = previous.time;
  test::render(renderer, cameraAt(frame.time), settings, View::Final, frame);

  const int k = blur.tileSize(height);
  const int tilesX = (width + k - 1) / k, tilesY = (height + k - 1) / k;
  const glm::vec2 size(static_cast<float>(width), static_cast<float>(height));
  const glm::vec2 halfExposure = 0.5f * blur.shutter * size;
  const std::vector<std::uint8_t> velocity = renderer.retained("velocity").readRgba();
  const gl::RenderTarget& tilesTarget = renderer.retained("motion-tiles");
  const gl::RenderTarget& neighborsTarget = renderer.retained("motion-neighbors");
  ASSERT_EQ(tilesTarget.width(), tilesX);
  ASSERT_EQ(tilesTarget.height(), tilesY);
  ASSERT_EQ(neighborsTarget.width(), tilesX);
  const std::vector<std::uint8_t> tilesGpu = tilesTarget.readRgba(), neighborsGpu = neighborsTarget.readRgba();

  // Images are read back rows top to bottom; the passes count rows from the bottom (gl_FragCoord).
  const auto texel = [](const std::vector<std::uint8_t>& rgba, int w, int h, int x, int y) {
    return &rgba[(static_cast<size_t>(h - 1 - y) * w + x) * 4];
  };
  const auto quantised = [&](glm::vec2 v) {
    return VelocityPacking::velocityFromBytes(VelocityPacking::bytesFromVelocity(v / size).data()) * size;
  };
  const auto larger = [](glm::vec2 candidate, glm::vec2 largest) { return glm::dot(candidate, candidate) >
                                                                          glm::dot(largest, largest); };
  // V of each pixel.
  std::vector<glm::vec2> halfVectors(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      glm::vec2 v = VelocityPacking::velocityFromBytes(texel(velocity, width, height, x, y)) * halfExposure;
      const float length = glm::length(v);
      if (length > static_cast<float>(k)) v *= static_cast<float>(k) / length;
      halfVectors[static_cast<size_t>(y) * width + x] = v;
    }
  // TileMax, in the passes' order: rows of K pixels, then columns of K of those.
  std::vector<glm::vec2> columns(static_cast<size_t>(tilesX) * height), tiles(static_cast<size_t>(tilesX) * tilesY);
  for (int y = 0; y < height; ++y)
    for (int tx = 0; tx < tilesX; ++tx) {
      glm::vec2 largest(0.0f);
      bool first = true;
      for (int x = tx * k; x < std::min(width, tx * k + k); ++x) {
        const glm::vec2 v = halfVectors[static_cast<size_t>(y) * width + x];
        if (first || larger(v, largest)) largest = v;
        first = false;
      }
      columns[static_cast<size_t>(y) * tilesX + tx] = quantised(largest);
    }
  for (int ty = 0; ty < tilesY; ++ty)
    for (int tx = 0; tx < tilesX; ++tx) {
      glm::vec2 largest(0.0f);
      bool first = true;
      for (int y = ty * k; y < std::min(height, ty * k + k); ++y) {
        const glm::vec2 v = columns[static_cast<size_t>(y) * tilesX + tx];
        if (first || larger(v, largest)) largest = v;
        first = false;
      }
      tiles[static_cast<size_t>(ty) * tilesX + tx] = quantised(largest);
    }

  // Compares the GPU's tiles with the mirror's: the lengths within 0.1 pixel everywhere (float order and a code of
  // quantisation apart); the vectors too, where the motion is shorter than K (at most 1 % of tiles apart: near-ties).
  int movingTiles = 0;
  const auto compare = [&](const std::vector<std::uint8_t>& gpu, const std::vector<glm::vec2>& cpu, const char* what) {
    int vectorMismatches = 0, clampedTiles = 0;
    float worstLength = 0.0f;
    for (int ty = 0; ty < tilesY; ++ty)
      for (int tx = 0; tx < tilesX; ++tx) {
        const glm::vec2 g = VelocityPacking::velocityFromBytes(texel(gpu, tilesX, tilesY, tx, ty)) * size;
        const glm::vec2 c = cpu[static_cast<size_t>(ty) * tilesX + tx];
        worstLength = std::max(worstLength, std::abs(glm::length(g) - glm::length(c)));
        // Motions clamped to K are exactly as long as each other: which of them wins is float order.
        const bool clamped = glm::length(c) > static_cast<float>(k) - 0.05f;
        clampedTiles += clamped;
        vectorMismatches += !clamped && glm::length(g - c) > 0.1f;
        movingTiles += glm::length(c) > 1.0f;
      }
    std::printf("[ motion blur ] %s: %d x %d tiles of %d px, largest length difference %.4f px; of the %d tiles "
                "below the clamp to K, %d vectors more than 0.1 px apart\n",
                what, tilesX, tilesY, k, worstLength, tilesX * tilesY - clampedTiles, vectorMismatches);
    EXPECT_LE(worstLength, 0.1f) << what;
    EXPECT_LE(vectorMismatches, tilesX * tilesY / 100) << what;
  };
  compare(tilesGpu, tiles, "TileMax");

  // NeighborMax: the largest of the 3 x 3 tiles around, rows from the bottom, left to right.
  std::vector<glm::vec2> neighbors(tiles.size());
  for (int ty = 0; ty < tilesY; ++ty)
    for (int tx = 0; tx < tilesX; ++tx) {
      glm::vec2 largest(0.0f);
      bool first = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = std::clamp(tx + dx, 0, tilesX - 1), v = std::clamp(ty + dy, 0, tilesY - 1);
          const glm::vec2 candidate = tiles[static_cast<size_t>(v) * tilesX + u];
          if (first || larger(candidate, largest)) largest = candidate;
          first = false;
        }
      neighbors[static_cast<size_t>(ty) * tilesX + tx] = quantised(largest);
    }
  compare(neighborsGpu, neighbors, "NeighborMax");
  // The frame moves: most tiles hold motions of pixels, and the clamp to K is reached somewhere.
  EXPECT_GT(movingTiles, tilesX * tilesY) << "over both comparisons";
  float longest = 0.0f;
  for (const glm::vec2& v : tiles) longest = std::max(longest, glm::length(v));
  EXPECT_GT(longest, 0.95f * static_cast<float>(k)) << "the pan should reach the largest blur radius";
}

TEST(MotionBlurSettings, TheTileSizeScalesWithTheHeightAndTheParametersAreTheTables) {
  MotionBlurSettings settings;
  EXPECT_EQ(settings.tileSize(720), 20);
  EXPECT_EQ(settings.tileSize(1080), 30);
  EXPECT_EQ(settings.tileSize(360), 10);
  EXPECT_EQ(settings.tileSize(10), 1);
  settings.maxRadius = 64.0f;
  EXPECT_EQ(settings.tileSize(4320), MotionBlurEffect::kMaxTile);
  RenderSettings frame;
  EXPECT_EQ(frame.get("motion-blur"), "off");
  EXPECT_EQ(frame.get("motion-blur.shutter"), "0.5");
  EXPECT_THROW(frame.set("motion-blur.shutter", "1.5"), InputError);
  EXPECT_THROW(frame.set("motion-blur.samples", "1"), InputError);
  EXPECT_TRUE(effectEntry("motion-blur").info.temporal);
}

}  // namespace
}  // namespace obscura
