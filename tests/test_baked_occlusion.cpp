// Where the material's baked occlusion meets the screen-space AO (docs/pbr.md, "Where the AO goes"): measured on a
// baked-AO sample against the ray-traced reference. The sample is an asset as artists bake one: a plinth (a floor
// tile) with a box on it, the plinth's occlusion texture baked with the box (by the reference tracer itself, at the
// AO radius), then placed in a scene beside a wall the bake never saw. On the floor's pixels the true ambient
// visibility (the reference traced through the whole scene) is compared with the screen-space AO alone, the baked
// texture alone, their product and their minimum: the rule the lighting pass uses (lighting.frag) must be the closer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "TestSupport.h"
#include "base/Text.h"
#include "frame/FrameContext.h"
#include "reference/AoReferenceTracer.h"
#include "scene/GltfLoader.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

constexpr float kRadius = 1.0f;
constexpr int kBakeSize = 128;

// The floor tile: 6 x 6 m at y = 0, u along +x, v along -z (addQuad's order).
glm::vec2 floorUv(const glm::vec3& p) { return {(p.x + 3.0f) / 6.0f, (3.0f - p.z) / 6.0f}; }
glm::vec3 floorPoint(const glm::vec2& uv) { return {uv.x * 6.0f - 3.0f, 0.0f, 3.0f - uv.y * 6.0f}; }

Scene asset() {
  Scene scene;
  Mesh floor;
  addQuad(floor, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, {-3, 0, -3});
  scene.meshes.push_back(floor);
  scene.meshes.push_back(makeBox({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}));
  for (int m = 0; m < 2; ++m) scene.instances.push_back({m, glm::mat4(1.0f)});
  return scene;
}

// The bake: the tile's ambient visibility with the box, per texel centre (rows in v).
std::vector<float> bake(const Scene& tile) {
  const AoReferenceTracer tracer(tile);
  std::vector<float> texels(static_cast<size_t>(kBakeSize * kBakeSize));
  for (int j = 0; j < kBakeSize; ++j)
    for (int i = 0; i < kBakeSize; ++i) {
      const glm::vec2 uv((static_cast<float>(i) + 0.5f) / kBakeSize, (static_cast<float>(j) + 0.5f) / kBakeSize);
      texels[static_cast<size_t>(j * kBakeSize + i)] =
          tracer.visibilityAt(floorPoint(uv), {0, 1, 0}, {kRadius, 256, 2}, static_cast<std::uint32_t>(i),
                              static_cast<std::uint32_t>(j));
    }
  return texels;
}

// The baked value the lighting pass reads at uv: the texture sampled bilinearly, clamped (as an 8-bit texel).
float sampleBaked(const std::vector<float>& texels, const glm::vec2& uv) {
  auto texel = [&](int i, int j) {
    i = std::clamp(i, 0, kBakeSize - 1);
    j = std::clamp(j, 0, kBakeSize - 1);
    return std::round(texels[static_cast<size_t>(j * kBakeSize + i)] * 255.0f) / 255.0f;
  };
  const float x = uv.x * kBakeSize - 0.5f, y = uv.y * kBakeSize - 0.5f;
  const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y));
  const float fx = x - static_cast<float>(i), fy = y - static_cast<float>(j);
  return (texel(i, j) * (1 - fx) + texel(i + 1, j) * fx) * (1 - fy) +
         (texel(i, j + 1) * (1 - fx) + texel(i + 1, j + 1) * fx) * fy;
}

}  // namespace

TEST(BakedOcclusion, TheLightingPassCombinesItWithTheAoByTheRuleThatMatchesTheReference) {
  const Scene tile = asset();
  const std::vector<float> baked = bake(tile);

  // The scene: the asset, and a wall 0.6 m behind the box that the bake never saw.
  Scene scene = tile;
  Image image;
  image.width = image.height = kBakeSize;
  for (float v : baked) {
    const auto r = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    image.rgba.insert(image.rgba.end(), {r, r, r, 255});
  }
  scene.images.push_back(image);
  scene.textures.push_back({0, {0x2601, 0x2601, 0x812F, 0x812F}});  // LINEAR, clamped
  Material floorMaterial;
  floorMaterial.occlusionTexture = 0;
  scene.materials.push_back(floorMaterial);
  scene.meshes[0].material = 0;
  Mesh wall;
  addQuad(wall, {-3, 0, -1.1f}, {3, 0, -1.1f}, {3, 2, -1.1f}, {-3, 2, -1.1f});
  scene.meshes.push_back(wall);
  scene.instances.push_back({2, glm::mat4(1.0f)});

  const int width = 320, height = 180;
  const Camera camera = test::makeCamera({2.0f, 1.8f, 2.6f}, {-0.2f, 0.2f, -0.6f}, width, height, 0.1f, 50.0f);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  RenderSettings settings;
  settings.set("ao.radius", "1");
  test::render(renderer, camera, settings, View::Final, test::retaining({"ao", "gbuffer"}));
  const std::vector<std::uint8_t> ao = renderer.retained("ao").readRgba();
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  const ReferenceFrame reference = AoReferenceTracer(scene).trace(camera, {kRadius, 256, 2});
  const FrameCamera frame = FrameCamera::from(camera, width, height);
  const glm::mat4 cameraToWorld = glm::inverse(frame.view);

  double errors[4] = {0, 0, 0, 0};  // the AO alone, the bake alone, the product, the minimum
  int floorPixels = 0, occludedByBoth = 0;
  for (int row = 0; row < height; ++row)
    for (int x = 0; x < width; ++x) {
      const size_t i = static_cast<size_t>(row) * width + x;
      const int code = gbuffer[4 * i + 2] * 256 + gbuffer[4 * i + 3];
      if (code == 65535) continue;
      const glm::vec2 uv((static_cast<float>(x) + 0.5f) / width, 1.0f - (static_cast<float>(row) + 0.5f) / height);
      const glm::vec3 p = glm::vec3(cameraToWorld * glm::vec4(frame.reconstruction.viewPosition(uv, static_cast<float>(code) / 65535.0f), 1));
      if (std::abs(p.y) > 0.01f || std::abs(p.x) > 2.9f || p.z < -1.05f || p.z > 2.9f) continue;  // the floor only
      if (std::max(std::abs(p.x), std::abs(p.z)) < 0.55f) continue;
      const double ssao = ao[4 * i] / 255.0, tex = sampleBaked(baked, floorUv(p));
      const double truth = reference.visibility[i];
      const double combined[4] = {ssao, tex, ssao * tex, std::min(ssao, tex)};
      for (int k = 0; k < 4; ++k) errors[k] += std::abs(combined[k] - truth);
      ++floorPixels;
      occludedByBoth += ssao < 0.9 && tex < 0.9;
    }
  ASSERT_GT(floorPixels, width * height / 5);
  for (double& e : errors) e /= floorPixels;
  std::printf("baked occlusion with the screen-space AO, %d floor pixels (%d darkened by both), mean absolute error "
              "against the reference: AO alone %.4f, bake alone %.4f, product %.4f, minimum %.4f\n",
              floorPixels, occludedByBoth, errors[0], errors[1], errors[2], errors[3]);
  EXPECT_GT(occludedByBoth, floorPixels / 20) << "the sample must have pixels both see occluded";
  // lighting.frag combines them by the minimum: it must be the closer of the two rules, and closer than either
  // estimate alone.
  EXPECT_LT(errors[3], errors[2]);
  EXPECT_LT(errors[3], errors[0]);
  EXPECT_LT(errors[3], errors[1]);
}

// The G-buffer's normal: the interpolated vertex normal, or the shading normal (the normal texture applied;
// RendererOptions::gbufferShadingNormals). On the metallic-roughness sample, whose floor tiles are normal-mapped, the
// AO with each is compared with the ray-traced reference (which integrates around the true, flat surface): the
// default must be the closer.
TEST(BakedOcclusion, TheGBufferNormalIsTheOneWhoseAoMatchesTheReference) {
  const Scene scene = loadGltfFile(test::sourceDir() + "/assets/scenes/pbr-samples.glb");
  const int width = 320, height = 180;
  const Camera camera = test::makeCamera({0.0f, 1.7f, 4.0f}, {0.0f, 0.55f, 0.0f}, width, height);
  const float radius = 0.5f;
  const ReferenceFrame reference = AoReferenceTracer(scene).trace(camera, {radius, 256, 2});
  auto meanError = [&](bool shadingNormals, double* floorError) {
    RendererOptions options;
    options.gbufferShadingNormals = shadingNormals;
    Renderer renderer = test::makeRenderer(options);
    renderer.setScene(scene);
    RenderSettings settings;
    settings.set("ao.radius", formatShortest(radius));
    test::render(renderer, camera, settings, View::Final, test::retaining({"ao", "gbuffer"}));
    const std::vector<std::uint8_t> ao = renderer.retained("ao").readRgba();
    const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
    const FrameCamera frame = FrameCamera::from(camera, width, height);
    const glm::mat4 cameraToWorld = glm::inverse(frame.view);
    double sum = 0.0, floorSum = 0.0;
    int count = 0, floorCount = 0;
    for (size_t i = 0; i < reference.visibility.size(); ++i) {
      if (!reference.mask[i]) continue;
      const double error = std::abs(ao[4 * i] / 255.0 - reference.visibility[i]);
      sum += error;
      ++count;
      const int code = gbuffer[4 * i + 2] * 256 + gbuffer[4 * i + 3];
      const int x = static_cast<int>(i % width), row = static_cast<int>(i / width);
      const glm::vec2 uv((static_cast<float>(x) + 0.5f) / width, 1.0f - (static_cast<float>(row) + 0.5f) / height);
      const glm::vec3 p(cameraToWorld * glm::vec4(frame.reconstruction.viewPosition(uv, static_cast<float>(code) / 65535.0f), 1.0f));
      if (std::abs(p.y) < 0.01f) {  // the normal-mapped floor
        floorSum += error;
        ++floorCount;
      }
    }
    *floorError = floorSum / std::max(floorCount, 1);
    return sum / std::max(count, 1);
  };
  double geometricFloor = 0.0, shadingFloor = 0.0;
  const double geometric = meanError(false, &geometricFloor), shading = meanError(true, &shadingFloor);
  std::printf("AO against the reference on the PBR sample, mean absolute error: geometric G-buffer normal %.4f "
              "(floor %.4f), shading normal %.4f (floor %.4f)\n",
              geometric, geometricFloor, shading, shadingFloor);
  EXPECT_NE(geometricFloor, shadingFloor) << "the normal texture must reach the G-buffer when asked";
  EXPECT_LT(RendererOptions{}.gbufferShadingNormals ? shading : geometric,
            RendererOptions{}.gbufferShadingNormals ? geometric : shading);
}
