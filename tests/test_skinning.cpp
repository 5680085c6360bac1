// Skinning and morph targets on the GPU against the CPU mirror (scene/Animation.h: posedScene): every path GpuScene
// can take (joint texture, uniform palette, palette pieces under GLES 2's minimum limits, CPU) draws the same
// G-buffer as the same pose baked on the CPU and drawn as a still scene.
// GCC 12 warns of a null memmove inside std::vector's assignment here (-Wnonnull, a false positive of its
// optimiser with inlined empty ranges; no line of this file is named in the warning).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wnonnull"
#endif
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "scene/Animation.h"
#include "scene/Primitives.h"
#include "scene/SkinnedTube.h"

namespace obscura {
namespace {

// A vertical tube (radius 0.3, height 4) skinned to a chain of `joints` joints along y that bends about z over one
// second while its root slides along x (scene/SkinnedTube.h), on a floor.
Scene bendingTube(int joints) {
  Scene scene;
  SkinnedTubeShape shape;
  shape.joints = joints;
  addSkinnedTube(scene, shape, glm::vec3(0.0f));
  scene.meshes.push_back(test::makeRectangle({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}));
  scene.instances.push_back(Instance{static_cast<int>(scene.meshes.size()) - 1, glm::mat4(1.0f), -1, -1});
  return scene;
}

// A sphere on a node with `targets` morph targets (each pushes one octant's side outwards, with normal deltas
// where `normals`), their weights animated from 0 to 1 over a second.
Scene morphingSphere(int targets, bool normals) {
  Scene scene;
  Mesh sphere = makeSphere(1.0f, 32, 16);
  for (int t = 0; t < targets; ++t) {
    MorphTarget target;
    const float ft = static_cast<float>(t);
    const glm::vec3 direction =
        glm::normalize(glm::vec3(std::cos(1.7f * ft), 0.4f * static_cast<float>(t % 3) - 0.4f, std::sin(1.7f * ft)));
    for (size_t v = 0; v < sphere.positions.size(); ++v) {
      const float push = std::max(0.0f, glm::dot(sphere.normals[v], direction));
      target.positions.push_back(0.6f * push * push * sphere.normals[v]);
      if (normals) target.normals.push_back(0.3f * push * (direction - sphere.normals[v]));
    }
    sphere.morphTargets.push_back(target);
  }
  scene.meshes.push_back(sphere);
  Node node;
  node.translation = glm::vec3(0.0f, 1.2f, 0.0f);
  node.weights.assign(static_cast<size_t>(targets), 0.0f);
  scene.nodes.push_back(node);
  Animation grow;
  AnimationSampler weights;
  weights.times = {0.0f, 1.0f};
  weights.components = targets;
  weights.values.assign(static_cast<size_t>(targets), 0.0f);
  for (int t = 0; t < targets; ++t)
    weights.values.push_back(0.3f + 0.7f * static_cast<float>(t + 1) / static_cast<float>(targets));
  grow.samplers.push_back(weights);
  grow.channels.push_back({0, 0, AnimationPath::Weights});
  scene.animations.push_back(grow);
  Instance instance;
  instance.mesh = 0;
  instance.node = 0;
  scene.instances.push_back(instance);
  return scene;
}

Camera frontCamera() { return test::makeCamera({0.5f, 2.0f, 9.0f}, {0.5f, 2.0f, 0.0f}, 160, 120, 0.5f, 30.0f); }

// Pixels whose G-buffer bytes (normal and depth) differ by more than `tolerance` in any channel, over the covered
// pixels of either image.
double differingFraction(const test::RenderedImage& a, const test::RenderedImage& b, int tolerance) {
  int differing = 0, covered = 0;
  for (size_t p = 0; p < a.rgba.size(); p += 4) {
    bool same = true;
    for (size_t c = 0; c < 3; ++c) same = same && std::abs(int(a.rgba[p + c]) - int(b.rgba[p + c])) <= tolerance;
    const bool any = a.rgba[p] != 255 || b.rgba[p] != 255;  // depth view: background white
    if (any) ++covered;
    if (!same) ++differing;
  }
  return covered == 0 ? 1.0 : static_cast<double>(differing) / covered;
}

// The scene at `time`, posed on the GPU by `options`, and the same pose baked on the CPU, in two views.
struct PathCase {
  const char* name;
  std::optional<SkinningPath> path;
  bool gles2Minimum;
};

class SkinningPaths : public ::testing::TestWithParam<PathCase> {};

void expectSameAsCpu(const Scene& scene, const RendererOptions& options, double time, const char* what) {
  Renderer gpu = test::makeRenderer(options);
  gpu.setScene(scene);
  FrameOptions frame;
  frame.time = time;
  frame.animation = AnimationChoice::one(0);
  const Camera camera = frontCamera();
  Renderer cpu = test::makeRenderer();
  cpu.setScene(posedScene(scene, evaluatePose(scene, time, PoseOptions{AnimationChoice::one(0), true})));
  for (const View& view : {View::Depth, View::Normals}) {
    const test::RenderedImage posed = test::render(gpu, camera, RenderSettings(), view, frame);
    const test::RenderedImage baked = test::render(cpu, camera, RenderSettings(), view);
    // The same triangles through a different float order: a few edge pixels and one step of depth may differ.
    EXPECT_LT(differingFraction(posed, baked, 2), 0.01) << what << ", view " << view.name;
  }
  // ... and it did move: the rest pose differs.
  FrameOptions rest = frame;
  rest.animation = AnimationChoice::none();
  const test::RenderedImage still = test::render(gpu, camera, RenderSettings(), View::Depth, rest);
  const test::RenderedImage posed = test::render(gpu, camera, RenderSettings(), View::Depth, frame);
  EXPECT_GT(differingFraction(still, posed, 2), 0.02) << what << ": the pose at " << time << " s is not the rest pose";
}

TEST_P(SkinningPaths, DrawTheSameSkinAsTheCpuMirror) {
  const PathCase c = GetParam();
  RendererOptions options;
  options.skinning = c.path;
  if (c.gles2Minimum) options.simulateVertexLimits = VertexLimits::gles2Minimum();
  for (int joints : {3, 40}) {
    const Scene scene = bendingTube(joints);
    Renderer probe = test::makeRenderer(options);
    probe.setScene(scene);
    const GpuScene& gpu = probe.gpuScene();
    const std::string what = std::string(c.name) + ", " + std::to_string(joints) + " joints, path " +
                             skinningPathName(gpu.skinningPath());
    if (c.path == SkinningPath::Cpu) {
      EXPECT_EQ(gpu.skinningPath(), SkinningPath::Cpu);
    }
    if (c.path == SkinningPath::Uniforms) {
      EXPECT_EQ(gpu.skinningPath(), SkinningPath::Uniforms);
    }
    if (c.gles2Minimum && c.path != SkinningPath::Cpu) {
      // No vertex textures at the minimum: the palette, 16 joints; 40 joints need several pieces.
      EXPECT_EQ(gpu.skinningPath(), SkinningPath::Uniforms);
      EXPECT_EQ(gpu.paletteSize(), 16);
      if (joints == 40) {
        EXPECT_GT(gpu.pieceCount(), 3u) << "the tube is split into palette pieces";
      }
    }
    if (!c.path && !c.gles2Minimum && test::context().caps().maxVertexTextureImageUnits > 0 &&
        test::context().caps().textureFloat) {
      EXPECT_EQ(gpu.skinningPath(), SkinningPath::Texture);
    }
    expectSameAsCpu(scene, options, 0.7, what.c_str());
  }
}

INSTANTIATE_TEST_SUITE_P(Skinning, SkinningPaths,
                         ::testing::Values(PathCase{"default", std::nullopt, false},
                                           PathCase{"uniforms", SkinningPath::Uniforms, false},
                                           PathCase{"uniforms-gles2-minimum", SkinningPath::Uniforms, true},
                                           PathCase{"texture-gles2-minimum", SkinningPath::Texture, true},
                                           PathCase{"cpu", SkinningPath::Cpu, false}),
                         [](const auto& param) {
                           std::string name = param.param.name;
                           for (char& ch : name)
                             if (ch == '-') ch = '_';
                           return name;
                         });

TEST(Skinning, ASkeletonLargerThanThePaletteRendersAsWithALargePalette) {
  const Scene scene = bendingTube(40);
  RendererOptions small, large;
  small.skinning = large.skinning = SkinningPath::Uniforms;
  small.simulateVertexLimits = VertexLimits::gles2Minimum();
  Renderer a = test::makeRenderer(small), b = test::makeRenderer(large);
  a.setScene(scene);
  b.setScene(scene);
  ASSERT_LT(a.gpuScene().paletteSize(), 40);
  ASSERT_GE(b.gpuScene().paletteSize(), 40) << "this context's uniforms hold the whole skeleton";
  FrameOptions frame;
  frame.time = 0.6;
  for (const View& view : {View::Depth, View::Normals}) {
    const auto split = test::render(a, frontCamera(), RenderSettings(), view, frame);
    const auto whole = test::render(b, frontCamera(), RenderSettings(), view, frame);
    EXPECT_LT(differingFraction(split, whole, 1), 0.002) << view.name;
  }
}

// A context with GLES 2's 8 combined texture units: the lighting's fragment stage may take all eight (gpu/
// TextureUnits.h), so the joint texture has no unit of its own and the renderer takes the uniform palette, and the
// environment's BRDF table the joints' unit. The image is the joint texture's, on a context with units to spare.
TEST(Skinning, EightCombinedTextureUnitsTakeThePaletteAndTheSameImage) {
  const Scene scene = bendingTube(40);
  RendererOptions eight, plenty;
  eight.skinning = plenty.skinning = SkinningPath::Texture;
  eight.simulateFragmentLimits = FragmentLimits::gles2Minimum();
  Renderer a = test::makeRenderer(eight), b = test::makeRenderer(plenty);
  a.setScene(scene);
  b.setScene(scene);
  EXPECT_EQ(a.gpuScene().skinningPath(), SkinningPath::Uniforms);
  ASSERT_EQ(b.gpuScene().skinningPath(), SkinningPath::Texture) << "this context has a ninth unit";
  FrameOptions frame;
  frame.time = 0.6;
  for (const View& view : {View::Final, View::Normals}) {
    const auto eightUnits = test::render(a, frontCamera(), RenderSettings(), view, frame);
    const auto texture = test::render(b, frontCamera(), RenderSettings(), view, frame);
    EXPECT_LT(differingFraction(eightUnits, texture, 2), 0.002) << view.name;
  }
}

// The forward lighting draws the skin again and shades only where its depth equals the G-buffer's: every covered
// pixel must be shaded exactly once, so the deformation must give the same positions in both passes (geometry.vert's
// invariant gl_Position), on every path.
TEST(Skinning, TheForwardLightingShadesEverySkinnedPixelOnce) {
  const Scene scene = bendingTube(40);
  for (SkinningPath path : {SkinningPath::Texture, SkinningPath::Uniforms, SkinningPath::Cpu}) {
    RendererOptions options;
    options.skinning = path;
    options.allowDrawBuffers = false;
    if (path == SkinningPath::Uniforms) options.simulateVertexLimits = VertexLimits::gles2Minimum();
    Renderer renderer = test::makeRenderer(options);
    renderer.setScene(scene);
    FrameOptions frame;
    frame.time = 0.7;
    const auto depth = test::render(renderer, frontCamera(), RenderSettings(), View::Depth, frame);
    const auto count = test::render(renderer, frontCamera(), RenderSettings(), View{"shading-count"}, frame);
    int covered = 0, wrong = 0;
    for (size_t p = 0; p < depth.rgba.size(); p += 4) {
      const bool geometry = depth.rgba[p] != 255;
      covered += geometry;
      wrong += geometry ? count.rgba[p] != 32 : count.rgba[p] != 0;  // 32/255 per shading
    }
    EXPECT_GT(covered, 1000);
    EXPECT_EQ(wrong, 0) << skinningPathName(renderer.gpuScene().skinningPath());
  }
}

TEST(MorphTargets, OnTheGpuAsFarAsAttributesAllowThenOnTheCpu) {
  RendererOptions minimum;
  minimum.simulateVertexLimits = VertexLimits::gles2Minimum();
  struct Case {
    int targets;
    bool normals;
    bool expectGpu;  // at 8 attributes: 5 free, 2 targets with normals, 4 (the cap) without
  };
  for (const Case c : {Case{2, true, true}, Case{3, true, false}, Case{4, false, true}, Case{6, false, false}}) {
    const Scene scene = morphingSphere(c.targets, c.normals);
    const std::string what = std::to_string(c.targets) + " targets" + (c.normals ? " with normals" : "");
    expectSameAsCpu(scene, minimum, 0.8, what.c_str());
    Renderer renderer = test::makeRenderer(minimum);
    renderer.setScene(scene);
    FrameOptions frame;
    frame.time = 0.8;
    test::render(renderer, frontCamera(), RenderSettings(), View::Depth, frame);
    const GpuScene::Counts counts = renderer.gpuScene().lastDrawCounts();
    EXPECT_EQ(counts.gpuMorphed > 0, c.expectGpu) << what;
    EXPECT_EQ(counts.cpuDeformed > 0, !c.expectGpu) << what;
  }
}

}  // namespace
}  // namespace obscura
