// Resources and limits: GL objects return to their baseline after scene reloads, every pass leaves the baseline GL
// state, a GL error is caught and named, sizes from 1x1 to the context's limit, 16-bit index splitting, and a
// context without fragment highp.
#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "base/Error.h"
#include "gl/GlObjects.h"
#include "gl/PipelineState.h"
#include "gl/RenderTarget.h"
#include "renderer/EffectTable.h"
#include "scene/BuiltinScene.h"
#include "scene/GltfLoader.h"
#include "scene/MeshDetail.h"
#include "scene/Primitives.h"

using namespace obscura;

TEST(Resources, SceneReloadsReturnToTheBaselineObjectCount) {
  Renderer renderer = test::makeRenderer();
  const Camera camera = builtinSceneCamera(96, 64);
  const std::vector<Scene> scenes = {
      makeBuiltinScene(),
      loadGltfFile(test::assimpModels() + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"),
      loadGltfFile(test::assimpModels() + "/BoxTextured-glTF/BoxTextured.gltf")};
  renderer.setScene(scenes[0]);
  test::render(renderer, camera, AoSettings{}, View::Final);  // allocates every target and program once
  const gl::LiveObjects baseline = gl::liveObjects();
  for (int reload = 0; reload < 10; ++reload) {
    renderer.setScene(scenes[static_cast<size_t>(reload) % scenes.size()]);
    renderer.setScene(scenes[0]);
    test::render(renderer, camera, AoSettings{}, View::Final);
    EXPECT_EQ(gl::liveObjects().total(), baseline.total()) << "after reload " << reload;
    EXPECT_EQ(gl::liveObjects().buffers, baseline.buffers);
    EXPECT_EQ(gl::liveObjects().textures, baseline.textures);
  }
}

// The Renderer made by the tests checks the baseline after every pass (checkGlErrors) and names the pass that left
// state behind; this runs every view, at full and half AO resolution, with every tone curve.
TEST(Resources, EveryPassLeavesTheBaselineGlState) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  RenderSettings settings;
  for (bool half : {false, true}) {
    settings.ao().halfResolution = half;
    for (const std::string& view : frameViewNames()) {
      EXPECT_NO_THROW(test::render(renderer, builtinSceneCamera(64, 48), settings, View{view})) << view;
      EXPECT_EQ(gl::baselineStateDifferences(), "") << view;
    }
  }
  for (const char* op : {"linear", "reinhard", "aces", "neutral", "agx"}) {
    settings.set("tonemap.operator", op);
    EXPECT_NO_THROW(test::render(renderer, builtinSceneCamera(64, 48), settings, View::Final)) << op;
  }
}

TEST(Resources, AGlErrorIsCaughtAndAttributed) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  glEnable(0x1234);  // not a capability: GL_INVALID_ENUM, pending until someone asks
  try {
    test::render(renderer, builtinSceneCamera(32, 24), AoSettings{}, View::Final);
    FAIL() << "the GL error went unnoticed";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("pending before the frame"), std::string::npos) << e.what();
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_NO_THROW(test::render(renderer, builtinSceneCamera(32, 24), AoSettings{}, View::Final));
}

// An error raised inside a pass is blamed on that pass: a timer hook (called as each pass ends, before the check)
// raises GL_INVALID_ENUM at the end of the chosen pass.
TEST(Resources, AGlErrorRaisedInAPassNamesThatPass) {
  struct ErrorAtTheEndOf : PassTimer {
    std::string target;
    explicit ErrorAtTheEndOf(std::string p) : target(std::move(p)) {}
    void begin(const std::string&) override {}
    void end(const std::string& pass) override {
      if (pass == target) glEnable(0x1234);
    }
  };
  Renderer renderer = test::makeRenderer();
  // The built-in scene with a line across it, so that the points-and-lines pass runs too.
  Scene scene = makeBuiltinScene();
  scene.lineMeshes.push_back({false, {glm::vec3(-1.0f, 1.0f, 0.0f), glm::vec3(1.0f, 1.0f, 0.0f)}, {}, -1});
  scene.lineInstances.push_back({0, glm::mat4(1.0f), -1});
  // And a transmissive pane, so that the transparent layer's passes (transmission-levels, transparency) run too.
  Material glass;
  glass.transmissionFactor = 1.0f;
  scene.materials.push_back(glass);
  Mesh pane = test::makeRectangle({-1.0f, 0.0f, 0.5f}, {2.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
  pane.material = static_cast<int>(scene.materials.size()) - 1;
  scene.meshes.push_back(pane);
  Instance paneInstance;
  paneInstance.mesh = static_cast<int>(scene.meshes.size()) - 1;
  scene.instances.push_back(paneInstance);
  renderer.setScene(scene);
  // The display colour's stages run as passes of their own where the stages do not fuse.
  RendererOptions separateStages;
  separateStages.fuseStages = false;
  Renderer separate = test::makeRenderer(separateStages);
  separate.setScene(scene);
  // Bloom's chain has all its levels from 128 pixels up (a level is at least 2 pixels).
  const Camera small = builtinSceneCamera(32, 24), large = builtinSceneCamera(128, 128);
  const gl::RenderTarget smallOutput("output", small.width, small.height, GL_NEAREST,
                                     gl::RenderTarget::Depth::Renderbuffer, test::context().caps().depth24);
  const gl::RenderTarget largeOutput("output", large.width, large.height, GL_NEAREST,
                                     gl::RenderTarget::Depth::Renderbuffer, test::context().caps().depth24);
  for (const std::string& pass : framePassNames()) {
    const bool bloom = pass.rfind("bloom", 0) == 0;
    const Camera& camera = bloom ? large : small;
    const gl::RenderTarget& output = bloom ? largeOutput : smallOutput;
    // Where the G-buffer pass writes the base colour too, no frame has a base-colour pass of its own.
    if (pass == "base-color" && test::context().caps().drawBuffers) continue;
    AoSettings settings;
    settings.halfResolution = pass == "upsample";  // the upsampler runs only for half-resolution AO
    settings.temporal = pass == "ao-temporal";
    if (pass == "hierarchy") settings.depthHierarchy = DepthHierarchy::On;  // auto builds none
    // The frame's own passes run for a debug view, the shading count's and the base colour's for theirs, the present
    // pass when the final image is also kept after the frame, the tone-mapping pass when something else reads the
    // HDR colour (otherwise the lighting does its work).
    const View view = pass == "view"            ? View::Ao
                      : pass == "shading-count" ? View{"shading-count"}
                      : pass == "base-color"    ? View{"base-color"}
                      : pass == "velocity"      ? View{"velocity"}
                                                : View::Final;
    RenderSettings frame = settings;
    // The motion blur's passes, TAA's, depth of field's, fog's, bloom's and the edges' run only with their switches
    // on.
    if (pass.rfind("motion-", 0) == 0) frame.set("motion-blur", "on");
    if (pass.rfind("taa", 0) == 0) frame.set("taa", "on");
    if (pass.rfind("dof-", 0) == 0) frame.set("dof", "on");
    if (pass == "fog") frame.set(pass, "on");
    if (bloom) frame.set("bloom", "on");
    if (pass.rfind("edges", 0) == 0) frame.set("edges", "on");
    if (pass == "peel") frame.set("ao.layers", "2");  // the AO's second depth layer
    // The upscale runs below render scale 1, as its own pass where FXAA is off.
    if (pass == "upscale") {
      frame.set("resolution.scale", "0.5");
      frame.set("fxaa", "off");
    }
    // The lens flare and the glare; auto exposure, its histogram passes with
    // percentile metering, its reductions on frames wide enough to need one or two.
    if (pass == "lens-flare") frame.set("lens-flare", "on");
    if (pass == "glare" || pass == "chromatic-aberration") frame.set(pass, "on");
    if (pass.rfind("exposure-", 0) == 0) frame.set("auto-exposure", "on");
    const bool displayStage = pass == "grading" || pass == "vignette" || pass == "grain" || pass == "dither";
    if (displayStage) frame.set(pass, "on");
    if (pass == "grading") frame.set("grading.saturation", "1.2");
    if (pass == "exposure-histogram" || pass == "exposure-bins") frame.set("auto-exposure.metering", "percentile");
    const Camera wide = pass == "exposure-reduce-2" ? builtinSceneCamera(2100, 24)
                        : pass == "exposure-reduce" ? builtinSceneCamera(200, 24)
                                                    : camera;
    const gl::RenderTarget wideOutput("output", wide.width, wide.height, GL_NEAREST,
                                      gl::RenderTarget::Depth::Renderbuffer, test::context().caps().depth24);
    FrameOptions options;
    if (pass == "present") options.retain = {"display-color"};
    if (pass == "tonemap") options.retain = {"scene-color"};
    ErrorAtTheEndOf timer(pass);
    options.timer = &timer;
    try {
      if (wide.width != camera.width)
        renderer.render(wide, frame, view, OutputTarget{wideOutput.framebuffer(), wide.width, wide.height, {}},
                        options);
      else
        (displayStage ? separate : renderer)
            .render(camera, frame, view, OutputTarget{output.framebuffer(), camera.width, camera.height, {}}, options);
      ADD_FAILURE() << "the GL error raised in " << pass << " went unnoticed";
    } catch (const GlError& e) {
      EXPECT_NE(std::string(e.what()).find("after pass " + pass), std::string::npos) << e.what();
    }
    gl::restoreBaselineState();  // the frame was abandoned mid-way
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(Resources, AnIncompleteFramebufferIsNamedWithItsReason) {
  test::context();
  try {
    // A zero-sized colour attachment: GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT (or, on some drivers, missing).
    const gl::RenderTarget target("empty target", 0, 0, GL_NEAREST, gl::RenderTarget::Depth::None, false);
    FAIL() << "a framebuffer with a 0x0 attachment was accepted";
  } catch (const GlError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("framebuffer 'empty target' is incomplete: "), std::string::npos) << message;
    EXPECT_NE(message.find("(status 0x"), std::string::npos) << message;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(Limits, RendersAtOneByOne) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  for (bool half : {false, true}) {
    AoSettings settings;
    settings.halfResolution = half;
    for (const std::string& view : frameViewNames()) {
      const test::RenderedImage image = test::render(renderer, builtinSceneCamera(1, 1), settings, View{view});
      EXPECT_EQ(image.rgba.size(), 4u) << view;
    }
  }
}

TEST(Limits, SizesBeyondTheContextAreRefused) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const int limit = test::context().caps().maxRenderSize();
  try {
    renderer.render(builtinSceneCamera(), AoSettings{}, View::Final, OutputTarget{0, limit + 1, 16, {}});
    FAIL() << "accepted " << limit + 1;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("outside what this context can render"), std::string::npos) << e.what();
  }
}

// The largest size the context allows (16384 on llvmpipe): every target allocates and the pipeline runs. Heavy (6 GB
// on llvmpipe), so ctest runs it once, on the EGL (true GLES 2) context. The scene is a box on a slab, an eighth of the
// frame across in its middle: the targets are the full size, but the passes run over the scene's bounds on screen
// (Renderer: the covered rectangle), a few percent of the pixels, around coordinates of 8192. With the built-in room
// filling the frame it took 54 s alone and 160 to 200 s in the suite.
TEST(Limits, RendersAtTheLargestSizeTheContextAllows) {
  if (!std::getenv("OBSCURA_TEST_LARGEST_SIZE")) GTEST_SKIP() << "run by the limits.largest_size ctest entry";
  Renderer renderer = test::makeRenderer();
  renderer.setScene(test::sceneOf({makeBox({-1.0f, -0.1f, -1.0f}, {1.0f, 0.0f, 1.0f}),
                                   makeBox({-0.3f, 0.0f, -0.3f}, {0.3f, 0.6f, 0.3f})}));
  const int size = test::context().caps().maxRenderSize();
  const Camera camera = test::makeCamera({0.0f, 7.0f, 15.0f}, {0.0f, 0.0f, 0.0f}, size, size, 1.0f, 40.0f);
  // SAO at its fewest samples (the settings below are SAO's: GTAO, the default estimator, ignores them and costs
  // this test about a third more) and the depth hierarchy it reads (auto builds none): every AO target at this size,
  // at the least arithmetic.
  AoSettings settings;
  settings.estimator = AoEstimator::Sao;
  settings.samples = 4;
  settings.spiralTurns = 1;
  settings.depthHierarchy = DepthHierarchy::On;
  settings.blur = false;
  settings.radius = 0.5f;
  const gl::RenderTarget output("largest", size, size, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                                test::context().caps().depth24);
  renderer.render(camera, settings, View::AoRaw, {output.framebuffer(), size, size, {}});
  const std::vector<std::string> ran = test::livePasses(renderer);
  for (const char* pass : {"gbuffer", "hierarchy", "sao"})
    EXPECT_NE(std::find(ran.begin(), ran.end(), pass), ran.end()) << pass;
  // Read the middle eighth of the frame, where the box stands on the slab: AO in range at its foot.
  const int window = size / 8;
  std::vector<std::uint8_t> middle(static_cast<size_t>(window) * window * 4);
  glBindFramebuffer(GL_FRAMEBUFFER, output.framebuffer());
  glReadPixels((size - window) / 2, (size - window) / 2, window, window, GL_RGBA, GL_UNSIGNED_BYTE, middle.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  int occluded = 0;
  for (size_t i = 0; i < middle.size(); i += 4) occluded += middle[i] < 250;
  std::printf("%dx%d: %d occluded pixels in the middle %dx%d\n", size, size, occluded, window, window);
  EXPECT_GT(occluded, 0) << "no AO anywhere in the middle of the frame at " << size << "x" << size;
}

TEST(Limits, MeshesOverSixteenBitsAreSplitWithoutOesElementIndexUint) {
  Mesh big = makeSphere(1.0f, 400, 200);  // 80 k vertices
  ASSERT_GT(big.positions.size(), 65535u);
  Scene scene = test::sceneOf({std::move(big)});
  const Camera camera = test::makeCamera({0, 0.5f, 3.0f}, {0, 0, 0}, 128, 96);
  Renderer withUint = test::makeRenderer();
  RendererOptions webgl1;
  webgl1.allowUint32Indices = false;
  Renderer without = test::makeRenderer(webgl1);
  withUint.setScene(scene);
  without.setScene(scene);
  // A mesh split into pieces has no levels of detail (they index the whole mesh's vertices): both in full.
  RenderSettings settings;
  settings.set("gbuffer.lod", "0");
  EXPECT_FALSE(without.gpuScene().usesUint32Indices());
  EXPECT_GT(without.gpuScene().pieceCount(), 1u);
  // The same triangles are drawn either way: the images agree exactly.
  for (const View& view : {View::Normals, View::Final}) {
    const test::RenderedImage a = test::render(withUint, camera, settings, view);
    const test::RenderedImage b = test::render(without, camera, settings, view);
    EXPECT_EQ(a.rgba, b.rgba) << view.name;
  }
}

// Levels of detail (gbuffer.lod, scene/MeshDetail.h): a dense sphere far away draws a coarser level in every
// geometry pass, and the image stays within a fraction of a level of the full one; near, it draws more triangles;
// at 0 it draws them all. In an orthographic view the level follows the view's size alone.
TEST(Lod, DistantMeshesDrawCoarserLevelsThatLeaveTheImageAsItWas) {
  const Mesh sphere = makeSphere(1.0f, 200, 100);
  const long full = static_cast<long>(sphere.indices.size() / 3);
  Renderer renderer = test::makeRenderer();
  Scene scene = test::sceneOf({sphere});
  addDetailLevels(scene);  // as the loaders do
  ASSERT_FALSE(scene.meshes[0].levels.empty());
  renderer.setScene(scene);
  RenderSettings lod, fullDetail;
  lod.set("gbuffer.lod", "0.5");
  fullDetail.set("gbuffer.lod", "0");
  auto drawn = [&](const Camera& camera, const RenderSettings& settings) {
    test::render(renderer, camera, settings, View::Final);
    return renderer.gpuScene().lastDrawCounts();
  };
  const Camera far = test::makeCamera({0, 0.5f, 12.0f}, {0, 0, 0}, 160, 120);
  const Camera near = test::makeCamera({0, 0.5f, 2.5f}, {0, 0, 0}, 160, 120);
  const GpuScene::Counts farCounts = drawn(far, lod);
  EXPECT_EQ(farCounts.coarser, farCounts.draws);
  EXPECT_LT(farCounts.triangles * 4, full) << "a sphere 20 pixels across needs under a quarter of 40k triangles";
  const GpuScene::Counts nearCounts = drawn(near, lod);
  EXPECT_GT(nearCounts.triangles, farCounts.triangles);
  EXPECT_EQ(drawn(far, fullDetail).triangles, full);
  EXPECT_EQ(drawn(far, fullDetail).coarser, 0);
  for (const Camera& camera : {far, near}) {
    const test::ColorDifference difference = test::colorDifference(
        test::render(renderer, camera, lod, View::Final), test::render(renderer, camera, fullDetail, View::Final));
    EXPECT_LT(difference.mean, 0.25) << "levels of 255, over the whole frame";
  }
  Camera orthographic = far;
  orthographic.orthographic = true;
  orthographic.ymag = 20.0f;  // the sphere 6 pixels across: the coarsest level, as far away
  EXPECT_LE(drawn(orthographic, lod).triangles, farCounts.triangles);
  EXPECT_EQ(drawn(orthographic, lod).coarser, 1);
  orthographic.ymag = 1.2f;  // filling the frame
  EXPECT_GT(drawn(orthographic, lod).triangles, farCounts.triangles);
  // The renderer draws the levels the scene carries and makes none of its own: a hand-made level (every other
  // triangle, with no error) is what a distant sphere draws, and without levels it draws them all.
  Mesh handMade = sphere;
  DetailLevel everyOther;
  for (size_t t = 0; t + 2 < sphere.indices.size(); t += 6)
    everyOther.indices.insert(everyOther.indices.end(), sphere.indices.begin() + static_cast<long>(t),
                              sphere.indices.begin() + static_cast<long>(t) + 3);
  handMade.levels = {everyOther};
  renderer.setScene(test::sceneOf({handMade}));
  EXPECT_EQ(drawn(far, lod).triangles, static_cast<long>(everyOther.indices.size() / 3));
  renderer.setScene(test::sceneOf({sphere}));
  EXPECT_EQ(drawn(far, lod).triangles, full);
  // The frame's preset low takes half a pixel, medium (the default) a third, high and ultra full detail.
  RenderSettings low;
  EXPECT_EQ(low.get("gbuffer.lod"), "0.35");
  low.set("preset", "low");
  EXPECT_EQ(low.get("gbuffer.lod"), "0.5");
  EXPECT_EQ(low.get("gbuffer.preset"), "low");
  low.set("preset", "medium");
  EXPECT_EQ(low.get("gbuffer.lod"), "0.35");
  low.set("preset", "high");
  EXPECT_EQ(low.get("gbuffer.lod"), "0");
}

TEST(Limits, AContextWithoutFragmentHighpIsRefusedClearly) {
  gl::GlCaps caps = test::context().caps();
  caps.fragmentHighp = false;  // as on a mediump-only mobile GPU
  try {
    Renderer renderer(caps);
    FAIL() << "accepted a context without fragment highp";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("no highp float in fragment shaders"), std::string::npos) << e.what();
  }
}

// Vertex array objects (OES_vertex_array_object; core on OSMesa's desktop context) are an extension: the draws
// without them stay, and both draw the same image, bit for bit, on scenes that take each of the draw's paths (rigid
// pieces, the joint texture's skinning, GPU morph targets, which set their streams per draw beside pieces bound by
// their objects, tangents and PBR textures), with every effect on too (the velocity pass, the AO's depth peel and the
// forward lighting draw the scene as well). The Renderer checks after every pass that no object stays bound.
TEST(Resources, VertexArrayObjectsDrawTheSameImageAsStreamsSetPerDraw) {
  const bool available = test::context().caps().vertexArrayObject;
  if (!available) std::printf("this context has no vertex array objects: both renderers set streams per draw\n");
  std::vector<test::FramedScene> cases;
  cases.push_back(test::framedBuiltinScene(96, 64));
  cases.push_back(test::framedFile("pbr-samples", test::sourceDir() + "/assets/scenes/pbr-samples.glb", 96, 64));
  cases.push_back(test::framedFile("simple_skin", test::assimpModels() + "/simple_skin/simple_skin.gltf", 96, 64));
  cases.push_back(test::framedFile(
      "AnimatedMorphCube",
      test::assimpModels() + "/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf", 96, 64));
  RendererOptions without;
  without.allowVertexArrays = false;
  for (const test::FramedScene& c : cases) {
    Renderer withObjects = test::makeRenderer(), withStreams = test::makeRenderer(without);
    withObjects.setScene(c.scene);
    withStreams.setScene(c.scene);
    EXPECT_EQ(withObjects.gpuScene().usesVertexArrays(), available) << c.name;
    EXPECT_FALSE(withStreams.gpuScene().usesVertexArrays()) << c.name;
    for (const RenderSettings& settings : {RenderSettings{}, RenderSettings::everyEffectOn()}) {
      for (double time : {0.25, 0.5}) {  // two frames: the second has a previous pose (motion, history)
        FrameOptions options;
        options.time = time;
        const test::RenderedImage a = test::render(withObjects, c.camera, settings, View::Final, options);
        const test::RenderedImage b = test::render(withStreams, c.camera, settings, View::Final, options);
        EXPECT_EQ(test::worstByteDifference(a, b), 0) << c.name << " at " << time;
        EXPECT_EQ(gl::baselineStateDifferences(), "") << c.name;
        EXPECT_EQ(withStreams.gpuScene().lastDrawCounts().vertexArrays, 0) << c.name;
      }
    }
    if (available) {
      // The last draw call (the last geometry pass of the frame) bound objects for every piece but those morphed on
      // the GPU or deformed on the CPU (the morphed cube's only piece).
      test::render(withObjects, c.camera, RenderSettings{}, View::Final);
      const GpuScene::Counts counts = withObjects.gpuScene().lastDrawCounts();
      EXPECT_GT(counts.draws, 0) << c.name;
      EXPECT_EQ(counts.vertexArrays, counts.draws - counts.gpuMorphed - counts.cpuDeformed) << c.name;
    }
  }
}
