// Bloom (effects/bloom/BloomEffect.h): the CPU mirror of its weights against Jimenez 2014's taps, why the chain decodes
// texels by hand (the hardware's filter on encoded bytes, measured), and the GPU chain on frames made here: a frame
// with no pixel above the threshold is unchanged, a single bright pixel spreads into a symmetric glow that falls off
// with the distance and carries `intensity` times its light above the threshold, and a smooth HDR gradient stays
// monotonic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "TestSupport.h"
#include "effects/bloom/BloomEffect.h"
#include "encoding/HdrEncoding.h"
#include "frame/PassContext.h"
#include "gl/RenderTarget.h"
#include "scene/BuiltinScene.h"

using namespace obscura;

namespace {

// A frame of linear HDR colours, rows bottom to top (GL's order).
struct Frame {
  int width = 0, height = 0;
  std::vector<glm::vec3> pixels;
  glm::vec3& at(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
  const glm::vec3& at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

Frame blank(int width, int height) { return Frame{width, height, std::vector<glm::vec3>(size_t(width) * height)}; }

// The frame through BloomEffect::render, as the pass runs it, decoded.
Frame bloomed(BloomEffect& bloom, const BloomSettings& settings, const Frame& input) {
  std::vector<std::uint8_t> bytes;
  for (const glm::vec3& c : input.pixels) {
    const HdrTexel t = encodeHdr(c);
    bytes.insert(bytes.end(), t.begin(), t.end());
  }
  const gl::Texture2D scene(input.width, input.height, GL_NEAREST, bytes.data());
  const gl::RenderTarget out("bloom test output", input.width, input.height, GL_NEAREST,
                             gl::RenderTarget::Depth::None, false);
  bloom.render(settings, scene, {input.width, input.height}, [&out] { out.bindForDrawing(); });
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  const std::vector<std::uint8_t> read = out.readRgba();  // rows top to bottom
  Frame result = blank(input.width, input.height);
  for (int row = 0; row < input.height; ++row)
    for (int x = 0; x < input.width; ++x) {
      const size_t i = (static_cast<size_t>(row) * input.width + x) * 4;
      result.at(x, input.height - 1 - row) = decodeHdr(HdrTexel{read[i], read[i + 1], read[i + 2], read[i + 3]});
    }
  return result;
}

}  // namespace

TEST(Bloom, TheDownsampleWeightsAreJimenezsThirteenTaps) {
  // The 13 bilinear taps on texel corners (offsets in texels from the corner at the pixel's centre), each a 2 x 2
  // box, spread over the 6 x 6 texels at offsets -3 .. 2.
  struct Tap {
    int x, y;
    float weight;
  };
  std::vector<Tap> taps = {{-1, -1, 0.125f}, {1, -1, 0.125f}, {-1, 1, 0.125f}, {1, 1, 0.125f}};
  for (int y : {-2, 0, 2})
    for (int x : {-2, 0, 2}) taps.push_back({x, y, (x == 0 ? 2.0f : 1.0f) * (y == 0 ? 2.0f : 1.0f) / 32.0f});
  float grid[6][6] = {};
  float total = 0.0f;
  for (const Tap& t : taps) {
    total += t.weight;
    for (int dy : {-1, 0})
      for (int dx : {-1, 0}) grid[t.y + dy + 3][t.x + dx + 3] += t.weight / 4.0f;
  }
  EXPECT_FLOAT_EQ(total, 1.0f);
  float sum = 0.0f;
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      EXPECT_FLOAT_EQ(bloomDownsampleWeight(i, j), grid[j][i]) << i << ", " << j;
      sum += bloomDownsampleWeight(i, j);
    }
  EXPECT_FLOAT_EQ(sum, 1.0f);
}

TEST(Bloom, TheUpsampleWeightsAreATentOfBilinearTaps) {
  for (float f : {0.0f, 0.25f, 0.5f, 0.75f, 0.999f}) {
    // Bilinear taps at -1, 0, +1 texels (weights 1/4, 1/2, 1/4), each splitting between texels i and i + 1.
    float expected[4] = {};
    const float tent[3] = {0.25f, 0.5f, 0.25f};
    for (int t = 0; t < 3; ++t) {
      expected[t] += tent[t] * (1.0f - f);
      expected[t + 1] += tent[t] * f;
    }
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
      EXPECT_FLOAT_EQ(bloomUpsampleWeight(k, f), expected[k]) << k << " at " << f;
      sum += bloomUpsampleWeight(k, f);
    }
    EXPECT_FLOAT_EQ(sum, 1.0f);
  }
}

TEST(Bloom, TheSoftThresholdKeepsNothingAtOrBelowTheThresholdAndIsSmooth) {
  const float t = 1.0f, knee = 0.5f, k = knee * t;
  auto kept = [&](float m) { return m * bloomThresholdScale(glm::vec3(m, 0.2f * m, 0.0f), t, knee); };
  for (float m : {0.0f, 0.3f, 0.999f, 1.0f}) EXPECT_EQ(kept(m), 0.0f) << m;
  // The quadratic meets the line m - T - K at T + 2K with the line's value and slope 1.
  const float joint = t + 2.0f * k, h = 1e-3f;
  EXPECT_NEAR(kept(joint), joint - t - k, 1e-5f);
  EXPECT_NEAR((kept(joint - h) - kept(joint - 2 * h)) / h, 1.0f, 2e-3f);
  EXPECT_NEAR(kept(5.0f), 5.0f - t - k, 1e-5f);
  // A hard threshold without a knee.
  EXPECT_FLOAT_EQ(3.0f * bloomThresholdScale(glm::vec3(3.0f), 1.0f, 0.0f), 2.0f);
  // The colour keeps its hue: one factor scales every channel.
  EXPECT_EQ(bloomThresholdScale(glm::vec3(4.0f, 2.0f, 1.0f), t, knee), kept(4.0f) / 4.0f);
}

TEST(Bloom, TheChainHasSixLevelsDownToAbout1Of64) {
  EXPECT_EQ(bloomLevels({1280, 720}), 6);  // 20 x 11 at the bottom
  EXPECT_EQ(bloomLevels({640, 360}), 6);   // 10 x 5
  EXPECT_EQ(bloomLevels({160, 90}), 5);    // 5 x 2: a sixth level would be 2 x 1
  EXPECT_EQ(bloomLevels({4, 4}), 1);
}

// Why the chain decodes texels by hand: the bilinear filter at the midpoint of two texels, as a GPU computes it on the
// stored bytes (then rounded back to bytes by the decoder), against the mean of the two decoded colours, for HDR
// colours spread over 2^-6 .. 2^6 per channel.
TEST(Bloom, HardwareFilteringOfEncodedTexelsIsWrong) {
  std::mt19937 random(15);
  std::uniform_real_distribution<float> exponent(-6.0f, 6.0f);
  auto channel = [&] { return std::exp2(exponent(random)); };
  auto colour = [&] {
    const float r = channel(), g = channel();
    return glm::vec3(r, g, channel());
  };
  std::vector<std::pair<glm::vec3, glm::vec3>> pairs;
  for (int i = 0; i < 20000; ++i) pairs.emplace_back(colour(), colour());
  std::printf("hardware-filtered midpoint, error relative to the true mean's largest channel:\n");
  for (const HdrEncoding& encoding : hdrEncodingCandidates()) {
    double sum = 0.0, worst = 0.0, byHandWorst = 0.0;
    for (const auto& [a, b] : pairs) {
      const HdrTexel ta = encodeHdr(a, encoding), tb = encodeHdr(b, encoding);
      HdrTexel filtered;
      for (int c = 0; c < 4; ++c) filtered[c] = static_cast<std::uint8_t>(std::lround(0.5 * (ta[c] + tb[c])));
      const glm::vec3 truth = 0.5f * (decodeHdr(ta, encoding) + decodeHdr(tb, encoding));
      const float largest = std::max(truth.r, std::max(truth.g, truth.b));
      const glm::vec3 hardware = decodeHdr(filtered, encoding);
      // By hand: decode both, average, encode again (what the chain stores).
      const glm::vec3 byHand = decodeHdr(encodeHdr(truth, encoding), encoding);
      double e = 0.0, h = 0.0;
      for (int c = 0; c < 3; ++c) {
        e = std::max(e, double(std::abs(hardware[c] - truth[c]) / largest));
        h = std::max(h, double(std::abs(byHand[c] - truth[c]) / largest));
      }
      sum += e;
      worst = std::max(worst, e);
      byHandWorst = std::max(byHandWorst, h);
    }
    std::printf("  %-8s mean %.4f, worst %.3f; decoded by hand: worst %.5f\n", encoding.name().c_str(),
                sum / static_cast<double>(pairs.size()), worst, byHandWorst);
    EXPECT_GT(worst, 0.05) << encoding.name() << ": the hardware's filter would do";
    if (encoding.kind == kHdrColorEncoding.kind) {
      EXPECT_LT(byHandWorst, 1.0 / 500.0) << "half a step of a 9-bit mantissa";
    }
  }
}

// With no pixel above the threshold, the frame the viewer sees is the frame without bloom (within 1/255): the built-in
// scene with the threshold at its brightest channel, and, so that the test can fail, below it the frame changes.
TEST(Bloom, NoPixelAboveTheThresholdLeavesTheFrameUnchanged) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(160, 90);
  RenderSettings plain;
  plain.set("fxaa", "off");
  const test::RenderedImage reference =
      test::render(renderer, camera, plain, View::Final, test::retaining({"scene-color"}));
  const float brightest = test::brightestChannel(test::retainedHdr(renderer, "scene-color"));
  ASSERT_GT(brightest, 0.1f);
  std::printf("the built-in scene's brightest channel: %.4f\n", brightest);
  auto worstChange = [&](float threshold) {
    RenderSettings settings = plain;
    settings.set("bloom", "on");
    settings.of<BloomSettings>().threshold = threshold;
    settings.of<BloomSettings>().intensity = 1.0f;
    return test::worstByteDifference(test::render(renderer, camera, settings, View::Final), reference);
  };
  EXPECT_LE(worstChange(brightest), 1) << "threshold at the brightest channel, " << brightest;
  EXPECT_GT(worstChange(0.5f * brightest), 4) << "half of it: the frame must change";
}

// One pixel of 400 (linear) in a black 512 x 512 frame, on the diagonal at (256, 256). The glow (the output less the
// input) is symmetric about the diagonal, falls off with the distance, is centred on the pixel and carries
// intensity x (400 - T - K) of light.
TEST(Bloom, ASingleBrightPixelSpreadsIntoASymmetricFallingGlowCarryingTheStatedEnergy) {
  BloomEffect bloom(test::effectResources());
  const int side = 512, c = 256;
  const float value = 400.0f;
  Frame input = blank(side, side);
  input.at(c, c) = glm::vec3(value);
  const BloomSettings settings;  // threshold 1, knee 0.5, intensity 0.1, radius 0.75
  const Frame out = bloomed(bloom, settings, input);

  double energy = 0.0, mx = 0.0, my = 0.0, transposed = 0.0, mirrored = 0.0, peak = 0.0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const float glow = out.at(x, y).g - input.at(x, y).g;
      energy += glow;
      mx += glow * (x + 0.5);
      my += glow * (y + 0.5);
      if (!(x == c && y == c)) peak = std::max(peak, double(glow));
      transposed = std::max(transposed, double(std::abs(glow - (out.at(y, x).g - input.at(y, x).g))));
      const int mirror = 2 * c - x;
      if (mirror >= 0 && mirror < side && !(x == c && y == c) && !(mirror == c && y == c))
        mirrored = std::max(mirrored, double(std::abs(glow - out.at(mirror, y).g)));
    }
  const double expected = settings.intensity * (value - settings.threshold - settings.knee * settings.threshold);
  std::printf("glow energy %.3f (expected %.3f, %.2f %%), centroid (%.3f, %.3f) for the pixel's centre (%.1f, %.1f), "
              "largest glow beside the pixel %.4f, asymmetry: transpose %.5f, mirror about the pixel %.4f\n",
              energy, expected, 100.0 * energy / expected, mx / energy, my / energy, c + 0.5, c + 0.5, peak,
              transposed, mirrored);
  EXPECT_NEAR(energy / expected, 1.0, 0.02);
  EXPECT_NEAR(mx / energy, c + 0.5, 0.1);
  EXPECT_NEAR(my / energy, c + 0.5, 0.1);
  // About the diagonal: to one step of RGB9E5 at the peak (the tents filter along x, then y, rounding in between).
  EXPECT_LE(transposed, peak / 256.0) << "symmetric about the diagonal";
  // Left and right of the pixel along its row, relative to the glow there: each level's grid is centred on a corner
  // of 2^k x 2^k blocks, not on the pixel, so the two sides differ a little (measured: see docs/bloom-and-fog.md).
  std::printf("left/right asymmetry along the pixel's row, relative:");
  double worstAsymmetry = 0.0, meanAsymmetry = 0.0;
  for (int d = 1; d <= 64; ++d) {
    const double right = out.at(c + d, c).g, left = out.at(c - d, c).g;
    const double asymmetry = std::abs(right - left) / std::max(right, left);
    if (d <= 12) std::printf(" %d: %.3f", d, asymmetry);
    worstAsymmetry = std::max(worstAsymmetry, asymmetry);
    meanAsymmetry += asymmetry / 64.0;
  }
  std::printf("; 1 .. 64 pixels: mean %.3f, worst %.3f\n", meanAsymmetry, worstAsymmetry);
  EXPECT_LT(meanAsymmetry, 0.02);
  EXPECT_LT(worstAsymmetry, 0.25);
  // Falling off: the mean glow over rings of one pixel's width around the pixel's centre decreases outwards.
  std::vector<double> ring(side, 0.0);
  std::vector<int> count(side, 0);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int r = static_cast<int>(std::hypot(x - c, y - c));
      ring[static_cast<size_t>(r)] += out.at(x, y).g - input.at(x, y).g;
      ++count[static_cast<size_t>(r)];
    }
  int rises = 0;
  // (From radius 1: at the pixel itself the glow is below the step of RGB9E5 at 400.)
  for (int r = 2; r < 200; ++r) {
    const double inner = ring[size_t(r - 1)] / count[size_t(r - 1)], outer = ring[size_t(r)] / count[size_t(r)];
    if (outer > inner * 1.001) {
      ++rises;
      ADD_FAILURE() << "the glow rises from radius " << r - 1 << " (" << inner << ") to " << r << " (" << outer << ")";
    }
  }
  EXPECT_EQ(rises, 0);
  EXPECT_GT(ring[100] / count[100], 0.0) << "the glow reaches 100 pixels";
}

// The chain against its CPU mirror on a random HDR frame (the filters reaching past its edges clamp there): with
// radius 0 the glow is level 1 alone, so the frame plus the tent of the 13-tap filter of the thresholded frame
// (bloomDownsampleWeight, bloomThresholdScale, bloomUpsampleWeight, texels clamped to the edges). The prefilter runs
// in two passes (2 x 2 blocks on two grids, then 13 of them: bloom.frag) and must give the 13 taps' result. (An even
// size: on an odd one the blocks leave the frame's last column and row to the clamp at the edge, where the 13 taps
// read texel by texel spread level 1 over the whole frame: up to a frame pixel apart, at its far edge: BloomEffect.h.)
TEST(Bloom, TheChainWithRadiusZeroIsTheTentOfTheThirteenTapsOfTheThresholdedFrame) {
  BloomEffect bloom(test::effectResources());
  const int width = 62, height = 46;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> exponent(-4.0f, 3.0f);
  Frame input = blank(width, height);
  for (glm::vec3& c : input.pixels) {
    c = glm::vec3(std::exp2(exponent(random)), std::exp2(exponent(random)), std::exp2(exponent(random)));
    c = decodeHdr(encodeHdr(c));  // what the GPU reads
  }
  BloomSettings settings;
  settings.radius = 0.0f;
  settings.intensity = 1.0f;
  const Frame out = bloomed(bloom, settings, input);

  auto clampTo = [](int v, int n) { return std::clamp(v, 0, n - 1); };
  auto thresholded = [&](int x, int y) {
    const glm::vec3 c = input.at(clampTo(x, width), clampTo(y, height));
    return c * bloomThresholdScale(c, settings.threshold, settings.knee);
  };
  const int w1 = width / 2, h1 = height / 2;
  Frame level1 = blank(w1, h1);
  for (int p = 0; p < h1; ++p)
    for (int o = 0; o < w1; ++o)
      for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i)
          level1.at(o, p) += bloomDownsampleWeight(i, j) * thresholded(2 * o - 2 + i, 2 * p - 2 + j);
  double worst = 0.0, largestGlow = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float px = (float(x) + 0.5f) * float(w1) / float(width) - 0.5f;
      const float py = (float(y) + 0.5f) * float(h1) / float(height) - 0.5f;
      const float fx = std::floor(px), fy = std::floor(py);
      const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
      glm::vec3 glow(0.0f);
      for (int l = 0; l < 4; ++l)
        for (int k = 0; k < 4; ++k)
          glow += bloomUpsampleWeight(k, px - fx) * bloomUpsampleWeight(l, py - fy) *
                  level1.at(clampTo(ix - 1 + k, w1), clampTo(iy - 1 + l, h1));
      // RGB9E5 shares one exponent between the channels: each is as exact as a step of the largest.
      const glm::vec3 expected = input.at(x, y) + glow;
      const float largest = std::max(expected.r, std::max(expected.g, expected.b));
      for (int ch = 0; ch < 3; ++ch) {
        worst = std::max(worst, double(std::abs(out.at(x, y)[ch] - expected[ch]) / largest));
        largestGlow = std::max(largestGlow, double(glow[ch]));
      }
    }
  std::printf("%d x %d, radius 0: largest glow %.3f; the chain against its mirror: worst %.5f of the pixel's largest "
              "channel\n",
              width, height, largestGlow, worst);
  EXPECT_GT(largestGlow, 1.0) << "the glow is large enough to show an error";
  // Five RGB9E5 roundings (half a step of a 9-bit mantissa, at most 1/512 of the largest channel, each) between the
  // input and the output.
  EXPECT_LT(worst, 0.006);
}

// A smooth HDR gradient (2^-4 .. 2^6 along x, the same on every row) with everything blooming (threshold 0): every
// row of the result is monotonic (no band where it steps back), and close to the gradient's own glow.
TEST(Bloom, ASmoothHdrGradientStaysMonotonic) {
  BloomEffect bloom(test::effectResources());
  const int width = 512, height = 64;
  Frame input = blank(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float v = std::exp2(-4.0f + 10.0f * static_cast<float>(x) / static_cast<float>(width - 1));
      input.at(x, y) = glm::vec3(v, 0.5f * v, 0.25f * v);
    }
  for (float threshold : {0.0f, 1.0f}) {
    BloomSettings settings;
    settings.threshold = threshold;
    settings.intensity = 1.0f;
    const Frame out = bloomed(bloom, settings, input);
    int reversals = 0;
    double largestStepBack = 0.0;
    for (int y = 0; y < height; ++y)
      for (int x = 1; x < width; ++x)
        for (int ch = 0; ch < 3; ++ch) {
          const float back = out.at(x - 1, y)[ch] - out.at(x, y)[ch];
          if (back > 0.0f) {
            ++reversals;
            largestStepBack = std::max(largestStepBack, double(back / out.at(x, y)[ch]));
          }
        }
    std::printf("gradient, threshold %g: %d reversals, the largest %.5f of the value\n", threshold, reversals,
                largestStepBack);
    EXPECT_EQ(reversals, 0) << "threshold " << threshold;
    // The glow adds light: every pixel at least its input (as the GPU read it: encoded).
    for (int x = 0; x < width; ++x) EXPECT_GE(out.at(x, 7).r, decodeHdr(encodeHdr(input.at(x, 7))).r) << x;
  }
}

TEST(Bloom, RunsAfterTaaAndBeforeTheToneMappingWhichTheLightingThenLeavesAlone) {
  const std::vector<std::string>& passes = framePassNames();
  auto position = [&](const char* name) { return std::find(passes.begin(), passes.end(), name) - passes.begin(); };
  // The lighting, its shading count, then the points and lines (drawn lit, before the fog that covers them too).
  EXPECT_EQ(position("lines"), position("lighting") + 2);
  EXPECT_EQ(position("fog"), position("lines") + 1) << "fog right after the lit surfaces, lines and points";
  EXPECT_LT(position("taa"), position("bloom"));
  EXPECT_LT(position("bloom"), position("tonemap"));
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(96, 64);
  for (bool on : {false, true}) {
    RenderSettings settings;
    settings.set("bloom", on ? "on" : "off");
    test::render(renderer, camera, settings, View::Final);
    bool tonemapRuns = false, bloomRuns = false;
    std::string absorbedBy;
    for (const PlannedPass& pass : renderer.lastPlan().passes()) {
      if (!pass.live) continue;
      tonemapRuns |= pass.decl.name == "tonemap";
      bloomRuns |= pass.decl.name == "bloom";
      if (std::find(pass.absorbed.begin(), pass.absorbed.end(), "tonemap") != pass.absorbed.end())
        absorbedBy = pass.decl.name;
    }
    EXPECT_EQ(bloomRuns, on);
    EXPECT_FALSE(tonemapRuns) << "never a pass of its own";
    // Bloom reads the lit image: the tone curve runs in bloom's composite, a stage head (frame/Stage.h), instead.
    EXPECT_EQ(absorbedBy, on ? "bloom" : "lighting");
  }
}

// Fused into the composite or run as passes of their own (RendererOptions::fuseStages), the tone curve and the
// display stages give the same image but for the HDR encoding the fused program skips after the composite.
TEST(Bloom, TheToneCurveInTheCompositesPassGivesTheImageOfSeparatePasses) {
  RenderSettings settings;
  settings.set("bloom", "on");
  settings.set("bloom.threshold", "0.5");
  settings.set("vignette", "on");
  settings.set("fxaa", "off");
  settings.set("dither", "off");
  const test::ColorDifference d =
      test::FusedAndSeparate(makeBuiltinScene(), builtinSceneCamera(160, 90), settings).difference;
  std::printf("bloom with the tone curve and the vignette fused into its composite against separate passes: largest "
              "difference %d/255, mean %.4f/255\n",
              d.worst, d.mean);
  // One RGB9E5 quantisation fewer per pixel (test_dof.cpp's figures: a level in about a fifth of the channels).
  EXPECT_LE(d.worst, 1);
  EXPECT_LT(d.mean, 0.3);
}
