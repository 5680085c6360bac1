// The camera's finish's per-pixel functions on the GPU (shaders_es2/vignette, grain, dither), against their CPU mirrors
// and their stated properties: the vignette's factor (1 at the centre, falling outwards, round on screen); the grain's
// zero mean, its luminance weighting and a new pattern each frame; the dithering's banding on a smooth dark gradient
// (runs of one 8-bit value) and its mean change. Then as stages of the real frame: with every per-pixel stage on, the
// frame has no more full-screen passes than the default one; the vignette and the grain against their mirrors applied
// to the frame without them; the dithering on a fog ramp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "TestSupport.h"
#include "effects/chromatic_aberration/ChromaticAberrationEffect.h"
#include "effects/dither/Dither.h"
#include "effects/grain/Grain.h"
#include "effects/vignette/Vignette.h"
#include "encoding/ColorLut.h"
#include "gl/ShaderLibrary.h"
#include "renderer/Renderer.h"
#include "scene/BuiltinScene.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

// A point program whose fragment is `body` (v_first and v_second: drawPoints' two values).
gl::Program pointProgram(const std::string& includes, const std::string& body) {
  test::context();
  const std::string fragment = "#include \"lib/precision.glsl\"\n#include \"lib/stage.glsl\"\n" + includes +
                               "varying vec4 v_first;\nvarying vec3 v_second;\nvoid main() { " + body + " }\n";
  const std::vector<std::pair<std::string, std::string>> defines = {{"STAGE_OUTPUT_DISPLAY", "1"}};
  return gl::Program("finish stage test", ShaderLibrary::composeText(test::kTwoValuePointVertex, defines, {}),
                     ShaderLibrary::composeText(fragment, defines, {}), true);
}

// Counts runs of one value longer than `longest` in a row of bytes.
int longRuns(const std::vector<int>& row, int longest) {
  int runs = 0, length = 1;
  for (size_t i = 1; i <= row.size(); ++i) {
    if (i < row.size() && row[i] == row[i - 1]) {
      ++length;
      continue;
    }
    if (length > longest) ++runs;
    length = 1;
  }
  return runs;
}

}  // namespace

TEST(Vignette, TheFactorFallsFromTheCentreAndIsRoundOnScreen) {
  VignetteSettings settings;
  const float aspect = 16.0f / 9.0f;
  const glm::vec3 shape = vignetteShape(settings, aspect);
  EXPECT_FLOAT_EQ(vignetteFactor({0.5f, 0.5f}, shape), 1.0f);
  float previous = 1.0f;
  for (float t = 0.05f; t <= 0.5f; t += 0.05f) {
    const float f = vignetteFactor({0.5f + t, 0.5f + t}, shape);
    EXPECT_LT(f, previous) << t;
    previous = f;
  }
  // Round on screen: the same distance in pixels along x and y gives the same factor.
  EXPECT_NEAR(vignetteFactor({0.5f + 0.2f / aspect, 0.5f}, shape), vignetteFactor({0.5f, 0.7f}, shape), 1e-6f);
  // The GPU's factor against the mirror over a grid of uv.
  const gl::Program program = pointProgram("#include \"vignette/vignette.glsl\"\n",
                                           "gl_FragColor = vec4(vec3(vignetteFactor(v_first.xy)), 1.0);");
  program.use();
  gl::Program::set(program.uniform("u_vignetteShape"), shape);
  std::vector<glm::vec4> uv;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      uv.emplace_back((static_cast<float>(x) + 0.5f) / 64.0f, (static_cast<float>(y) + 0.5f) / 64.0f, 0.0f, 0.0f);
  const std::vector<std::uint8_t> out = test::drawPoints(program, uv);
  float worst = 0.0f;
  for (size_t i = 0; i < uv.size(); ++i)
    worst = std::max(worst, std::abs(out[i * 4] - 255.0f * vignetteFactor(glm::vec2(uv[i]), shape)));
  EXPECT_LE(worst, 1.0f);
}

TEST(Grain, HasZeroMeanFollowsTheLuminanceAndChangesEveryFrame) {
  const gl::Program program = pointProgram("#include \"lib/hash.glsl\"\n#include \"grain/grain.glsl\"\n",
                                           "gl_FragColor = vec4(grain(v_first.rgb, v_second.xy), 1.0);");
  GrainSettings settings;
  settings.enabled = true;
  auto run = [&](float grey, std::uint64_t frame) {
    program.use();
    gl::Program::set(program.uniform("u_grain"), grainUniform(settings, frame));
    std::vector<glm::vec4> colour(static_cast<size_t>(test::kPointSide) * test::kPointSide, glm::vec4(grey));
    std::vector<glm::vec3> pixel;
    for (int i = 0; i < test::kPointSide * test::kPointSide; ++i)
      pixel.emplace_back(static_cast<float>(i % test::kPointSide) + 0.5f,
                         static_cast<float>(i / test::kPointSide) + 0.5f, 0.0f);
    const std::vector<std::uint8_t> out = test::drawPoints(program, colour, pixel);
    std::vector<float> values(colour.size());
    for (size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>(out[i * 4 + 1]) - 255.0f * grey;
    return values;
  };
  auto stats = [](const std::vector<float>& v) {
    double sum = 0.0, squares = 0.0;
    for (float x : v) {
      sum += x;
      squares += double(x) * x;
    }
    const double mean = sum / static_cast<double>(v.size());
    return std::make_pair(mean, std::sqrt(squares / static_cast<double>(v.size()) - mean * mean));
  };
  const std::vector<float> dark = run(0.2f, 0), bright = run(0.9f, 0), next = run(0.2f, 1);
  const auto [darkMean, darkSd] = stats(dark);
  const auto [brightMean, brightSd] = stats(bright);
  double correlation = 0.0;
  for (size_t i = 0; i < dark.size(); ++i) correlation += double(dark[i] - darkMean) * (next[i] - darkMean);
  correlation /= static_cast<double>(dark.size()) * darkSd * darkSd;
  std::printf("grain: at 0.2 mean %+.3f sd %.2f; at 0.9 mean %+.3f sd %.2f (bytes); frame to frame correlation %.3f\n",
              darkMean, darkSd, brightMean, brightSd, correlation);
  EXPECT_LT(std::abs(darkMean), 0.3);
  EXPECT_LT(std::abs(brightMean), 0.3);
  EXPECT_GT(darkSd, 2.0 * brightSd);
  EXPECT_LT(std::abs(correlation), 0.1);
  // The mirror's noise at a few pixels, against the GPU's (the hash's float arithmetic may differ in a last bit).
  int close = 0;
  const glm::vec4 u = grainUniform(settings, 0);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec2 p(static_cast<float>(i % test::kPointSide) + 0.5f, static_cast<float>(i / test::kPointSide) + 0.5f);
    close += std::abs(dark[static_cast<size_t>(i)] - 255.0f * (grained(glm::vec3(0.2f), p, u).g - 0.2f)) <= 1.0f;
  }
  EXPECT_GE(close, 950);
}

// A smooth dark gradient, 8/255 to 12/255 over 1024 pixels (a dim sky): quantised as it is, it falls into runs of one
// value 256 pixels long; dithered, no run is longer than 64 pixels, and the mean moves by less than half a step.
TEST(Dither, BreaksTheBandsOfADarkGradientWithoutMovingItsMean) {
  const gl::Program program = pointProgram("#include \"lib/hash.glsl\"\n#include \"dither/dither.glsl\"\n",
                                           "gl_FragColor = vec4(v_first.rgb, 1.0); "
                                           "if (v_first.a > 0.5) gl_FragColor.rgb = dither(v_first.rgb, v_second.xy);");
  const int width = 1024, rows = 32;
  auto run = [&](bool dithered) {
    program.use();
    std::vector<glm::vec4> colour;
    std::vector<glm::vec3> pixel;
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < width; ++x) {
        const float v = (8.0f + 4.0f * (static_cast<float>(x) + 0.5f) / width) / 255.0f;
        colour.emplace_back(glm::vec3(v), dithered ? 1.0f : 0.0f);
        pixel.emplace_back(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, 0.0f);
      }
    const std::vector<std::uint8_t> out = test::drawPoints(program, colour, pixel);
    int runs = 0;
    double change = 0.0;
    for (int y = 0; y < rows; ++y) {
      std::vector<int> row;
      for (int x = 0; x < width; ++x) {
        const size_t i = static_cast<size_t>(y) * width + static_cast<size_t>(x);
        row.push_back(out[i * 4 + 1]);
        change += out[i * 4 + 1] - 255.0 * colour[i].g;
      }
      runs += longRuns(row, 64);
    }
    return std::make_pair(runs, change / (static_cast<double>(width) * rows));
  };
  const auto [plainRuns, plainChange] = run(false);
  const auto [ditheredRuns, ditheredChange] = run(true);
  std::printf("dark gradient: %d runs longer than 64 pixels quantised as it is (mean change %+.3f / 255), %d dithered "
              "(mean change %+.3f / 255)\n",
              plainRuns, plainChange, ditheredRuns, ditheredChange);
  EXPECT_GE(plainRuns, 3 * rows);
  EXPECT_EQ(ditheredRuns, 0);
  EXPECT_LT(std::abs(ditheredChange), 0.5);
  // The offsets are triangular in (-1, 1) steps: mean 0, variance 1/6.
  double sum = 0.0, squares = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const glm::vec2 pixel(static_cast<float>(i % 317) + 0.5f, static_cast<float>(i / 317) + 0.5f);
    const float o = 255.0f * ditherOffset(pixel);
    sum += o;
    squares += double(o) * o;
  }
  EXPECT_NEAR(sum / 100000.0, 0.0, 0.01);
  EXPECT_NEAR(squares / 100000.0, 1.0 / 6.0, 0.01);
}

// A white bar near the right edge of a black frame: red lands further out and blue further in than green, each by
// the intensity times the bar's distance from the centre (the channels' centroids along x), the centre's colour
// unchanged.
TEST(ChromaticAberration, RedAndBlueLieOutsideAndInsideGreenByTheStatedShift) {
  Renderer renderer = test::makeRenderer();
  // The bar glows (emission 1: display white), in a black room.
  Scene scene;
  test::addStill(scene, test::makeRectangle({1.55f, -2.0f, 0.0f}, {0.04f, 0.0f, 0.0f}, {0.0f, 4.0f, 0.0f}),
                 glm::vec3(0.0f));
  scene.materials.back().emissiveFactor = glm::vec3(1.0f);
  renderer.setScene(scene);
  const int width = 320, height = 180;
  const Camera camera = test::makeCamera({0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, width, height, 0.1f, 100.0f, 60.0f);
  RenderSettings settings;
  settings.set("fxaa", "off");
  settings.set("ao", "off");
  settings.set("lighting.environment", "uniform");
  settings.set("lighting.environment-intensity", "0");
  settings.set("lighting.sun-intensity", "0");
  settings.set("chromatic-aberration", "on");
  settings.set("chromatic-aberration.intensity", "0.03");
  const test::RenderedImage image = test::render(renderer, camera, settings, View::Final);
  double centroid[3] = {}, mass[3] = {};
  const int row = height / 2;
  for (int x = 0; x < width; ++x)
    for (int c = 0; c < 3; ++c) {
      const double v = image.channel(x, row, c);
      centroid[c] += v * (x + 0.5);
      mass[c] += v;
    }
  for (int c = 0; c < 3; ++c) centroid[c] /= mass[c];
  const double fromCentre = centroid[1] - 0.5 * width;
  std::printf("bar at %.2f px from the centre: red %+.2f px, blue %+.2f px from green (expected %+.2f, %+.2f)\n",
              fromCentre, centroid[0] - centroid[1], centroid[2] - centroid[1], 0.03 * fromCentre, -0.03 * fromCentre);
  ASSERT_GT(fromCentre, 50.0);
  // Magnified by 1 + k and 1 - k about the centre: k d out and in (to first order in k).
  EXPECT_NEAR(centroid[0] - centroid[1], 0.03 * fromCentre, 0.5);
  EXPECT_NEAR(centroid[2] - centroid[1], -0.03 * fromCentre, 0.5);
  EXPECT_FLOAT_EQ(aberrationSource({0.5f, 0.5f}, 0, 0.03f).x, 0.5f);
}

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The built-in scene through the real frame without FXAA (each pixel its own), at 160 x 90.
test::RenderedImage builtinFrame(Renderer& renderer, RenderSettings settings) {
  settings.set("fxaa", "off");
  return test::render(renderer, builtinSceneCamera(160, 90), settings, View::Final);
}

}  // namespace

// Issue 29: with every per-pixel stage on (fog, the tone curve, grading with its LUT and every other part, the
// vignette, the grain, the dithering) the frame has no more full-screen passes than the default frame: they run
// inside the lighting's pass, in both lighting forms; and with TAA on, inside the tone curve's pass after it.
TEST(FinishStages, EveryStageOnAddsNoFullScreenPassToTheDefaultFrame) {
  const std::string lut = test::writeTempFile("plan.cube", writeCubeLut(ColorLut::identity(17)));
  for (bool deferred : {true, false})
    for (bool taa : {false, true}) {
      RendererOptions options;
      options.allowDrawBuffers = deferred;
      Renderer renderer = test::makeRenderer(options);
      renderer.setScene(makeBuiltinScene());
      const Camera camera = builtinSceneCamera(96, 64);
      RenderSettings base;
      if (taa) base.set("taa", "on");
      test::render(renderer, camera, base, View::Final);
      const std::vector<std::string> plain = test::livePasses(renderer);
      RenderSettings every = base;
      for (const char* on : {"fog", "tonemap", "grading", "vignette", "grain", "dither"}) every.set(on, "on");
      every.set("grading.lut", lut);
      every.set("grading.temperature", "5000");
      every.set("grading.saturation", "1.2");
      test::render(renderer, camera, every, View::Final);
      const std::vector<std::string> all = test::livePasses(renderer);
      const std::string form = std::string(deferred ? "deferred" : "forward") + (taa ? ", taa" : "");
      std::printf("%s: default frame %s\n  every stage on: %s\n", form.c_str(), joined(plain).c_str(),
                  joined(all).c_str());
      EXPECT_EQ(test::passCount(all), test::passCount(plain)) << form;
      const std::string head = taa ? "tonemap" : "lighting";
      for (const char* stage : {"grading", "vignette", "grain", "dither"}) {
        EXPECT_EQ(std::count(all.begin(), all.end(), std::string(stage) + " (done by " + head + ")"), 1)
            << form << ": " << stage;
      }
    }
}

// The vignette through the frame: the mirror's factor on the display-referred light of the frame without it, at
// each pixel's uv, within a byte and a half (the stage multiplies the tone curve's unquantised colour, the mirror
// that colour's bytes).
TEST(FinishStages, TheVignetteInTheFrameIsTheMirrorsOfTheFrameWithoutIt) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  RenderSettings plainSettings;
  plainSettings.set("dither", "off");
  const test::RenderedImage plain = builtinFrame(renderer, plainSettings);
  RenderSettings settings = plainSettings;
  settings.set("vignette", "on");
  settings.set("vignette.intensity", "0.6");
  settings.set("vignette.roundness", "0.5");
  const test::RenderedImage vignetted = builtinFrame(renderer, settings);
  const glm::vec3 shape =
      vignetteShape(settings.of<VignetteSettings>(),
                    static_cast<float>(plain.width) / static_cast<float>(plain.height));
  float worst = 0.0f, darkest = 1.0f;
  const float width = static_cast<float>(plain.width), height = static_cast<float>(plain.height);
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) {
      const float fx = static_cast<float>(x), fy = static_cast<float>(y);
      const glm::vec2 uv((fx + 0.5f) / width, 1.0f - (fy + 0.5f) / height);  // rows top to bottom
      const glm::vec3 in(plain.channel(x, y, 0), plain.channel(x, y, 1), plain.channel(x, y, 2));
      const glm::vec3 expected = 255.0f * obscura::vignetted(in / 255.0f, uv, shape);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(vignetted.channel(x, y, c) - expected[c]));
      darkest = std::min(darkest, vignetteFactor(uv, shape));
    }
  std::printf("vignette through the frame: worst %.2f / 255 from the mirror; the corners' factor %.3f\n", worst,
              darkest);
  EXPECT_LT(darkest, 0.5f);
  // Half a step of the mirror's rounding against the frame's; a GPU's pow, in the factor and the sRGB curves (its
  // precision left to the implementation by GLSL ES 1.00), a little more (NVIDIA's driver on an H200: 1.52 steps).
  EXPECT_LE(worst, 2.0f);
}

// The grain through the frame, at the frame's index: the mirror's grain on the frame without it, at each pixel's
// gl_FragCoord, within a byte and a half for nearly every value (the hash's float arithmetic may differ in a last
// bit, moving a cell's value), and a new pattern in the next frame.
TEST(FinishStages, TheGrainInTheFrameIsTheMirrorsAtTheFramesIndex) {
  Renderer renderer = test::makeRenderer();  // a fresh renderer: its frames are 0, 1, 2, ...
  renderer.setScene(makeBuiltinScene());
  RenderSettings plainSettings;
  plainSettings.set("dither", "off");
  const test::RenderedImage plain = builtinFrame(renderer, plainSettings);  // frame 0
  RenderSettings settings = plainSettings;
  settings.set("grain", "on");
  settings.set("grain.intensity", "0.2");
  const test::RenderedImage first = builtinFrame(renderer, settings);   // frame 1
  const test::RenderedImage second = builtinFrame(renderer, settings);  // frame 2
  const glm::vec4 u = grainUniform(settings.of<GrainSettings>(), 1);
  int close = 0, values = 0, changed = 0;
  double mean = 0.0;
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) {
      // Rows top to bottom, gl_FragCoord from below.
      const glm::vec2 fragCoord(static_cast<float>(x) + 0.5f, static_cast<float>(plain.height - y) - 0.5f);
      const glm::vec3 in(plain.channel(x, y, 0), plain.channel(x, y, 1), plain.channel(x, y, 2));
      const glm::vec3 expected = 255.0f * grained(in / 255.0f, fragCoord, u);
      for (int c = 0; c < 3; ++c) {
        close += std::abs(first.channel(x, y, c) - glm::clamp(expected[c], 0.0f, 255.0f)) <= 1.5f;
        changed += first.channel(x, y, c) != second.channel(x, y, c);
        mean += first.channel(x, y, c) - in[c];
        ++values;
      }
    }
  std::printf("grain through the frame: %.2f %% of the values within 1.5 / 255 of the mirror, mean change %+.3f / 255, "
              "%.1f %% of the values change in the next frame\n",
              100.0 * close / values, mean / values, 100.0 * changed / values);
  EXPECT_GE(close, values * 99 / 100);
  EXPECT_LT(std::abs(mean / values), 0.5);
  EXPECT_GT(changed, values / 2);
}

// Dithering through the frame, on a smooth dark gradient: linear fog over a black plane tilted away from an
// orthographic camera, whose view depth, and so the fog, grows linearly down the frame (from black to about 11/255,
// about 45 rows per 8-bit value). Quantised as it is, the columns fall into runs of one value longer than 32 pixels;
// dithered (the default), none is, and the mean moves by less than half a step.
TEST(FinishStages, DitheringInTheFrameBreaksTheBandsOfAFogRamp) {
  Scene scene;
  test::addStill(scene, test::makeRectangle({-3.0f, -3.0f, -3.0f}, {6.0f, 0.0f, 0.0f}, {0.0f, 6.0f, 6.0f}),
                 glm::vec3(0.0f));
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  Camera camera = test::makeCamera({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, 64, 512, 0.1f, 20.0f, 50.0f);
  camera.orthographic = true;
  camera.ymag = 2.0f;
  RenderSettings settings;
  settings.set("ao", "off");
  settings.set("lighting.environment", "uniform");
  settings.set("lighting.environment-intensity", "0");
  settings.set("lighting.sun-intensity", "0");
  settings.set("tonemap.operator", "linear");
  settings.set("fog", "on");
  settings.set("fog.mode", "linear");
  settings.set("fog.start", "3");
  settings.set("fog.end", "7");
  settings.set("fog.color", "0.0035,0.0035,0.0035");
  auto measure = [&](bool dithered) {
    RenderSettings s = settings;
    s.set("dither", dithered ? "on" : "off");
    const test::RenderedImage image = test::render(renderer, camera, s, View::Final);
    int runs = 0;
    double sum = 0.0;
    int top = 255, bottom = 0;
    for (int x = 0; x < image.width; ++x) {
      std::vector<int> column;
      for (int y = 0; y < image.height; ++y) {
        column.push_back(image.channel(x, y, 1));
        sum += image.channel(x, y, 1);
      }
      runs += longRuns(column, 32);
      top = std::min(top, column.front());
      bottom = std::max(bottom, column.back());
    }
    return std::make_tuple(runs, sum / (static_cast<double>(image.width) * image.height), top, bottom);
  };
  const auto [plainRuns, plainMean, plainTop, plainBottom] = measure(false);
  const auto [ditheredRuns, ditheredMean, ditheredTop, ditheredBottom] = measure(true);
  std::printf("fog ramp %d .. %d / 255 over 512 rows: %d runs longer than 32 pixels quantised as it is, %d dithered; "
              "mean %.3f / 255 undithered, %.3f dithered (change %+.3f)\n",
              plainTop, plainBottom, plainRuns, ditheredRuns, plainMean, ditheredMean, ditheredMean - plainMean);
  EXPECT_GE(plainRuns, 5 * 64) << "the ramp must band without dithering";
  EXPECT_EQ(ditheredRuns, 0);
  EXPECT_LT(std::abs(ditheredMean - plainMean), 0.5);
}
