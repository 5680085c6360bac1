// Distance fog (effects/fog/FogEffect.h): the CPU mirror against the lecture deck's equations written out again here,
// and the GPU's fog pass read back per pixel against the mirror's fog factor at the distance reconstructed from the
// G-buffer's depth, in each mode, with and without height falloff, the background included.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "effects/fog/FogEffect.h"
#include "encoding/HdrEncoding.h"
#include "frame/ViewReconstruction.h"
#include "scene/BuiltinScene.h"

using namespace obscura;

namespace {

FogSettings fogOf(FogMode mode, float heightFalloff) {
  FogSettings s;
  s.enabled = true;
  s.mode = mode;
  // For the built-in scene, whose surfaces lie 3 .. 15 m from its camera: every mode spans most of [0, 1] there.
  s.density = mode == FogMode::Exponential ? 0.15f : 0.12f;
  s.start = 3.0f;
  s.end = 12.0f;
  s.color = glm::vec3(0.6f, 0.7f, 2.5f);  // HDR, and unlike any surface colour
  s.heightFalloff = heightFalloff;
  return s;
}

}  // namespace

TEST(Fog, TheMirrorIsTheDecksEquations) {
  const glm::mat4 identity(1.0f);  // camera at the origin looking down -z, world up = view up
  for (float d : {0.0f, 1.0f, 3.0f, 7.5f, 12.0f, 30.0f}) {
    const glm::vec3 p(0.0f, 0.0f, -d);
    FogSettings s = fogOf(FogMode::Linear, 0.0f);
    EXPECT_NEAR(FogFactor::of(s, identity).at(p, false), std::clamp((12.0 - d) / (12.0 - 3.0), 0.0, 1.0), 1e-6) << d;
    s = fogOf(FogMode::Exponential, 0.0f);
    EXPECT_NEAR(FogFactor::of(s, identity).at(p, false), std::exp(-0.15 * d), 1e-6) << d;
    s = fogOf(FogMode::SquaredExponential, 0.0f);
    EXPECT_NEAR(FogFactor::of(s, identity).at(p, false), std::exp(-std::pow(0.12 * d, 2.0)), 1e-6) << d;
  }
  // The background is fully fogged in every mode without height falloff (exponential fog: 2^-126, the smallest
  // normal float the factor is clamped to).
  for (FogMode mode : {FogMode::Linear, FogMode::Exponential, FogMode::SquaredExponential})
    EXPECT_LT(FogFactor::of(fogOf(mode, 0.0f), identity).at(glm::vec3(0.3f, 0.2f, -1.0f), true), 1e-37f);
}

TEST(Fog, HeightFalloffIsTheOpticalDepthOfExponentialHeightFog) {
  // The camera 2 m up, looking along -z; exponential fog's f must be e^-(integral of the density along the ray),
  // here integrated numerically, for rays climbing, level and descending.
  const float b = 0.4f, h0 = 2.0f, density = 0.3f;
  const glm::mat4 view = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -h0, 0.0f));
  FogSettings s = fogOf(FogMode::Exponential, b);
  s.density = density;
  const FogFactor fog = FogFactor::of(s, view);
  for (const glm::vec3& direction : {glm::vec3(0.0f, 0.3f, -1.0f), glm::vec3(0.0f, 0.0f, -1.0f),
                                     glm::vec3(0.2f, -0.15f, -1.0f)}) {
    const glm::vec3 u = glm::normalize(direction);
    for (float d : {0.5f, 4.0f, 12.0f}) {
      double opticalDepth = 0.0;
      const int steps = 20000;
      for (int i = 0; i < steps; ++i) {
        const double t = (i + 0.5) * d / steps;
        opticalDepth += density * std::exp(-b * (h0 + t * u.y)) * d / steps;
      }
      EXPECT_NEAR(fog.at(u * d, false), std::exp(-opticalDepth), 2e-5) << "up " << u.y << ", d " << d;
    }
  }
  // The background: a climbing ray sees the finite integral to infinity, a level or descending one endless fog.
  const glm::vec3 up = glm::normalize(glm::vec3(0.0f, 0.5f, -1.0f));
  EXPECT_NEAR(fog.at(up, true), std::exp(-density * std::exp(-b * h0) / (b * up.y)), 1e-6);
  EXPECT_LT(fog.at(glm::vec3(0.0f, -0.1f, -1.0f), true), 1e-37f);
}

// Each mode's pass against the mirror: the frame rendered without fog gives each pixel's lit colour and depth, the
// frame with fog the pass's result; expected = f c_s + (1 - f) c_f with f from FogFactor at the pixel's centre. Through
// the built-in camera and its orthographic twin, whose parallel rays start on the eye's plane.
TEST(Fog, EachModeMatchesItsAnalyticFogFactorPerPixel) {
  for (bool orthographic : {false, true}) {
    Renderer renderer = test::makeRenderer();
    renderer.setScene(makeBuiltinScene());
    const int width = 160, height = 90;
    const Camera camera = orthographic ? builtinSceneCamera(width, height).asOrthographic()
                                       : builtinSceneCamera(width, height);
    const FrameCamera frameCamera = FrameCamera::from(camera, width, height);
    RenderSettings plain;
    plain.set("fxaa", "off");
    test::render(renderer, camera, plain, View::Final, test::retaining({"scene-color", "gbuffer"}));
    const std::vector<std::uint8_t> lit = renderer.retained("scene-color").readRgba();
    const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();

    for (FogMode mode : {FogMode::Linear, FogMode::Exponential, FogMode::SquaredExponential}) {
      for (float falloff : {0.0f, 0.35f}) {
        const std::string what = std::string(fogModeName(mode)) + (falloff > 0.0f ? " with height falloff" : "");
        RenderSettings settings = plain;
        settings.of<FogSettings>() = fogOf(mode, falloff);
        test::render(renderer, camera, settings, View::Final, test::retaining({"scene-color"}));
        const std::vector<std::uint8_t> fogged = renderer.retained("scene-color").readRgba();
        const FogFactor fog = FogFactor::of(settings.of<FogSettings>(), frameCamera.view);
        float worst = 0.0f;
        int partial = 0, background = 0;
        for (int row = 0; row < height; ++row) {
          for (int x = 0; x < width; ++x) {
            const size_t i = (static_cast<size_t>(row) * width + x) * 4;
            const glm::vec2 uv((static_cast<float>(x) + 0.5f) / static_cast<float>(width),
                               1.0f - (static_cast<float>(row) + 0.5f) / static_cast<float>(height));  // top to bottom
            const int code = gbuffer[i + 2] * 256 + gbuffer[i + 3];
            const bool isBackground = code == 65535;
            const ViewReconstruction& r = frameCamera.reconstruction;
            const float depth = static_cast<float>(code) / 65535.0f;
            const glm::vec3 p = isBackground ? r.farPlaneRay(uv) : r.viewPosition(uv, depth);
            const float f = fog.at(p, isBackground, r.eyeRayOrigin(p));
            partial += f > 0.05f && f < 0.95f;
            background += isBackground;
            const glm::vec3 surface = decodeHdr(HdrTexel{lit[i], lit[i + 1], lit[i + 2], lit[i + 3]});
            const glm::vec3 expected = f * surface + (1.0f - f) * settings.of<FogSettings>().color;
            const glm::vec3 got = decodeHdr(HdrTexel{fogged[i], fogged[i + 1], fogged[i + 2], fogged[i + 3]});
            // Relative to the brightest channel: RGB9E5 keeps 9 bits of it (half a step: 1/1024).
            const float largest = std::max(expected.r, std::max(expected.g, expected.b));
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[c] - expected[c]) / largest);
          }
        }
        std::printf("fog %s%s: worst error %.5f of the brightest channel; %d of %d pixels partly fogged, %d "
                    "background\n",
                    what.c_str(), orthographic ? " (orthographic)" : "", worst, partial, width * height, background);
        EXPECT_LT(worst, 2.5f / 512.0f) << what;
        EXPECT_GT(partial, width * height / 4) << what << ": the fog must vary over the frame for the test to tell";
      }
    }
  }
}

// Fog and the tone curve are per-pixel stages (frame/Stage.h): on the default frame they run inside the lighting's
// pass, in both of its forms, so turning fog on adds no full-screen pass; with TAA between them, the fog still runs in
// the lighting and the tone curve as a pass of its own (TAA reads the fogged HDR colour).
TEST(Fog, FogAndToneMappingAddNoFullScreenPassToTheDefaultFrame) {
  for (bool deferred : {true, false}) {
    RendererOptions options;
    options.allowDrawBuffers = deferred;  // without several render targets: the forward form
    Renderer renderer = test::makeRenderer(options);
    renderer.setScene(makeBuiltinScene());
    const Camera camera = builtinSceneCamera(96, 64);
    auto ran = [&](RenderSettings settings) {
      test::render(renderer, camera, settings, View::Final);
      std::vector<std::string> names;
      for (const PlannedPass& pass : renderer.lastPlan().passes()) {
        if (!pass.live) continue;
        names.push_back(pass.decl.name);
        for (const std::string& absorbed : pass.absorbed)
          names.push_back(absorbed + " (done by " + pass.decl.name + ")");
      }
      return names;
    };
    RenderSettings fog;
    fog.set("fog", "on");
    const std::vector<std::string> without = ran(RenderSettings()), with = ran(fog);
    const auto passes = [](const std::vector<std::string>& names) {
      return std::count_if(names.begin(), names.end(),
                           [](const std::string& n) { return n.find(" (done by ") == std::string::npos; });
    };
    const std::string form = deferred ? "deferred" : "forward";
    EXPECT_EQ(passes(with), passes(without)) << form;
    EXPECT_EQ(std::count(without.begin(), without.end(), "tonemap (done by lighting)"), 1) << form;
    EXPECT_EQ(std::count(with.begin(), with.end(), "fog (done by lighting)"), 1) << form;
    EXPECT_EQ(std::count(with.begin(), with.end(), "tonemap (done by lighting)"), 1) << form;
    for (const PlannedPass& pass : renderer.lastPlan().passes())
      if (pass.live && pass.decl.name == "lighting") {
        EXPECT_EQ(pass.stageOutput, "display-color") << form;
      }
    fog.set("taa", "on");
    const std::vector<std::string> taa = ran(fog);
    EXPECT_EQ(std::count(taa.begin(), taa.end(), "fog (done by lighting)"), 1) << form;
    EXPECT_EQ(std::count(taa.begin(), taa.end(), "tonemap"), 1) << form << ": after TAA, a pass of its own";
  }
}

// Fused or run as passes of their own (RendererOptions::fuseStages), the stages give the same image but for the HDR
// encoding the fused program skips between them (RGB9E5: 9 bits of the largest channel) and the position fog reads
// (the surface's own against the G-buffer's 16-bit depth): measured here, in both lighting forms, with fog in each
// mode and every tone curve.
TEST(Fog, FusedStagesGiveTheImageOfSeparatePasses) {
  const Camera camera = builtinSceneCamera(160, 90);
  for (bool deferred : {true, false}) {
    RendererOptions fused, separate;
    fused.allowDrawBuffers = separate.allowDrawBuffers = deferred;
    separate.fuseStages = false;
    Renderer a = test::makeRenderer(fused), b = test::makeRenderer(separate);
    a.setScene(makeBuiltinScene());
    b.setScene(makeBuiltinScene());
    int worst = 0;
    double sum = 0.0;
    size_t count = 0;
    for (FogMode mode : {FogMode::Linear, FogMode::Exponential, FogMode::SquaredExponential})
      for (const char* curve : {"neutral", "aces", "agx", "reinhard", "linear"}) {
        RenderSettings settings;
        settings.of<FogSettings>() = fogOf(mode, mode == FogMode::Exponential ? 0.35f : 0.0f);
        settings.set("tonemap.operator", curve);
        settings.set("tonemap.exposure", "0.5");
        settings.set("fxaa", "off");  // the stages' own output, drawn into the output
        // Undithered: a step of noise on colours that differ by a fraction of a step would add its own differences.
        settings.set("dither", "off");
        const test::RenderedImage one = test::render(a, camera, settings, View::Final);
        const test::RenderedImage two = test::render(b, camera, settings, View::Final);
        for (size_t i = 0; i < one.rgba.size(); ++i) {
          if (i % 4 == 3) continue;
          const int d = std::abs(int(one.rgba[i]) - int(two.rgba[i]));
          worst = std::max(worst, d);
          sum += d;
          ++count;
        }
      }
    std::printf("%s lighting, fog and tone mapping fused against separate passes: largest difference %d/255, mean "
                "%.4f/255\n",
                deferred ? "deferred" : "forward", worst, sum / static_cast<double>(count));
    EXPECT_LE(worst, 2) << (deferred ? "deferred" : "forward");
    EXPECT_LT(sum / static_cast<double>(count), 0.1) << (deferred ? "deferred" : "forward");
  }
}
