// What the library reads instead of computing at start-up (environment/BuiltinSky.h), against computing it now: the
// baked BRDF table, the built-in sky's levels and irradiance, and the sun they were made for; and the sky's image,
// supersampled only where its radiance is not smooth, against supersampling every texel.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "effects/lighting/LightingEffect.h"
#include "environment/BuiltinSky.h"

using namespace obscura;

TEST(BuiltinSky, TheBakedDataIsWhatTheLibraryComputesNow) {
  EXPECT_EQ(environmentBrdfTable(), computeEnvironmentBrdfTable());
  EXPECT_EQ(builtinSkySun(), LightingSettings{}.directionToSun()) << "the default sun is the baked sky's";
  const PreparedEnvironment& baked = builtinSky();
  const EnvironmentImage image = ProceduralSky{builtinSkySun()}.image(kEnvironmentWidth, kEnvironmentHeight);
  const PreparedEnvironment now = prepareEnvironment(image);
  for (int level = 0; level < kEnvironmentLevels; ++level)
    EXPECT_EQ(baked.specular.encodedLevel(level), now.specular.encodedLevel(level)) << "level " << level;
  for (size_t i = 0; i < 9; ++i) EXPECT_EQ(baked.irradiance.coefficients[i], now.irradiance.coefficients[i]) << i;
  // The texture and the CPU mirror read the same values either way.
  for (const glm::vec3& direction : {glm::vec3(0.0f, 1.0f, 0.0f), glm::normalize(glm::vec3(0.3f, 0.2f, -0.9f)),
                                     builtinSkySun()})
    for (float roughness : {0.0f, 0.3f, 0.9f})
      EXPECT_EQ(baked.specular.sample(direction, roughness), now.specular.sample(direction, roughness));
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
