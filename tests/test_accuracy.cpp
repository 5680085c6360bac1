// Regression guard: SAO's default AO of the built-in scene against the ray-traced reference, traced here at a small
// size. The bounds are the figures reached when the defaults were last tuned (tools/tune-defaults.sh, measured by
// this test at 320x180) plus headroom; a change to the AO pipeline that makes the defaults clearly worse fails here.
// After re-running the tuning, update the figures below if they moved (docs/accuracy.md has the full tables).
#include <gtest/gtest.h>

#include "TestSupport.h"
#include "metrics/AoMetrics.h"
#include "reference/AoReferenceTracer.h"
#include "scene/BuiltinScene.h"

using namespace obscura;

namespace {

// Reached with the tuned defaults (preset medium, r = 1 m) on llvmpipe at 320x180, 256 rays per pixel.
constexpr double kReachedMae = 0.0386;
constexpr double kReachedHaloMae = 0.0543;
constexpr double kReachedSsim = 0.878;
constexpr double kReachedPearson = 0.811;
// Headroom for other rasterisers and small pipeline changes: a tenth of the error, plus half a grey level.
constexpr double kHeadroom = 1.1;
constexpr double kSlack = 0.5 / 255.0;

struct Measured {
  AoComparison tuned, paper;
};

Measured measureBuiltinScene() {
  const Scene scene = makeBuiltinScene();
  const Camera camera = builtinSceneCamera(320, 180);
  const AoSettings defaults;
  const ReferenceFrame reference = AoReferenceTracer(scene).trace(camera, {defaults.radius, 256, 2});
  const GreyImage truth = GreyImage::fromRed(reference.aoImage());
  const std::vector<std::uint8_t> band = discontinuityBand(GreyImage::fromRed(reference.depthImage()), {});

  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  auto measure = [&](const AoSettings& settings) {
    const test::RenderedImage ao = test::render(renderer, camera, settings, View::Ao);
    return compareAo(truth, GreyImage::fromRed(Image{ao.width, ao.height, ao.rgba}), reference.mask, band);
  };
  AoSettings paper = defaults;
  paper.intensity = kPaperEstimatorParameters.intensity;
  paper.bias = kPaperEstimatorParameters.bias;
  paper.contrast = kPaperEstimatorParameters.contrast;
  return {measure(defaults), measure(paper)};
}

}  // namespace

TEST(Accuracy, BuiltinSceneDefaultsStayCloseToTheReference) {
  const Measured m = measureBuiltinScene();
  RecordProperty("mae", std::to_string(m.tuned.mae));
  RecordProperty("halo_mae", std::to_string(m.tuned.haloMae));
  RecordProperty("ssim", std::to_string(m.tuned.ssim));
  RecordProperty("pearson", std::to_string(m.tuned.pearson));
  std::printf("tuned: MAE %.4f halo %.4f SSIM %.4f Pearson %.4f | paper values: MAE %.4f halo %.4f SSIM %.4f "
              "Pearson %.4f\n",
              m.tuned.mae, m.tuned.haloMae, m.tuned.ssim, m.tuned.pearson, m.paper.mae, m.paper.haloMae, m.paper.ssim,
              m.paper.pearson);
  EXPECT_GT(m.tuned.pixels, 320u * 180u / 2);
  EXPECT_GT(m.tuned.haloPixels, m.tuned.pixels / 50);
  EXPECT_LE(m.tuned.mae, kReachedMae * kHeadroom + kSlack);
  EXPECT_LE(m.tuned.haloMae, kReachedHaloMae * kHeadroom + kSlack);
  EXPECT_GE(m.tuned.ssim, 1.0 - (1.0 - kReachedSsim) * kHeadroom);
  EXPECT_GE(m.tuned.pearson, 1.0 - (1.0 - kReachedPearson) * kHeadroom);
  // Tuning is worth having: the fitted defaults beat the SAO paper's values on this scene.
  EXPECT_LT(m.tuned.mae, m.paper.mae);
}
