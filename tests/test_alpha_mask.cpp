// alphaMode MASK in every geometry pass: a quad standing on a floor, its base-colour texture transparent on the left
// half (test::cutOutQuadOnAFloor). The cut-out half must be missing from the G-buffer (mask view), from the lit image
// and from the AO it would cast on the floor; with alphaMode OPAQUE the same quad is whole. (The ray-traced reference
// is held to the same in test_reference.cpp.)
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "frame/FrameContext.h"

using namespace obscura;

namespace {

constexpr int kWidth = 200, kHeight = 150;

struct Probe {
  int x, y;
};

// The image pixel (row 0 at the top) that shows world point `p`.
Probe pixelOf(const Camera& camera, const glm::vec3& p) {
  const FrameCamera frame = FrameCamera::from(camera, camera.width, camera.height);
  const glm::vec3 window =
      glm::project(p, frame.view, frame.projection, glm::vec4(0, 0, camera.width, camera.height));
  const Probe probe{static_cast<int>(window.x), camera.height - 1 - static_cast<int>(window.y)};
  EXPECT_TRUE(probe.x >= 1 && probe.y >= 1 && probe.x < camera.width - 1 && probe.y < camera.height - 1)
      << "probe (" << p.x << ", " << p.y << ", " << p.z << ") is not in view";
  return probe;
}

struct Views {
  test::RenderedImage mask, ao, final;
};

Views renderViews(AlphaMode mode, const Camera& camera) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(test::cutOutQuadOnAFloor(mode));
  // The uniform environment: the background is one colour in every direction, so the hole can be compared with the
  // background anywhere (the sky's varies with the direction).
  RenderSettings settings = AoSettings{};
  settings.set("lighting.environment", "uniform");
  return {test::render(renderer, camera, settings, View::Mask), test::render(renderer, camera, settings, View::Ao),
          test::render(renderer, camera, settings, View::Final)};
}

float meanAo(const test::RenderedImage& ao, Probe centre) {
  float sum = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) sum += ao.red(centre.x + dx, centre.y + dy);
  return sum / 9.0f;
}

}  // namespace

TEST(AlphaMask, CutOutTexelsAreMissingFromEveryPass) {
  const Camera camera = test::makeCamera({0.0f, 1.2f, 4.0f}, {0.0f, 0.6f, 0.0f}, kWidth, kHeight);
  // 1.5 m either side of the middle: more than the 1 m AO radius from the other half.
  const Probe cutOut = pixelOf(camera, {-1.5f, 1.5f, 0.0f}), kept = pixelOf(camera, {1.5f, 1.5f, 0.0f});
  // On the floor just in front of the quad's foot: the contact shadow of the kept half, open floor under the cut half.
  const Probe floorUnderCut = pixelOf(camera, {-1.5f, 0.0f, 0.1f});
  const Probe floorUnderKept = pixelOf(camera, {1.5f, 0.0f, 0.1f});
  const Probe sky = {kWidth / 2, 2};

  const Views masked = renderViews(AlphaMode::Mask, camera);
  const Views opaque = renderViews(AlphaMode::Opaque, camera);

  // G-buffer: the ray through the cut-out half continues over the floor's horizon into the background.
  EXPECT_EQ(masked.mask.channel(cutOut.x, cutOut.y, 0), 0) << "the cut-out half was drawn into the G-buffer";
  EXPECT_EQ(masked.mask.channel(kept.x, kept.y, 0), 255);
  EXPECT_EQ(opaque.mask.channel(cutOut.x, cutOut.y, 0), 255) << "alphaMode OPAQUE must ignore the texture's alpha";
  ASSERT_EQ(masked.mask.channel(sky.x, sky.y, 0), 0) << "the probe for the background sees geometry";

  // Lighting pass: the background colour shows through the hole; the kept half is drawn.
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(masked.final.channel(cutOut.x, cutOut.y, c), masked.final.channel(sky.x, sky.y, c)) << "channel " << c;
  EXPECT_NE(masked.final.channel(kept.x, kept.y, 0), masked.final.channel(sky.x, sky.y, 0));

  // AO: the floor at the foot of the cut-out half is as open as the floor far away; the kept half still darkens its
  // foot, and with the whole quad opaque both feet are dark.
  const float openFloor = meanAo(masked.ao, pixelOf(camera, {0.0f, 0.0f, 1.6f}));  // 1.6 m from everything
  EXPECT_GE(openFloor, 0.95f);
  EXPECT_GE(meanAo(masked.ao, floorUnderCut), openFloor - 0.03f) << "occlusion from a cut-out surface";
  EXPECT_LT(meanAo(masked.ao, floorUnderKept), openFloor - 0.1f) << "no contact shadow at the kept half";
  EXPECT_LT(meanAo(opaque.ao, floorUnderCut), openFloor - 0.1f) << "no contact shadow under the opaque quad";
}
