// Points and lines (effects/lines/LinesEffect.h) and compressed files through the whole frame:
// - lines and points are drawn where they project, in their colour (unlit), hidden where a surface is nearer, not in
//   the G-buffer (the mask) and not in the AO (the same AO with and without them);
// - the corpus's Mesh_PrimitiveMode files draw their segments and points where they project;
// - the Draco copy of 2CylinderEngine renders the same mask, depth and normals as the uncompressed one, within its
//   quantisation.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "frame/FrameContext.h"
#include "scene/GltfLoader.h"

using namespace obscura;

namespace {

constexpr int kWidth = 240, kHeight = 180;

glm::vec2 windowOf(const Camera& camera, const glm::vec3& p) {  // x right, y down (image rows), pixel centres at .5
  const FrameCamera frame = FrameCamera::from(camera, camera.width, camera.height);
  const glm::vec3 w = glm::project(p, frame.view, frame.projection, glm::vec4(0, 0, camera.width, camera.height));
  return {w.x, static_cast<float>(camera.height) - w.y};
}

bool lit(const test::RenderedImage& image, int x, int y, float threshold = 0.5f) {
  return float(image.channel(x, y, 0) + image.channel(x, y, 1) + image.channel(x, y, 2)) > threshold * 3.0f * 255.0f;
}

// A grey wall (z = 0, x and y in [-1, 1]) facing the camera; a red line in front of it (z = 0.5) reaching past its
// right edge over the background; a green line behind it (z = -0.5), hidden; a row of blue points in front.
Scene wallWithLines() {
  Scene scene = test::sceneOf({test::makeRectangle({-1.0f, -1.0f, 0.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f})});
  scene.materials.push_back(Material());
  scene.materials.back().baseColorFactor = glm::vec4(0.2f, 0.2f, 0.2f, 1.0f);
  scene.meshes[0].material = 0;
  LineMesh red;
  red.positions = {{-0.8f, 0.5f, 0.5f}, {1.8f, 0.5f, 0.5f}};
  red.colors = {glm::vec4(1, 0, 0, 1), glm::vec4(1, 0, 0, 1)};
  LineMesh green;
  green.positions = {{-0.8f, -0.2f, -0.5f}, {0.8f, -0.2f, -0.5f}};
  green.colors = {glm::vec4(0, 1, 0, 1), glm::vec4(0, 1, 0, 1)};
  LineMesh blue;
  blue.points = true;
  for (int i = 0; i < 5; ++i) blue.positions.push_back({-0.6f + 0.3f * float(i), -0.6f, 0.3f});
  blue.colors.assign(blue.positions.size(), glm::vec4(0, 0, 1, 1));
  for (LineMesh* mesh : {&red, &green, &blue}) {
    scene.lineInstances.push_back({static_cast<int>(scene.lineMeshes.size()), glm::mat4(1.0f), -1});
    scene.lineMeshes.push_back(*mesh);
  }
  return scene;
}

}  // namespace

TEST(PointsAndLines, DrawnWhereTheyProjectHiddenBehindSurfacesAndOutOfTheAo) {
  const Camera camera = test::makeCamera({0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, kWidth, kHeight);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(wallWithLines());
  const RenderSettings settings;
  const test::RenderedImage color = test::render(renderer, camera, settings, View{"scene-color"});
  const test::RenderedImage mask = test::render(renderer, camera, settings, View::Mask);
  const test::RenderedImage ao = test::render(renderer, camera, settings, View::Ao);

  // The red line: red along its projection, over the wall and over the background alike.
  const glm::vec2 from = windowOf(camera, {-0.8f, 0.5f, 0.5f}), to = windowOf(camera, {1.8f, 0.5f, 0.5f});
  const int row = static_cast<int>(from.y);
  int red = 0, columns = 0;
  for (int x = static_cast<int>(from.x) + 2; x < std::min(static_cast<int>(to.x) - 2, kWidth - 1); ++x, ++columns) {
    bool found = false;
    for (int dy = -1; dy <= 1; ++dy)
      found = found || (color.channel(x, row + dy, 0) > 200 && color.channel(x, row + dy, 1) < 40);
    red += found;
  }
  EXPECT_GT(columns, 100);
  EXPECT_EQ(red, columns) << "the red line has gaps";
  const int pastTheWall = static_cast<int>(windowOf(camera, {1.4f, 0.5f, 0.5f}).x);
  EXPECT_EQ(mask.channel(pastTheWall, row, 0), 0) << "not background past the wall";
  EXPECT_EQ(mask.channel(static_cast<int>(from.x) + 10, row, 0), 255) << "not the wall under the line";

  // The green line is behind the wall: nowhere.
  int green = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      green += color.channel(x, y, 1) > 150 && color.channel(x, y, 0) < 60 && color.channel(x, y, 2) < 60;
  EXPECT_EQ(green, 0);

  // The points: blue squares of max(1, round(180 / 360)) = 1 pixel where they project.
  for (int i = 0; i < 5; ++i) {
    const glm::vec2 p = windowOf(camera, {-0.6f + 0.3f * float(i), -0.6f, 0.3f});
    bool found = false;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        found = found || color.channel(static_cast<int>(p.x) + dx, static_cast<int>(p.y) + dy, 2) > 200;
    EXPECT_TRUE(found) << "point " << i;
  }

  // Not in the G-buffer, so not in the AO: the wall's AO is that of the wall alone.
  Scene wallAlone = wallWithLines();
  wallAlone.lineMeshes.clear();
  wallAlone.lineInstances.clear();
  Renderer alone = test::makeRenderer();
  alone.setScene(wallAlone);
  const test::RenderedImage aoAlone = test::render(alone, camera, settings, View::Ao);
  const test::RenderedImage maskAlone = test::render(alone, camera, settings, View::Mask);
  EXPECT_EQ(ao.rgba, aoAlone.rgba);
  EXPECT_EQ(mask.rgba, maskAlone.rgba);
  // And the final image outside the lines is the wall's: only pixels near a line or point differ (by more than the
  // 2/255 that separate the lighting's tone-mapping form from the tone-mapping pass's: docs/architecture.md).
  const test::RenderedImage withLines = test::render(renderer, camera, settings, View::Final);
  const test::RenderedImage without = test::render(alone, camera, settings, View::Final);
  int differing = 0;
  for (size_t i = 0; i < withLines.rgba.size(); i += 4)
    differing += std::abs(withLines.rgba[i] - without.rgba[i]) > 2;
  EXPECT_GT(differing, 100);
  EXPECT_LT(differing, 3 * 200 + 5 * 9 + 200);  // about the red line's pixels (FXAA widens them), the points
}

// glTF-Asset-Generator's point and line files: every lit pixel lies on a projected segment (or at a point), and every
// segment is covered.
TEST(PointsAndLines, CorpusPointAndLineFilesDrawTheirPrimitives) {
  for (const char* file : {"Mesh_PrimitiveMode_00", "Mesh_PrimitiveMode_01", "Mesh_PrimitiveMode_02",
                           "Mesh_PrimitiveMode_03", "Mesh_PrimitiveMode_07", "Mesh_PrimitiveMode_10"}) {
    const Scene scene =
        loadGltfFile(test::assimpModels() + "/glTF-Asset-Generator/Mesh_PrimitiveMode/" + file + ".gltf");
    const Camera camera = Camera::fit(scene.worldBounds(), kWidth, kHeight);
    Renderer renderer = test::makeRenderer();
    renderer.setScene(scene);
    // A dark environment: the background (the sky by default) is then no brighter than the threshold, and the lines,
    // which are unlit, keep their colour.
    RenderSettings settings;
    settings.set("lighting.environment-intensity", "0");
    const test::RenderedImage color = test::render(renderer, camera, settings, View{"scene-color"});
    const LineMesh& mesh = scene.lineMeshes[0];
    const glm::mat4 world = scene.lineInstances[0].world;
    std::vector<glm::vec2> projected;
    for (const glm::vec3& p : mesh.positions) projected.push_back(windowOf(camera, glm::vec3(world * glm::vec4(p, 1))));
    auto distance = [&](glm::vec2 q) {
      float best = 1e9f;
      if (mesh.points) {
        for (const glm::vec2& p : projected) best = std::min(best, glm::length(q - p));
      } else {
        for (size_t s = 0; s + 1 < projected.size(); s += 2) {
          const glm::vec2 a = projected[s], b = projected[s + 1];
          const float t = glm::clamp(glm::dot(q - a, b - a) / std::max(1e-6f, glm::dot(b - a, b - a)), 0.0f, 1.0f);
          best = std::min(best, glm::length(q - (a + t * (b - a))));
        }
      }
      return best;
    };
    int litPixels = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        if (lit(color, x, y)) {
          ++litPixels;
          ASSERT_LT(distance({float(x) + 0.5f, float(y) + 0.5f}), 1.5f) << file << " lit at " << x << ", " << y;
        }
    EXPECT_GT(litPixels, mesh.points ? 100 : 200) << file;
    if (!mesh.points) {  // every segment covered: samples along it have a lit pixel within a pixel
      for (size_t s = 0; s + 1 < projected.size(); s += 2)
        for (float t = 0.05f; t < 1.0f; t += 0.1f) {
          const glm::vec2 q = projected[s] + t * (projected[s + 1] - projected[s]);
          bool found = false;
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              found = found || lit(color, static_cast<int>(q.x) + dx, static_cast<int>(q.y) + dy);
          EXPECT_TRUE(found) << file << " segment " << s / 2 << " at " << t;
        }
    }
  }
}

// The Draco copy of 2CylinderEngine (positions quantised to 14 bits, normals to 10) renders as the .glb does: the
// same mask but for a few edge pixels, depth codes within a few steps, normals within a few degrees.
TEST(Compression, DracoEngineRendersAsTheUncompressedOne) {
  const Scene draco = loadGltfFile(test::assimpModels() + "/draco/2CylinderEngine.gltf");
  const Scene plain = loadGltfFile(test::assimpModels() + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  const Camera camera = Camera::fit(plain.worldBounds(), 320, 240);
  Renderer a = test::makeRenderer(), b = test::makeRenderer();
  a.setScene(draco);
  b.setScene(plain);
  // In full detail: the decoder is compared, not the simplifier (gbuffer.lod's levels, made from each file's own
  // quantised vertices, collapse differently: 3 degrees of mean normal difference at the default 0.35 px).
  RenderSettings settings;
  settings.set("gbuffer.lod", "0");
  const test::RenderedImage maskA = test::render(a, camera, settings, View::Mask);
  const test::RenderedImage maskB = test::render(b, camera, settings, View::Mask);
  const test::RenderedImage depthA = test::render(a, camera, settings, View::Depth);
  const test::RenderedImage depthB = test::render(b, camera, settings, View::Depth);
  const test::RenderedImage normalsA = test::render(a, camera, settings, View::Normals);
  const test::RenderedImage normalsB = test::render(b, camera, settings, View::Normals);
  int covered = 0, maskDiffers = 0, both = 0;
  double depthError = 0.0, normalError = 0.0;
  for (int y = 0; y < maskA.height; ++y)
    for (int x = 0; x < maskA.width; ++x) {
      const bool inA = maskA.channel(x, y, 0) > 127, inB = maskB.channel(x, y, 0) > 127;
      covered += inB;
      maskDiffers += inA != inB;
      if (!(inA && inB)) continue;
      ++both;
      depthError += std::abs(depthA.channel(x, y, 0) - depthB.channel(x, y, 0)) / 255.0;
      glm::vec3 na(0.0f), nb(0.0f);
      for (int c = 0; c < 3; ++c) {
        na[c] = normalsA.channel(x, y, c) / 127.5f - 1.0f;
        nb[c] = normalsB.channel(x, y, c) / 127.5f - 1.0f;
      }
      normalError += std::acos(glm::clamp(glm::dot(glm::normalize(na), glm::normalize(nb)), -1.0f, 1.0f));
    }
  ASSERT_GT(covered, 5000);
  const double maskFraction = double(maskDiffers) / covered, meanDepth = depthError / both,
               meanNormalDegrees = glm::degrees(normalError / both);
  RecordProperty("mask_differs_permille", static_cast<int>(1000 * maskFraction));
  std::printf("Draco vs .glb: mask differs at %.2f %% of covered pixels, mean depth difference %.4f (of the view's "
              "range), mean normal difference %.2f degrees\n",
              100 * maskFraction, meanDepth, meanNormalDegrees);
  EXPECT_LT(maskFraction, 0.01);
  EXPECT_LT(meanDepth, 0.002);
  EXPECT_LT(meanNormalDegrees, 2.0);
}

// Renderer::prepare's rehearsal runs the lines' pass with a stand-in program: the pass keeps nothing of it (its
// attributes' locations are looked up each frame), and the frame is the one drawn without preparing.
TEST(PointsAndLines, APreparedFrameDrawsThemAsAnUnpreparedOne) {
  const Camera camera = test::makeCamera({0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, kWidth, kHeight);
  const RenderSettings settings;
  Renderer plain = test::makeRenderer();
  plain.setScene(wallWithLines());
  const test::RenderedImage expected = test::render(plain, camera, settings, View::Final);
  Renderer prepared = test::makeRenderer();
  prepared.setScene(wallWithLines());
  const gl::RenderTarget output("prepared output", kWidth, kHeight, GL_NEAREST, gl::RenderTarget::Depth::None, false);
  EXPECT_GT(prepared.prepare(camera, settings, OutputTarget{output.framebuffer(), kWidth, kHeight, {}}), 0u);
  const test::RenderedImage drawn = test::render(prepared, camera, settings, View::Final);
  EXPECT_EQ(prepared.programs().pending(), 0u);
  EXPECT_EQ(test::worstByteDifference(drawn, expected), 0);
}
