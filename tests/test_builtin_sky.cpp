// What the library reads instead of computing at start-up (environment/BuiltinSky.h), against computing it now: the
// baked BRDF table, the built-in sky's levels and irradiance, and the sun they were made for; and the sky's image,
// supersampled only where its radiance is not smooth, against supersampling every texel.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>

#include "effects/lighting/LightingEffect.h"
#include "environment/BuiltinSky.h"

using namespace obscura;

TEST(BuiltinSky, TheBakedDataIsWhatTheLibraryComputesNow) {
  EXPECT_EQ(environmentBrdfTable(), computeEnvironmentBrdfTable());
  EXPECT_EQ(builtinSkySun(), LightingSettings{}.directionToSun()) << "the default sun is the baked sky's";
  const EnvironmentImage image = ProceduralSky{builtinSkySun()}.image(kEnvironmentWidth, kEnvironmentHeight);
  const PreparedEnvironment now = prepareEnvironment(image, EnvironmentFiltering::Measured);
  for (EnvironmentFiltering filtering : {EnvironmentFiltering::Measured, EnvironmentFiltering::ByHand}) {
    SCOPED_TRACE(static_cast<int>(filtering));
    const PreparedEnvironment baked = builtinSky(filtering);
    for (int level = 0; level < kEnvironmentLevels; ++level)
      EXPECT_EQ(baked.specular.encodedLevel(level), now.specular.encodedLevel(level)) << "level " << level;
    for (size_t i = 0; i < 9; ++i) EXPECT_EQ(baked.irradiance.coefficients[i], now.irradiance.coefficients[i]) << i;
    if (filtering == EnvironmentFiltering::ByHand) {
      EXPECT_EQ(baked.specular.filteredFrom(), kEnvironmentLevels);
      continue;
    }
    // The filtered (RGBM) levels are encoded from the RGB9E5 ones, not from the exact levels: their bytes may differ
    // by a few levels (one RGBM multiplier shared by three channels), and what the shader and its mirror read from
    // them stays within 1 % of the brightest channel (0.4 % measured) (or of 1 % of the level's brightest, where dark).
    ASSERT_EQ(baked.specular.filteredFrom(), now.specular.filteredFrom());
    EXPECT_NEAR(baked.specular.filteredScale(), now.specular.filteredScale(), 1e-3f * now.specular.filteredScale());
    double worst = 0.0;
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 32; ++i) {
        const glm::vec3 direction =
            equirectDirection({(static_cast<float>(i) + 0.5f) / 32.0f, (static_cast<float>(j) + 0.5f) / 16.0f});
        for (float roughness : {0.0f, 0.3f, 0.5f, 0.7f, 0.9f, 1.0f}) {
          const glm::vec3 x = baked.specular.sample(direction, roughness);
          const glm::vec3 y = now.specular.sample(direction, roughness);
          const float reference = std::max({y.r, y.g, y.b, 0.01f * baked.specular.filteredScale()});
          for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(x[c] - y[c]) / reference));
        }
      }
    std::printf("the baked sky against the sky prefiltered now, filtering %d: worst relative difference %.5f\n",
                static_cast<int>(filtering), worst);
    EXPECT_LT(worst, 0.01);
  }
}

TEST(BuiltinSky, TheImageIsSupersampledWhereItMustBe) {
  const ProceduralSky sky{builtinSkySun()};
  const EnvironmentImage image = sky.image(kEnvironmentWidth, kEnvironmentHeight);
  double worst = 0.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      glm::vec3 sum(0.0f);
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
          sum += sky.radiance(equirectDirection({static_cast<float>((x + (i + 0.5) / 4.0) / image.width),
                                                 static_cast<float>((y + (j + 0.5) / 4.0) / image.height)}));
      const glm::vec3 mean = sum / 16.0f;
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(double(image.at(x, y)[c]) - mean[c]) / std::max(double(mean[c]), 1e-3));
    }
  std::printf("the sky's image against 4 x 4 samples in every texel: worst relative difference %.5f\n", worst);
  EXPECT_LT(worst, 1e-3);
}
