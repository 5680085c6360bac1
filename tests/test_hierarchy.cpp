// The depth hierarchy (SAO paper sec. 3.3 under WebGL 1 rules), half-resolution AO and the quality presets.
#include <gtest/gtest.h>

#include <cstdio>

#include "TestSupport.h"
#include "effects/ao/AoUpsamplePass.h"
#include "effects/ao/DepthHierarchyPass.h"
#include "effects/ao/SaoKernel.h"
#include "encoding/LinearDepthPacking.h"
#include "encoding/NormalEncoding.h"
#include "scene/BuiltinScene.h"

using namespace obscura;
namespace ldp = obscura::LinearDepthPacking;

namespace {

struct Difference {
  double mean = 0.0;
  int max = 0;
};

Difference aoDifference(const test::RenderedImage& a, const test::RenderedImage& b) {
  Difference d;
  for (size_t i = 0; i < a.rgba.size(); i += 4) {
    const int diff = std::abs(a.rgba[i] - b.rgba[i]);
    d.mean += diff;
    d.max = std::max(d.max, diff);
  }
  d.mean /= static_cast<double>(a.rgba.size() / 4);
  return d;
}

}  // namespace

// The storages this context can use (the mip chain needs two extensions).
std::vector<DepthHierarchyPass::Storage> availableStorages() {
  std::vector<DepthHierarchyPass::Storage> storages = {DepthHierarchyPass::Storage::SeparateTextures,
                                                       DepthHierarchyPass::Storage::Atlas};
  if (DepthHierarchyPass::storageFor(test::context().caps()) == DepthHierarchyPass::Storage::MipChain)
    storages.push_back(DepthHierarchyPass::Storage::MipChain);
  return storages;
}

TEST(DepthHierarchy, EveryLevelHoldsTheRotatedGridPickAndItsPlaceInEveryStorage) {
  // An odd size, so the floor()ed level sizes and the edge clamps are exercised.
  const Camera camera = builtinSceneCamera(203, 117);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  test::render(renderer, camera, AoSettings{}, View::Depth, test::retaining({"gbuffer"}));
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();  // rows top to bottom
  const glm::ivec2 size(camera.width, camera.height);
  auto gbufferTexel = [&](glm::ivec2 p) { return &gbuffer[(static_cast<size_t>(size.y - 1 - p.y) * size.x + p.x) * 4]; };

  const EffectResources& resources = test::effectResources();
  for (DepthHierarchyPass::Storage storage : availableStorages()) {
    DepthHierarchyPass hierarchy(resources.triangle, test::context().caps(), storage, resources);
    hierarchy.resize(size.x, size.y);
    ASSERT_EQ(hierarchy.storage(), storage);
    hierarchy.render(renderer.retained("gbuffer").color());
    // The atlas also holds level 0: the G-buffer's depth key with no offset.
    const int firstLevel = storage == DepthHierarchyPass::Storage::Atlas ? 0 : 1;
    for (int level = firstLevel; level <= SaoKernel::kMaxMipLevel; ++level) {
      const glm::ivec2 levelSize = SaoKernel::hierarchyLevelSize(size, level);
      const std::vector<std::uint8_t> texels = hierarchy.readLevel(level);
      ASSERT_EQ(texels.size(), static_cast<size_t>(levelSize.x * levelSize.y) * 4);
      int mismatches = 0;
      for (int y = 0; y < levelSize.y; ++y) {
        for (int x = 0; x < levelSize.x; ++x) {
          const std::uint8_t* t = &texels[(static_cast<size_t>(levelSize.y - 1 - y) * levelSize.x + x) * 4];
          const glm::ivec2 source = SaoKernel::hierarchySourcePixel({x, y}, level, size);
          const glm::ivec2 place = source - glm::ivec2(x, y) * (1 << level);
          const std::uint8_t* g = gbufferTexel(source);
          // A real depth of the block (bit-exact, never averaged), and where in the block it came from.
          if (t[2] != g[2] || t[3] != g[3] || t[0] != place.x || t[1] != place.y) ++mismatches;
          ASSERT_GE(place.x, 0);
          ASSERT_LT(place.x, 1 << level);
        }
      }
      EXPECT_EQ(mismatches, 0) << DepthHierarchyPass::storageName(storage) << " level " << level;
    }
  }
}

TEST(DepthHierarchy, ChangesTheBlurredAoLittle) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));  // the room the bounds below were measured on
  const Camera camera = builtinSceneCamera(320, 180);
  // Bounds (of 255) about 1.5 to 2 times what llvmpipe measured. At 0.5 m nearly every tap is within 16 px and reads
  // level 0, so the figure is close to nothing; the far radii are where the levels are read. Measured: SAO (hard cut
  // at r) 0.010, 0.68, 0.92; GTAO 0.005, 0.98, 1.33: it keeps each side's highest horizon, so a far tap that reads
  // its block's depth instead of its own moves that pixel's estimate more than SAO's mean of taps does.
  struct Case {
    AoEstimator estimator;
    float radius;
    double bound;
  };
  const Case cases[] = {{AoEstimator::Sao, 0.5f, 0.02}, {AoEstimator::Sao, 2.0f, 1.2},
                        {AoEstimator::Sao, 4.0f, 1.6},  {AoEstimator::Gtao, 0.5f, 0.01},
                        {AoEstimator::Gtao, 2.0f, 1.8}, {AoEstimator::Gtao, 4.0f, 2.4}};
  for (const Case& c : cases) {
    AoSettings with, without;
    with.estimator = without.estimator = c.estimator;
    with.depthHierarchy = DepthHierarchy::On;
    without.depthHierarchy = DepthHierarchy::Off;
    with.radius = without.radius = c.radius;
    const Difference d =
        aoDifference(test::render(renderer, camera, with, View::Ao), test::render(renderer, camera, without, View::Ao));
    RecordProperty(
        std::string(estimatorName(c.estimator)) + "_mean_at_" + std::to_string(static_cast<int>(c.radius * 10)),
        std::to_string(d.mean));
    // Far taps read one real depth per block instead of their own texel: the estimate barely moves.
    EXPECT_LE(d.mean, c.bound) << estimatorName(c.estimator) << ", radius " << c.radius << ": mean difference "
                               << d.mean << "/255, max " << d.max;
  }
}

TEST(DepthHierarchy, EveryStorageGivesTheSameAo) {
  const Camera camera = builtinSceneCamera(320, 180);
  AoSettings settings;
  settings.depthHierarchy = DepthHierarchy::On;
  settings.radius = 3.0f;  // far taps reach levels 3 to 5
  std::vector<std::pair<DepthHierarchyPass::Storage, test::RenderedImage>> images;
  for (DepthHierarchyPass::Storage storage : availableStorages()) {
    RendererOptions options;
    options.hierarchyStorage = storage;
    Renderer renderer = test::makeRenderer(options);
    ASSERT_EQ(renderer.hierarchyStorage(), storage);
    renderer.setScene(makeBuiltinScene());
    images.emplace_back(storage, test::render(renderer, camera, settings, View::AoRaw));
  }
  // The same bytes read through a different storage: the AO agrees to rounding.
  for (size_t i = 1; i < images.size(); ++i) {
    const Difference d = aoDifference(images[0].second, images[i].second);
    EXPECT_LE(d.max, 1) << DepthHierarchyPass::storageName(images[i].first) << " vs "
                        << DepthHierarchyPass::storageName(images[0].first) << ": mean " << d.mean;
  }
  if (images.size() < 3)
    std::printf("note: this context lacks EXT_shader_texture_lod or OES_fbo_render_mipmap; the browser suite "
                "compares the mip-chain path on WebGL 1\n");
}

TEST(DepthHierarchy, TheAtlasFallsBackToSeparateTexturesWhenTooWide) {
  gl::GlCaps caps = test::context().caps();
  caps.maxTextureSize = caps.maxRenderbufferSize = caps.maxViewportWidth = caps.maxViewportHeight = 512;
  const EffectResources& resources = test::effectResources();
  DepthHierarchyPass hierarchy(resources.triangle, caps, DepthHierarchyPass::Storage::Atlas, resources);
  hierarchy.resize(340, 200);  // 340 + 170 fits in 512
  EXPECT_EQ(hierarchy.storage(), DepthHierarchyPass::Storage::Atlas);
  hierarchy.resize(400, 200);  // 400 + 200 does not
  EXPECT_EQ(hierarchy.storage(), DepthHierarchyPass::Storage::SeparateTextures);
}

TEST(HalfResolution, UpsamplingDoesNotBleedAcrossADepthStep) {
  test::context();
  constexpr int kWidth = 64, kHeight = 48;
  const Camera camera = test::makeCamera({0, 0, 0}, {0, 0, -1}, kWidth, kHeight, 0.1f, 50.0f);
  const glm::ivec2 full(kWidth, kHeight), half = SaoKernel::hierarchyLevelSize(full, 1);
  // Full resolution: a surface 5 m away left of column 33 (odd, so the step falls inside a 2x2 block), 6 m right.
  auto distanceAt = [](int x) { return x < 33 ? 5.0f : 6.0f; };
  auto codeAt = [&](float distance) { return ldp::codeFromDepth((distance - camera.near) / (camera.far - camera.near)); };
  std::vector<std::uint8_t> gbuffer(kWidth * kHeight * 4), ao(static_cast<size_t>(half.x * half.y) * 4);
  const auto normal = encodeNormal(glm::vec3(0, 0, 1));
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const auto depth = ldp::bytesFromCode(codeAt(distanceAt(x)));
      std::uint8_t* g = &gbuffer[(static_cast<size_t>(y) * kWidth + x) * 4];
      g[0] = normal[0];
      g[1] = normal[1];
      g[2] = depth[0];
      g[3] = depth[1];
    }
  // Half resolution: each AO pixel carries the AO and depth of the G-buffer pixel it stands for; the near surface
  // is dark (AO 0), the far one unoccluded (AO 1).
  for (int y = 0; y < half.y; ++y)
    for (int x = 0; x < half.x; ++x) {
      const glm::ivec2 source = SaoKernel::aoCentrePixel({x, y}, 2, full);
      const float distance = distanceAt(source.x);
      const auto depth = ldp::bytesFromCode(codeAt(distance));
      std::uint8_t* a = &ao[(static_cast<size_t>(y) * half.x + x) * 4];
      a[0] = distance < 5.5f ? 0 : 255;
      a[1] = depth[0];
      a[2] = depth[1];
      a[3] = 255;
    }
  const gl::Texture2D gbufferTexture(kWidth, kHeight, GL_NEAREST, gbuffer.data());
  const gl::Texture2D aoTexture(half.x, half.y, GL_NEAREST, ao.data());
  AoUpsamplePass upsample(test::effectResources());
  const gl::RenderTarget target("upsampled", kWidth, kHeight, GL_NEAREST, gl::RenderTarget::Depth::None, false);
  target.bindForDrawing();
  upsample.render(aoTexture, gbufferTexture, FrameCamera::from(camera, kWidth, kHeight), AoSettings{});
  const std::vector<std::uint8_t> out = target.readRgba();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t* o = &out[(static_cast<size_t>(kHeight - 1 - y) * kWidth + x) * 4];
      ASSERT_EQ(o[0], distanceAt(x) < 5.5f ? 0 : 255) << "pixel " << x << "," << y;
      // The output keeps each pixel's own full-resolution depth key.
      const auto depth = ldp::bytesFromCode(codeAt(distanceAt(x)));
      ASSERT_EQ(o[1], depth[0]);
      ASSERT_EQ(o[2], depth[1]);
    }
}

TEST(HalfResolution, StaysCloseToFullResolution) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));  // the room the bound below was measured on
  const Camera camera = builtinSceneCamera(640, 360);
  AoSettings full, half;
  half.halfResolution = true;
  const Difference d = aoDifference(test::render(renderer, camera, full, View::Ao),
                                    test::render(renderer, camera, half, View::Ao));
  // Measured 2.9/255 on llvmpipe (thin creases such as the skirting ledge are where the two differ most).
  EXPECT_LE(d.mean, 3.5) << "mean difference " << d.mean << "/255, max " << d.max;
}

TEST(QualityPresets, EveryPresetRendersEveryView) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(160, 90);
  AoSettings reference;
  reference.applyPreset(QualityPreset::Ultra);
  const test::RenderedImage ultra = test::render(renderer, camera, reference, View::Ao);
  for (const PresetInfo& preset : qualityPresets()) {
    AoSettings settings;
    settings.applyPreset(preset.preset);
    for (const View& view : {View::Final, View::Ao, View::AoRaw})
      EXPECT_NO_THROW(test::render(renderer, camera, settings, view)) << preset.name;
    // Every preset estimates the same AO, with less noise as quality rises.
    const Difference d = aoDifference(test::render(renderer, camera, settings, View::Ao), ultra);
    EXPECT_LE(d.mean, 6.0) << preset.name << " vs ultra: mean " << d.mean;
  }
}
