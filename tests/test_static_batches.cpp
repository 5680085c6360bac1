// Static batches (gpu/GpuScene.h, staticBatchCount): the still, rigid, opaque instances that share a material drawn
// as one piece placed in world space. They draw what the instances drawn alone draw, in fewer draws.
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "TestSupport.h"
#include "gl/PipelineState.h"
#include "gl/Program.h"
#include "gpu/GpuScene.h"
#include "renderer/EffectTable.h"
#include "scene/Animation.h"
#include "scene/BuiltinScene.h"
#include "scene/GltfLoader.h"
#include "scene/MeshDetail.h"
#include "scene/Primitives.h"

namespace obscura {
namespace {

// A row of coloured boxes of one material (COLOR_0: the colour stream joins the batch), turned and scaled each their
// own way, one of them mirrored (a negative determinant: drawn alone, with the other winding), on a floor.
Scene boxesWithColours() {
  Scene scene;
  const int material = test::addMaterial(scene, {0.8f, 0.8f, 0.8f});
  Mesh box = makeBox({-0.3f, 0.0f, -0.3f}, {0.3f, 0.6f, 0.3f});
  box.colors.assign(box.positions.size(), glm::vec4(0.9f, 0.5f, 0.2f, 1.0f));
  for (size_t v = 0; v < box.colors.size(); v += 3) box.colors[v] = glm::vec4(0.2f, 0.6f, 0.9f, 1.0f);
  box.material = material;
  scene.meshes.push_back(box);
  for (int k = 0; k < 6; ++k) {
    glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(-2.5f + static_cast<float>(k), 0.0f, 0.0f));
    world = glm::rotate(world, 0.4f * static_cast<float>(k), glm::vec3(0, 1, 0));
    world = glm::scale(world, glm::vec3(1.0f, 0.6f + 0.2f * static_cast<float>(k), 1.0f));
    if (k == 3) world = glm::scale(world, glm::vec3(-1.0f, 1.0f, 1.0f));
    scene.instances.push_back({0, world});
  }
  test::addStill(scene, makeBox({-4.0f, -0.1f, -2.0f}, {4.0f, 0.0f, 2.0f}), {0.7f, 0.7f, 0.7f});
  return scene;
}

// Drawn in batches and drawn alone, each scene's image is the same within rounding: the batch's vertices are placed
// in world space on the CPU, the instance's by the vertex stage, and the two products may round differently (on
// llvmpipe the images are the same, bit for bit). Every effect on too: the velocity pass, the AO's depth peel and the
// forward lighting draw the scene as well; and at two times of an animated scene, whose moving parts join no batch.
TEST(StaticBatches, DrawTheImageOfTheInstancesDrawnAlone) {
  std::vector<test::FramedScene> cases;
  cases.push_back(test::framedBuiltinScene(160, 96));
  cases.push_back(test::framedScene("coloured boxes", boxesWithColours(), 160, 96));
  cases.push_back(test::framedFile("pbr-samples", test::sourceDir() + "/assets/scenes/pbr-samples.glb", 160, 96));
  RendererOptions alone;
  alone.batchStaticInstances = false;
  const RenderSettings every = RenderSettings::everyEffectOn();
  for (const test::FramedScene& c : cases) {
    Renderer batched = test::makeRenderer(), unbatched = test::makeRenderer(alone);
    batched.setScene(c.scene);
    unbatched.setScene(c.scene);
    EXPECT_EQ(unbatched.gpuScene().staticBatchCount(), 0) << c.name;
    for (const RenderSettings& settings : {RenderSettings{}, every}) {
      for (double time : {0.25, 0.5}) {
        FrameOptions options;
        options.time = time;
        const test::RenderedImage a = test::render(batched, c.camera, settings, View::Final, options);
        const test::RenderedImage b = test::render(unbatched, c.camera, settings, View::Final, options);
        const test::ColorDifference difference = test::colorDifference(a, b);
        std::printf("%s, %s, t %.2f: %d batches; mean %.4f, worst %d levels\n", c.name.c_str(),
                    settings.enabled("bloom") ? "every effect" : "defaults", time,
                    batched.gpuScene().staticBatchCount(), difference.mean, difference.worst);
        EXPECT_LT(difference.mean, 0.01) << c.name << " at " << time;
        EXPECT_LE(difference.worst, 4) << c.name << " at " << time;
        EXPECT_EQ(gl::baselineStateDifferences(), "") << c.name;
      }
    }
  }
}

// The still room (BuiltinScene.h): 28 instances in 7 materials. The floor, the red and the gold sphere have a
// material each; the walls (2), the stone (ledge, columns, plinths, piers, arch and stairs: 16), the blue spheres (2)
// and the wooden boxes (5) are batched: 7 draws instead of 28. In the moving room the pendulum's parts and the
// skinned limb draw alone; its still plinth joins the stone.
TEST(StaticBatches, TheBuiltinRoomDrawsOnePieceAMaterial) {
  auto counts = [](const Scene& scene, RendererOptions options) {
    // Every instance, the one this view does not see among them (frustum culling: test_scene_bounds.cpp).
    options.cullToView = false;
    Renderer renderer = test::makeRenderer(options);
    renderer.setScene(scene);
    test::render(renderer, builtinSceneCamera(96, 64), RenderSettings{}, View::Final);
    return std::make_pair(renderer.gpuScene().staticBatchCount(), renderer.gpuScene().lastDrawCounts());
  };
  RendererOptions alone;
  alone.batchStaticInstances = false;
  const Scene still = makeBuiltinScene(BuiltinSceneOptions::still());
  const auto [batches, batched] = counts(still, {});
  const auto [none, unbatched] = counts(still, alone);
  EXPECT_EQ(batches, 4);
  EXPECT_EQ(none, 0);
  EXPECT_EQ(batched.draws, 7);
  EXPECT_EQ(batched.batchedInstances, 25);
  EXPECT_EQ(unbatched.draws, 28);
  EXPECT_EQ(unbatched.batchedInstances, 0);
  EXPECT_EQ(batched.triangles, unbatched.triangles);

  const Scene moving = makeBuiltinScene(BuiltinSceneOptions::withMotion());
  const std::vector<bool> movingNode = movingNodes(moving);
  int still_ = 0;
  for (const Instance& instance : moving.instances)
    if ((instance.node < 0 || !movingNode[static_cast<size_t>(instance.node)]) && instance.skin < 0) ++still_;
  const auto [movingBatches, movingCounts] = counts(moving, {});
  EXPECT_EQ(movingBatches, 4);
  EXPECT_EQ(movingCounts.batchedInstances, 26) << "the still room's 25 and the limb's plinth";
  EXPECT_EQ(movingCounts.draws, 7 + static_cast<int>(moving.instances.size()) - still_)
      << "the still room's 7 and each moving instance's own";
}

// A member keeps its own level of detail (gbuffer.lod): a batch of spheres at several distances draws each at the
// level an instance drawn alone takes, the same triangles, in one draw per run of members at their full detail.
TEST(StaticBatches, MembersKeepTheirLevelsOfDetail) {
  Scene scene;
  const int material = test::addMaterial(scene, {0.8f, 0.5f, 0.3f});
  // 4096 vertices (GpuScene::kBatchMemberVertices), 7.9k triangles; the nearest fills the frame.
  Mesh sphere = makeSphere(0.5f, 63, 63);
  sphere.material = material;
  scene.meshes.push_back(sphere);
  for (int k = 0; k < 5; ++k) {
    const glm::vec3 at(0.0f, 0.0f, -4.0f * static_cast<float>(k));
    scene.instances.push_back({0, glm::translate(glm::mat4(1.0f), at)});
  }
  addDetailLevels(scene);
  ASSERT_FALSE(scene.meshes[0].levels.empty());
  RendererOptions alone;
  alone.batchStaticInstances = false;
  Renderer batched = test::makeRenderer(), unbatched = test::makeRenderer(alone);
  batched.setScene(scene);
  unbatched.setScene(scene);
  const Camera camera = test::makeCamera({0.0f, 0.3f, 0.9f}, {0.0f, 0.0f, -8.0f}, 320, 192);
  RenderSettings lod;
  lod.set("gbuffer.lod", "0.5");
  const test::RenderedImage a = test::render(batched, camera, lod, View::Final);
  const GpuScene::Counts inBatch = batched.gpuScene().lastDrawCounts();
  const test::RenderedImage b = test::render(unbatched, camera, lod, View::Final);
  const GpuScene::Counts each = unbatched.gpuScene().lastDrawCounts();
  std::printf("alone: %d draw calls, %d coarser, %ld triangles; batched: %d draw calls, %d coarser, %ld triangles\n",
              each.drawCalls, each.coarser, each.triangles, inBatch.drawCalls, inBatch.coarser, inBatch.triangles);
  EXPECT_EQ(batched.gpuScene().staticBatchCount(), 1);
  EXPECT_GT(each.coarser, 0) << "the far spheres take coarser levels";
  EXPECT_LT(each.coarser, 5) << "the nearest its full detail";
  EXPECT_EQ(inBatch.coarser, each.coarser);
  EXPECT_EQ(inBatch.triangles, each.triangles);
  EXPECT_EQ(inBatch.draws, 1);
  EXPECT_EQ(inBatch.batchedInstances, 5);
  EXPECT_EQ(each.drawCalls, 5);
  // The nearest at full detail, the others at coarser levels in turn: a call per run of one level.
  EXPECT_GT(inBatch.drawCalls, 1);
  EXPECT_LT(inBatch.drawCalls, each.drawCalls) << "two far spheres at one level draw in one call";
  EXPECT_LT(test::colorDifference(a, b).mean, 0.01);
}

// A mesh instanced many times is not copied as many times: the copies hold at most as many vertices as the scene's
// meshes, or one batch's worth (65536) where those are fewer. Of 200 instances of one 1089-vertex mesh (a forest of
// one tree), 60 join one batch and the rest draw alone; a second, smaller mesh joins first.
TEST(StaticBatches, TheCopiesStayWithinTheirBudget) {
  Scene scene;
  const int material = test::addMaterial(scene, {0.5f, 0.7f, 0.4f});
  Mesh tree = makeSphere(0.3f, 32, 32);  // 33 x 33 = 1089 vertices
  tree.material = material;
  Mesh stone = makeBox({-0.1f, 0.0f, -0.1f}, {0.1f, 0.1f, 0.1f});  // 24 vertices
  stone.material = material;
  scene.meshes = {tree, stone};
  for (int k = 0; k < 200; ++k) {
    const glm::vec3 at(static_cast<float>(k % 20), 0.0f, -static_cast<float>(k / 20));
    scene.instances.push_back({0, glm::translate(glm::mat4(1.0f), at)});
  }
  for (int k = 0; k < 3; ++k)
    scene.instances.push_back({1, glm::translate(glm::mat4(1.0f), glm::vec3(static_cast<float>(k), 0.0f, 1.0f))});
  ASSERT_EQ(scene.meshes[0].positions.size(), 1089u);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  const GpuScene& gpu = renderer.gpuScene();
  EXPECT_EQ(gpu.staticBatchCount(), 1);
  // 65536 vertices' budget: the three stones (72), then 60 trees (65340); the 61st would pass it.
  EXPECT_EQ(gpu.staticBatchVertices(), 3u * 24u + 60u * 1089u);
  test::render(renderer, Camera::fit(scene.worldBounds(), 96, 64), RenderSettings{}, View::Final);
  EXPECT_EQ(gpu.lastDrawCounts().batchedInstances, 63);
  EXPECT_EQ(gpu.lastDrawCounts().draws, 1 + 140);
}

// A pose that moves a member away from where its batch placed it (not one this scene's animations make: they move
// no member) draws that batch's members alone until the pose returns.
TEST(StaticBatches, AMemberPosedElsewhereDrawsItsBatchAlone) {
  const Scene scene = makeBuiltinScene(BuiltinSceneOptions::still());
  GpuScene gpu(scene, test::context().caps());
  ASSERT_EQ(gpu.staticBatchCount(), 4);
  const gl::Program program("static-batches-test",
                            "attribute vec3 a_position; uniform vec4 u_instanceTransforms[7];\n"
                            "void main() { gl_Position = u_instanceTransforms[0] + vec4(a_position, 1.0); }\n",
                            "#ifdef GL_ES\nprecision mediump float;\n#endif\n"
                            "void main() { gl_FragColor = vec4(1.0); }\n");
  const auto choose = [&](MaterialKind, VertexKind) -> const gl::Program& {
    program.use();
    return program;
  };
  const glm::mat4 view = builtinSceneCamera(96, 64).view();
  auto drawn = [&] {
    gpu.withholdDraws(true);  // the draws' choices and counts, no triangles
    gpu.draw(view, choose);
    gpu.withholdDraws(false);
    glUseProgram(0);
    return gpu.lastDrawCounts();
  };
  EXPECT_EQ(drawn().draws, 7);
  const ScenePose rest = evaluatePose(scene, 0.0, PoseOptions{AnimationChoice::none(), false});
  ScenePose moved = rest;
  const size_t lowBox = scene.instances.size() - 2;  // a wooden box: one of its batch's five
  moved.instanceWorld[lowBox] =
      glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.5f, 0.0f)) * rest.instanceWorld[lowBox];
  gpu.setPose(moved, rest);
  GpuScene::Counts counts = drawn();
  EXPECT_EQ(counts.draws, 7 - 1 + 5);
  EXPECT_EQ(counts.batchedInstances, 25 - 5);
  gpu.setPose(rest, moved);  // the previous pose moved: still apart (the velocity pass draws what moved)
  EXPECT_EQ(drawn().draws, 11);
  gpu.setPose(rest, rest);
  counts = drawn();
  EXPECT_EQ(counts.draws, 7);
  EXPECT_EQ(counts.batchedInstances, 25);
  EXPECT_EQ(gl::baselineStateDifferences(), "");
}

}  // namespace
}  // namespace obscura
