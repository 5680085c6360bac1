// Colour grading (effects/grading/ColorGrading.h): the white balance against its definition (D65 at 6504 K, warmer
// above, cooler below), the .cube parameter refusing a malformed file and keeping the grade, and the GPU's stage
// function (shaders_es2/grading/grading.glsl) against the CPU mirror: white balance, ASC CDL, saturation and
// contrast within a byte; an identity LUT leaving colours unchanged within 1/255; a LUT computed from a known function
// matching that function within 2/255, in one strip and wrapped onto rows of slices. Then the same through the real
// frame, where the stage runs fused into the lighting or the tone curve's pass, in both lighting forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/gtx/component_wise.hpp>

#include "TestSupport.h"
#include "effects/grading/ColorGrading.h"
#include "encoding/ColorLut.h"
#include "encoding/ToneMapping.h"
#include "gl/ShaderLibrary.h"
#include "renderer/Renderer.h"
#include "scene/BuiltinScene.h"

using namespace obscura;

namespace {

// A point program running gradeDisplay on v_first.rgb (sRGB display colour).
gl::Program gradingProgram(bool balance, bool lut) {
  test::context();  // current before any GL object is made
  const std::vector<std::pair<std::string, std::string>> defines = {{"GRADING_BALANCE", balance ? "1" : "0"},
                                                                    {"GRADING_LUT", lut ? "1" : "0"},
                                                                    {"STAGE_OUTPUT_DISPLAY", "1"}};
  const std::string fragment = R"(
#include "lib/precision.glsl"
#include "lib/stage.glsl"
#include "grading/grading.glsl"
varying vec4 v_first;
varying vec3 v_second;
void main() { gl_FragColor = vec4(gradeDisplay(v_first.rgb), 1.0); }
)";
  return gl::Program("grading test", ShaderLibrary::composeText(test::kTwoValuePointVertex, defines, {}),
                     ShaderLibrary::composeText(fragment, defines, {}), true);
}

void setBalance(const gl::Program& p, const GradingSettings& s) {
  p.use();
  gl::Program::set(p.uniform("u_gradingBalance"), gradingBalance(s));
  gl::Program::set(p.uniform("u_gradingOffset"), s.offset);
  gl::Program::set(p.uniform("u_gradingPower"), s.power);
  gl::Program::set(p.uniform("u_gradingSaturationContrast"), glm::vec2(s.saturation, s.contrast));
}

// The strip of `lut` as a LINEAR texture bound to unit 3 (drawPoints makes its target on unit 0), and its uniforms.
gl::Texture2D setLut(const gl::Program& p, const ColorLut& lut, float intensity, int maxTextureSize) {
  const LutStrip strip = lutStrip(lut, maxTextureSize);
  gl::Texture2D texture(strip.width, strip.height, GL_LINEAR, strip.rgba.data());
  p.use();
  texture.bind(3);
  glActiveTexture(GL_TEXTURE0);  // drawPoints makes its target on the active unit
  gl::Program::set(p.uniform("u_gradingLut"), 3);
  gl::Program::set(p.uniform("u_gradingLutLayout"),
                   glm::vec4(static_cast<float>(lut.size), static_cast<float>(strip.slicesPerRow),
                             static_cast<float>(strip.width), static_cast<float>(strip.height)));
  gl::Program::set(p.uniform("u_gradingLutDomainMin"), lut.domainMin);
  gl::Program::set(p.uniform("u_gradingLutDomainScale"), 1.0f / (lut.domainMax - lut.domainMin));
  gl::Program::set(p.uniform("u_gradingLutIntensity"), intensity);
  return texture;
}

// Colours spread over the cube, and the greys: byte values, as the display colour the stage reads holds.
std::vector<glm::vec4> testColours() {
  std::vector<glm::vec4> out;
  std::mt19937 random(29);
  std::uniform_int_distribution<int> byte(0, 255);
  auto unit = [&](std::mt19937&) { return static_cast<float>(byte(random)) / 255.0f; };
  for (int i = 0; i < 4000; ++i) out.emplace_back(unit(random), unit(random), unit(random), 1.0f);
  for (int g = 0; g <= 255; g += 5) out.emplace_back(glm::vec3(static_cast<float>(g) / 255.0f), 1.0f);
  return out;
}

// The largest difference, in bytes, between the GPU's output and expected(input).
float worstBytes(const std::vector<std::uint8_t>& out, const std::vector<glm::vec4>& in,
                 const std::function<glm::vec3(const glm::vec3&)>& expected) {
  float worst = 0.0f;
  for (size_t i = 0; i < in.size(); ++i) {
    const glm::vec3 e = expected(glm::vec3(in[i])) * 255.0f;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(static_cast<float>(out[i * 4 + c]) - e[c]));
  }
  return worst;
}

}  // namespace

TEST(Grading, WhiteBalanceIsAVonKriesAdaptationToD65) {
  const glm::vec2 d65 = whiteChromaticity(6504.0f);
  EXPECT_NEAR(d65.x, 0.3127f, 2e-4f);
  EXPECT_NEAR(d65.y, 0.3290f, 2e-4f);
  const glm::vec2 a = whiteChromaticity(2856.0f);  // CIE illuminant A: x 0.4476, y 0.4074
  EXPECT_NEAR(a.x, 0.4476f, 2e-3f);
  EXPECT_NEAR(a.y, 0.4074f, 2e-3f);
  const glm::mat3 identity = whiteBalanceMatrix(6504.0f, 0.0f);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(identity[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
  // Corrected for tungsten light the picture's grey turns blue; for a blue sky's, orange; tint towards magenta.
  const glm::vec3 grey(0.5f);
  const glm::vec3 tungsten = whiteBalanceMatrix(3200.0f, 0.0f) * grey, sky = whiteBalanceMatrix(10000.0f, 0.0f) * grey;
  EXPECT_GT(tungsten.b, tungsten.r + 0.1f);
  EXPECT_GT(sky.r, sky.b + 0.05f);
  const glm::vec3 magenta = whiteBalanceMatrix(6504.0f, 50.0f) * grey;
  EXPECT_LT(magenta.g, magenta.r);
  EXPECT_LT(magenta.g, magenta.b);
  // The white the balance is set for becomes neutral: that illuminant's white, in linear Rec. 709, maps to grey.
  std::printf("tungsten on grey: %.3f %.3f %.3f; sky: %.3f %.3f %.3f\n", tungsten.r, tungsten.g, tungsten.b, sky.r,
              sky.g, sky.b);
}

TEST(Grading, AMalformedLutIsRefusedWithItsLineAndTheGradeStays) {
  const std::string good = test::writeTempFile("good.cube", writeCubeLut(ColorLut::identity(2)));
  const std::string bad = test::writeTempFile("bad.cube", "LUT_3D_SIZE 2\n0 0 0\n1 0 0\nx 1 0\n");
  GradingSettings settings;
  settings.set("lut", good);
  ASSERT_TRUE(settings.lutData);
  try {
    settings.set("lut", bad);
    FAIL() << "a malformed .cube was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad + " line 4: 'x' is not a number"), std::string::npos) << e.what();
  }
  EXPECT_EQ(settings.get("lut"), good);
  EXPECT_EQ(settings.lutData->size, 2);
  settings.set("lut", "none");
  EXPECT_FALSE(settings.lutData);
}

TEST(Grading, TheStageIsTheMirror) {
  GradingSettings s;
  s.temperature = 4300.0f;
  s.tint = 20.0f;
  s.slope = {1.1f, 0.95f, 1.0f};
  s.offset = {0.01f, 0.0f, -0.02f};
  s.power = {0.9f, 1.0f, 1.1f};
  s.saturation = 1.3f;
  s.contrast = 1.2f;
  const gl::Program program = gradingProgram(true, false);
  setBalance(program, s);
  const std::vector<glm::vec4> in = testColours();
  const float worst =
      worstBytes(test::drawPoints(program, in), in, [&](const glm::vec3& c) { return gradeDisplay(c, s); });
  std::printf("white balance, ASC CDL, saturation, contrast: worst %.2f / 255 from the mirror\n", worst);
  EXPECT_LE(worst, 1.0f);
}

TEST(Grading, AnIdentityLutLeavesColoursWithinAByte) {
  const gl::Program program = gradingProgram(false, true);
  const std::vector<glm::vec4> in = testColours();
  for (int size : {17, 33, 65}) {
    const gl::Texture2D texture =
        setLut(program, ColorLut::identity(size), 1.0f, test::context().caps().maxTextureSize);
    const float worst = worstBytes(test::drawPoints(program, in), in, [](const glm::vec3& c) { return c; });
    std::printf("identity LUT of %d: worst %.2f / 255\n", size, worst);
    EXPECT_LE(worst, 1.0f) << size;
  }
}

TEST(Grading, ALutOfAKnownFunctionMatchesItWithinTwoBytesInOneStripOrWrapped) {
  auto grade = [](const glm::vec3& c) {
    const glm::vec3 s = c * c * (3.0f - 2.0f * c);
    return glm::clamp(glm::vec3(0.8f * s.r + 0.2f * c.g, 0.9f * s.g + 0.05f * c.b, 0.85f * s.b + 0.1f * c.r), 0.0f,
                      1.0f);
  };
  const ColorLut lut = ColorLut::of(33, grade);
  const gl::Program program = gradingProgram(false, true);
  const std::vector<glm::vec4> in = testColours();
  // One strip (33 x 33 slices side by side), and wrapped into textures 256 texels wide (7 slices a row).
  for (int maxSize : {test::context().caps().maxTextureSize, 256}) {
    const gl::Texture2D texture = setLut(program, lut, 1.0f, maxSize);
    const std::vector<std::uint8_t> out = test::drawPoints(program, in);
    const float worst = worstBytes(out, in, grade);
    const float mirror = worstBytes(out, in, [&](const glm::vec3& c) { return lut.apply(c); });
    std::printf("LUT of a known function, strip %dx%d: worst %.2f / 255 from the function, %.2f from the mirror\n",
                texture.width(), texture.height(), worst, mirror);
    EXPECT_LE(worst, 2.0f);
    EXPECT_LE(mirror, 1.0f);
  }
}

namespace {

// The built-in scene's display colour through the real frame, undithered and without FXAA (each pixel its own), at
// 160 x 90. Its view (a pass after the stages, as FXAA is) lets the forward lighting run the stages too: it cannot
// draw into the output framebuffer itself.
test::RenderedImage builtinFrame(Renderer& renderer, RenderSettings settings) {
  settings.set("dither", "off");
  settings.set("fxaa", "off");
  return test::render(renderer, builtinSceneCamera(160, 90), settings, View{"display-color"});
}

// The largest difference in bytes between `graded` and expected(each pixel of `plain`), over the colour channels.
float worstAgainst(const test::RenderedImage& graded, const test::RenderedImage& plain,
                   const std::function<glm::vec3(const glm::vec3&)>& expected) {
  float worst = 0.0f;
  for (size_t i = 0; i < plain.rgba.size(); i += 4) {
    const glm::vec3 in(plain.rgba[i] / 255.0f, plain.rgba[i + 1] / 255.0f, plain.rgba[i + 2] / 255.0f);
    const glm::vec3 e = expected(in) * 255.0f;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(static_cast<float>(graded.rgba[i + c]) - e[c]));
  }
  return worst;
}

// Where the plan ran the grading stage: the pass it was fused into, or its own.
std::string gradingRanIn(const Renderer& renderer) {
  for (const PlannedPass& pass : renderer.lastPlan().passes()) {
    if (!pass.live) continue;
    if (pass.decl.name == "grading") return "its own pass";
    for (const std::string& absorbed : pass.absorbed)
      if (absorbed == "grading") return pass.decl.name;
  }
  return "nowhere";
}

}  // namespace

// Through the frame: an identity LUT leaves the image within a byte, and a LUT of a known function gives that
// function of the ungraded image within two (the stage reads the tone curve's unquantised colour, the function here
// its bytes: half a step more at most, times the function's slope); the white balance, CDL, saturation and contrast
// give the mirror's grade of the ungraded image within a byte. With and without several render targets
// (RendererOptions::allowDrawBuffers); the grade runs inside the lighting's pass, its LUT on the unit the lighting leaves to stages.
TEST(Grading, ThroughTheFrameAnIdentityLutChangesNothingAndAKnownFunctionMatches) {
  auto known = [](const glm::vec3& c) {
    const glm::vec3 s = c * c * (3.0f - 2.0f * c);
    return glm::clamp(glm::vec3(0.8f * s.r + 0.2f * c.g, 0.9f * s.g + 0.05f * c.b, 0.85f * s.b + 0.1f * c.r), 0.0f,
                      1.0f);
  };
  const std::string identityFile = test::writeTempFile("frame-identity.cube", writeCubeLut(ColorLut::identity(33)));
  const std::string knownFile = test::writeTempFile("frame-known.cube", writeCubeLut(ColorLut::of(33, known)));
  for (bool deferred : {true, false}) {
    const std::string form = deferred ? "deferred" : "forward";
    RendererOptions options;
    options.allowDrawBuffers = deferred;
    Renderer renderer = test::makeRenderer(options);
    renderer.setScene(makeBuiltinScene());
    const test::RenderedImage plain = builtinFrame(renderer, RenderSettings());

    RenderSettings identity;
    identity.set("grading", "on");
    identity.set("grading.lut", identityFile);
    const float identityWorst = worstAgainst(builtinFrame(renderer, identity), plain, [](const glm::vec3& c) {
      return c;
    });
    const std::string identityIn = gradingRanIn(renderer);

    RenderSettings function = identity;
    function.set("grading.lut", knownFile);
    const float functionWorst = worstAgainst(builtinFrame(renderer, function), plain, known);

    RenderSettings balance;
    balance.set("grading", "on");
    balance.set("grading.temperature", "4300");
    balance.set("grading.tint", "20");
    balance.set("grading.slope", "1.1,0.95,1");
    balance.set("grading.offset", "0.01,0,-0.02");
    balance.set("grading.power", "0.9,1,1.1");
    balance.set("grading.saturation", "1.3");
    balance.set("grading.contrast", "1.2");
    // The stage grades the tone curve's unquantised colour, the mirror the ungraded frame's bytes: the distance to
    // the nearest of the mirror's grades of the colours within half a step of those bytes (the grade is monotonic in
    // each channel, so its extremes over that cube lie at its corners).
    const GradingSettings& mirror = balance.of<GradingSettings>();
    const test::RenderedImage balanced = builtinFrame(renderer, balance);
    float balanceWorst = 0.0f;
    for (size_t i = 0; i < plain.rgba.size(); i += 4) {
      const glm::vec3 in(plain.rgba[i], plain.rgba[i + 1], plain.rgba[i + 2]);
      glm::vec3 lowest(255.0f), highest(0.0f);
      for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 offset((corner & 1) ? 0.5f : -0.5f, (corner & 2) ? 0.5f : -0.5f, (corner & 4) ? 0.5f : -0.5f);
        const glm::vec3 graded = 255.0f * gradeDisplay(glm::clamp((in + offset) / 255.0f, 0.0f, 1.0f), mirror);
        lowest = glm::min(lowest, graded);
        highest = glm::max(highest, graded);
      }
      for (int c = 0; c < 3; ++c) {
        const float out = balanced.rgba[i + static_cast<size_t>(c)];
        balanceWorst = std::max(balanceWorst, std::max(lowest[c] - out, out - highest[c]));
      }
    }
    std::printf("%s, grading in %s: identity LUT worst %.2f / 255 from the ungraded frame; a known function's LUT "
                "worst %.2f / 255 from the function; balance, CDL, saturation, contrast worst %.2f / 255 beyond the "
                "mirror's grades of the ungraded bytes +- 1/2\n",
                form.c_str(), identityIn.c_str(), identityWorst, functionWorst, balanceWorst);
    EXPECT_LE(identityWorst, 1.0f) << form;
    EXPECT_LE(functionWorst, 2.0f) << form;
    EXPECT_LE(balanceWorst, 1.0f) << form;
    EXPECT_EQ(identityIn, "lighting") << form << ": fused into the lighting's pass, with the tone curve";
  }
}

// A malformed .cube given to the frame's settings is refused with its line, and the frame keeps the grade it had.
TEST(Grading, AMalformedLutLeavesTheFramesGradeAsItWas) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  RenderSettings settings;
  settings.set("grading", "on");
  settings.set("grading.lut", test::writeTempFile("frame-warm.cube", writeCubeLut(ColorLut::of(9, [](glm::vec3 c) {
                                                    return glm::vec3(c.r, c.g * 0.9f, c.b * 0.7f);
                                                  }))));
  const test::RenderedImage before = builtinFrame(renderer, settings);
  const std::string bad = test::writeTempFile("frame-bad.cube", "LUT_3D_SIZE 2\n0 0 0\n1 0 0\n0 1 0\n1 1\n");
  try {
    settings.set("grading.lut", bad);
    FAIL() << "a malformed .cube was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad + " line 5"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
  }
  const test::RenderedImage after = builtinFrame(renderer, settings);
  EXPECT_EQ(before.rgba, after.rgba);
}
