// Depth of field's arithmetic on the CPU (effects/dof/DepthOfFieldEffect.h, encoding/CocPacking.h): the CoC's codes,
// the thin lens against Samuelcik's formula and against the pinhole lens its reference samples, the lens points, and
// the parameters. tests/test_dof.cpp holds the GPU to the same mirrors.
#include <gtest/gtest.h>

#include <cmath>

#include "effects/dof/DepthOfFieldEffect.h"
#include "encoding/CocPacking.h"
#include "encoding/ToneMapping.h"
#include "renderer/AccumulationReference.h"
#include "renderer/RenderSettings.h"
#include "scene/Camera.h"

namespace obscura {
namespace {

namespace cp = CocPacking;

TEST(CocPacking, ZeroIsExactAndEveryCocRoundTripsWithinHalfAStep) {
  const float range = 32.0f;
  EXPECT_EQ(cp::codeFromCoc(0.0f, range), 32768);
  EXPECT_EQ(cp::cocFromCode(32768, range), 0.0f);
  EXPECT_EQ(cp::halfCodeFromCoc(0.0f, range), 128);
  EXPECT_EQ(cp::cocFromHalfCode(128, range), 0.0f);
  double worst16 = 0.0, worst8 = 0.0;
  for (int i = -100000; i <= 100000; ++i) {
    const float c = range * static_cast<float>(i) / 100000.0f;
    const auto bytes = cp::bytesFromCoc(c, range);
    worst16 = std::max(worst16, static_cast<double>(std::abs(cp::cocFromBytes(bytes.data(), range) - c)));
    worst8 = std::max(worst8, static_cast<double>(std::abs(cp::cocFromHalfCode(cp::halfCodeFromCoc(c, range),
                                                                                   range) - c)));
    // Signs survive: a pixel in front of the focus never decodes as behind it.
    if (c < 0.0f) {
      EXPECT_LE(cp::cocFromBytes(bytes.data(), range), 0.0f);
    }
    if (c > 0.0f) {
      EXPECT_GE(cp::cocFromBytes(bytes.data(), range), 0.0f);
    }
  }
  std::printf("[ coc packing ] range %.0f px: worst error 16 bits %.5f px, 8 bits %.4f px\n", range, worst16, worst8);
  // Half a step, plus the float arithmetic's rounding of C / R (a few ulps of R).
  EXPECT_LE(worst16, 0.5 * range / cp::kSteps16 + 1e-6 * range);
  EXPECT_LE(worst8, 0.5 * range / cp::kSteps8 + 1e-6 * range);
  // The composite blends the far field in from |C| = 1 px over one pixel: the 16-bit code moves that blend by at most
  // 1/2000 (1/8 of a display step), where 8 bits would move it by an eighth.
  EXPECT_LT(worst16, 1.0 / 2000.0);
  EXPECT_GT(worst8, 0.1);
}

TEST(CocPacking, OutOfRangeClampsAndNanIsZero) {
  EXPECT_EQ(cp::codeFromCoc(1e9f, 16.0f), 32768 + 32767);
  EXPECT_EQ(cp::codeFromCoc(-1e9f, 16.0f), 32768 - 32767);
  EXPECT_EQ(cp::codeFromCoc(INFINITY, 16.0f), 32768 + 32767);
  EXPECT_EQ(cp::codeFromCoc(NAN, 16.0f), 32768);
  EXPECT_EQ(cp::halfCodeFromCoc(-1e9f, 16.0f), 1);
  EXPECT_EQ(cp::halfCodeFromCoc(1e9f, 16.0f), 255);
}

TEST(ThinLens, IsSamuelciksCircleOfConfusionInPixelsSignedByDepth) {
  DofSettings settings;
  settings.fstop = 2.0f;
  settings.focalLength = 85.0f;
  settings.sensorHeight = 24.0f;
  const int height = 1080;
  const ThinLens lens = ThinLens::of(settings, height);
  const double a = 0.085 / 2.0, f = 0.085, p = 3.0;
  for (double d : {0.5, 1.0, 2.9, 3.0, 3.1, 10.0, 1000.0}) {
    const double millimetres = std::abs(a * f * (p - d) / (d * (p - f))) * 1000.0;  // C = |A F (P - D) / (D (P - F))|
    const double pixels = millimetres / 24.0 * height;
    const float c = lens.coc(static_cast<float>(d), static_cast<float>(p));
    EXPECT_NEAR(std::abs(c), pixels, 1e-4 * pixels + 1e-4) << d;
    if (d < p) {
      EXPECT_LT(c, 0.0f) << d;
    }
    if (d > p) {
      EXPECT_GT(c, 0.0f) << d;
    }
  }
  // The pinhole lens of the reference blurs a point at D over projScale A' |1/D - 1/P|: the same magnitude.
  const float projScale = 1234.5f;
  const float aperture = lens.pinholeAperture(3.0f, projScale);
  for (float d : {0.7f, 2.0f, 5.0f, 50.0f})
    EXPECT_NEAR(projScale * aperture * std::abs(1.0f / d - 1.0f / 3.0f), std::abs(lens.coc(d, 3.0f)),
                1e-4f * std::abs(lens.coc(d, 3.0f)));
  // A lens cannot focus nearer than its focal length.
  EXPECT_GT(lens.usableFocus(0.01f), 0.085f);
}

TEST(LensPoints, CoverTheDiscEvenly) {
  const int n = 64;
  glm::vec2 mean(0.0f);
  double secondMoment = 0.0;
  for (int i = 0; i < n; ++i) {
    const glm::vec2 p = lensPoint(i, n);
    EXPECT_LE(glm::length(p), 1.0f);
    mean += p / static_cast<float>(n);
    secondMoment += glm::dot(p, p) / n;
  }
  EXPECT_LT(glm::length(mean), 0.02f);
  EXPECT_NEAR(secondMoment, 0.5, 0.01);  // a uniform disc's mean r^2
}

TEST(DofSettings, ParametersAndPresets) {
  RenderSettings settings;
  EXPECT_EQ(settings.get("dof"), "off");
  EXPECT_EQ(settings.get("dof.focus"), "auto");
  settings.set("dof.focus", "2.5");
  EXPECT_EQ(settings.of<DofSettings>().focus.value_or(0.0f), 2.5f);
  settings.set("dof.focus", "auto");
  EXPECT_FALSE(settings.of<DofSettings>().focus.has_value());
  EXPECT_THROW(settings.set("dof.fstop", "0"), InputError);
  EXPECT_THROW(settings.set("dof.preset", "best"), InputError);
  EXPECT_EQ(settings.of<DofSettings>().taps(), 24);
  settings.set("preset", "ultra");
  EXPECT_EQ(settings.get("dof.preset"), "ultra");
  EXPECT_EQ(settings.of<DofSettings>().taps(), 64);
  settings.set("dof.preset", "low");
  EXPECT_EQ(settings.of<DofSettings>().taps(), 12);
  // The largest radius scales with the height and clamps to the tile passes' bound.
  EXPECT_FLOAT_EQ(settings.of<DofSettings>().maxRadiusPixels(720), 16.0f);
  EXPECT_FLOAT_EQ(settings.of<DofSettings>().maxRadiusPixels(1440), 32.0f);
  settings.set("dof.max-radius", "64");
  EXPECT_FLOAT_EQ(settings.of<DofSettings>().maxRadiusPixels(4320), 128.0f);
  // The autofocus pixel stays inside the frame.
  settings.set("dof.focus-x", "1");
  settings.set("dof.focus-y", "0");
  EXPECT_EQ(settings.of<DofSettings>().focusPixel(640, 360), glm::ivec2(639, 0));
}

TEST(PhysicalCamera, TheFieldOfViewFollowsFromTheSensorAndTheFocalLength) {
  const Camera fifty = Camera::fromJson(R"({"eye":[0,0,5],"target":[0,0,0],"focal_length_mm":50})", "test");
  EXPECT_NEAR(fifty.fovyDegrees, 2.0 * std::atan(12.0 / 50.0) * 180.0 / 3.14159265358979, 1e-4);  // 26.99 degrees
  const Camera small = Camera::fromJson(
      R"({"eye":[0,0,5],"target":[0,0,0],"focal_length_mm":35,"sensor_height_mm":15.6})", "test");
  EXPECT_NEAR(small.fovyDegrees, 2.0 * std::atan(7.8 / 35.0) * 180.0 / 3.14159265358979, 1e-4);
  EXPECT_THROW(Camera::fromJson(R"({"eye":[0,0,5],"target":[0,0,0],"focal_length_mm":50,"fovy_deg":30})", "test"),
               InputError);
  EXPECT_THROW(Camera::fromJson(R"({"eye":[0,0,5],"target":[0,0,0],"sensor_height_mm":24})", "test"), InputError);
  EXPECT_THROW(Camera::fromJson(R"({"eye":[0,0,5],"target":[0,0,0],"focal_length_mm":0})", "test"), InputError);
}

// The half-size fields' colour (dofFieldEncode): a byte of sqrt(c / (1 + c)) round-trips, and its step, measured in
// display colour (sRGB bytes, before any tone curve), stays near sRGB's own: under 1.5 bytes up to mid grey, under 2 at
// half of display white; it reaches 255 times display white.
TEST(DofField, HoldsHdrColourInAByteWithDisplayPrecision) {
  for (float c : {0.0f, 0.001f, 0.01f, 0.18f, 1.0f, 4.0f, 40.0f}) {
    const glm::vec3 back = dofFieldDecode(dofFieldEncode(glm::vec3(c)));
    EXPECT_NEAR(back.r, c, 1e-5f * std::max(c, 1.0f)) << c;
  }
  // One byte up from the encoding of c, in sRGB bytes of the display colour (linear, no tone curve).
  for (float c : {0.01f, 0.05f, 0.18f, 0.5f}) {
    const float f = std::round(dofFieldEncode(glm::vec3(c)).r * 255.0f) / 255.0f;
    const float next = dofFieldDecode(glm::vec3(f + 1.0f / 255.0f)).r, here = dofFieldDecode(glm::vec3(f)).r;
    const float step = (linearToSrgb(next) - linearToSrgb(here)) * 255.0f;
    EXPECT_LT(step, c < 0.2f ? 1.5f : 2.0f) << c;
  }
  EXPECT_NEAR(dofFieldDecode(glm::vec3(254.0f / 255.0f)).r, 127.0f, 1.0f);
  EXPECT_NEAR(dofFieldDecode(glm::vec3(1.0f)).r, 255.0f, 1e-3f);
}

}  // namespace
}  // namespace obscura
