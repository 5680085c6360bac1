// Image-based ambient light (environment/Environment.h, shaders_es2/lib/environment.glsl): the spherical-harmonic
// projection against analytic coefficients, the irradiance against a numeric integration, the prefiltered specular
// levels against the brute-force integral, Karis's (A, B) fit against the numerically integrated split sum, the shader
// against its CPU mirror in both layouts (mip chain and atlas), and the white furnace through the whole frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <random>
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>

#include "TestSupport.h"
#include "effects/lighting/LightingEffect.h"
#include "encoding/HdrEncoding.h"
#include "encoding/NormalEncoding.h"
#include "environment/Environment.h"
#include "scene/BuiltinScene.h"
#include "scene/ImageIo.h"
#include "scene/Primitives.h"

#include <stb_image_write.h>

using namespace obscura;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Directions spread over the sphere (a Fibonacci lattice), poles and the u seam (-z .. +z through -x: u = 0 / 1 at +z).
std::vector<glm::vec3> testDirections(int count) {
  std::vector<glm::vec3> out = {{0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0.01f, 0.3f, 1.0f}, {-0.01f, -0.2f, 1.0f}};
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / count, r = std::sqrt(1.0 - y * y), phi = golden * i;
    out.emplace_back(static_cast<float>(r * std::cos(phi)), static_cast<float>(y),
                     static_cast<float>(r * std::sin(phi)));
  }
  for (glm::vec3& d : out) d = glm::normalize(d);
  return out;
}

float relativeError(const glm::vec3& got, const glm::vec3& expected) {
  const float largest = std::max(expected.r, std::max(expected.g, expected.b));
  float worst = 0.0f;
  for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[c] - expected[c]) / largest);
  return worst;
}

EnvironmentImage builtinSky() { return ProceduralSky{}.image(kEnvironmentWidth, kEnvironmentHeight); }

}  // namespace

// R&H 2001: a constant environment L has L_00 = 2 sqrt(pi) L and nothing else; L(w) = 1 + a.w adds
// L_1m = sqrt(4 pi / 3) a_m (Y_1m = sqrt(3 / 4 pi) (y, z, x)); the irradiance over pi is then 1 + (2/3) a.n exactly
// (the clamped cosine's A_1 = 2 pi / 3).
TEST(Environment, ShProjectionOfAConstantAndALinearEnvironmentGivesTheAnalyticCoefficients) {
  const glm::vec3 constant(0.7f, 1.0f, 2.5f);
  const ShIrradiance flat = ShIrradiance::project(uniformEnvironment(constant, 256, 128));
  // The midpoint rule over 128 rows integrates y^2 (in L_20 and L_22) to 2e-5 of L_00.
  EXPECT_NEAR(flat.coefficients[0].b, 2.5 * 2.0 * std::sqrt(kPi), 1e-4);
  for (int i = 1; i < 9; ++i) EXPECT_LT(glm::length(flat.coefficients[i]), 1e-4f * flat.coefficients[0].b) << i;
  for (const glm::vec3& n : testDirections(20)) EXPECT_LT(relativeError(flat.reflectedRadiance(n), constant), 1e-4f);

  const glm::vec3 a(0.3f, -0.2f, 0.5f);
  EnvironmentImage linear(256, 128);
  for (int y = 0; y < linear.height; ++y)
    for (int x = 0; x < linear.width; ++x) linear.at(x, y) = glm::vec3(1.0f + glm::dot(a, linear.texelDirection(x, y)));
  const ShIrradiance sh = ShIrradiance::project(linear);
  const double k1 = std::sqrt(4.0 * kPi / 3.0);
  EXPECT_NEAR(sh.coefficients[0].r, 2.0 * std::sqrt(kPi), 1e-4);
  // The midpoint rule over rows integrates y^2 and z^2 to 2e-5 relative at 128 rows.
  EXPECT_NEAR(sh.coefficients[1].r, k1 * a.y, 2e-4);  // L_1-1: y
  EXPECT_NEAR(sh.coefficients[2].r, k1 * a.z, 2e-4);  // L_10: z
  EXPECT_NEAR(sh.coefficients[3].r, k1 * a.x, 2e-4);  // L_11: x
  for (int i = 4; i < 9; ++i) EXPECT_NEAR(sh.coefficients[i].r, 0.0, 2e-4) << i;
  float worst = 0.0f;
  for (const glm::vec3& n : testDirections(40))
    worst = std::max(worst, std::abs(sh.reflectedRadiance(n).r - (1.0f + 2.0f / 3.0f * glm::dot(a, n))));
  std::printf("SH of 1 + a.w: worst irradiance / pi error %.2e (exact: 1 + 2/3 a.n)\n", worst);
  EXPECT_LT(worst, 2e-4f);
}

// The built-in sky's irradiance from nine coefficients against the cosine-weighted integral over every texel.
TEST(Environment, ShIrradianceOfTheSkyMatchesTheIntegratedIrradiance) {
  const EnvironmentImage sky = builtinSky();
  const ShIrradiance sh = ShIrradiance::project(sky);
  float worst = 0.0f, sum = 0.0f;
  const std::vector<glm::vec3> normals = testDirections(40);
  for (const glm::vec3& n : normals) {
    glm::dvec3 e(0.0);
    for (int y = 0; y < sky.height; ++y)
      for (int x = 0; x < sky.width; ++x)
        e += glm::dvec3(sky.at(x, y)) *
             (std::max(0.0, static_cast<double>(glm::dot(n, sky.texelDirection(x, y)))) * sky.texelSolidAngle(y));
    const glm::vec3 expected(e / kPi);
    const float error = relativeError(sh.reflectedRadiance(n), expected);
    worst = std::max(worst, error);
    sum += error;
  }
  std::printf("sky irradiance from 9 SH terms: worst %.4f, mean %.4f of the integral's brightest channel\n", worst,
              sum / static_cast<float>(normals.size()));
  // R&H's bound for order 2 is 9 % in the worst case for any lighting, 3 % for typical ones; the sun makes this one
  // harder than a plain gradient.
  EXPECT_LT(worst, 0.06f);
}

// P(r, roughness) as stored (RGB9E5, bilinear between texel centres) against the brute-force integral of
// L(l) D(h) (n.l) over every texel of the source, at directions between texel centres.
TEST(Environment, PrefilteredLevelsMatchTheBruteForceIntegral) {
  const EnvironmentImage sky = builtinSky();
  const auto start = std::chrono::steady_clock::now();
  const PrefilteredEnvironment prefiltered = PrefilteredEnvironment::of(sky);
  std::printf("prefiltering the 512 x 256 sky (default samples) took %.0f ms on this machine's CPU\n",
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  const std::vector<glm::vec3> directions = testDirections(24);
  for (int level = 1; level < kEnvironmentLevels; ++level) {
    const float roughness = environmentLevelRoughness(level);
    float worst = 0.0f, sum = 0.0f;
    for (const glm::vec3& r : directions) {
      const float error = relativeError(prefiltered.sample(r, roughness), prefilterReference(sky, r, roughness));
      worst = std::max(worst, error);
      sum += error;
    }
    std::printf("prefiltered roughness %.1f (%d x %d): worst %.4f, mean %.4f of the reference's brightest channel\n",
                roughness, prefiltered.levels[level].width, prefiltered.levels[level].height, worst,
                sum / static_cast<float>(directions.size()));
    EXPECT_LT(worst, level == 1 ? 0.08f : 0.04f) << "roughness " << roughness;
  }
  // Roughness 0 is the environment itself.
  for (const glm::vec3& r : directions)
    EXPECT_LT(relativeError(prefiltered.sample(r, 0.0f), sky.radiance(r)), 2.0f / 512.0f);
}

// At roughness 1 GGX's D is 1 / pi for every half vector, so the prefiltered radiance (n = v = r) is the
// cosine-weighted mean of the radiance about r: E(r) / pi, which the nine spherical-harmonic terms give. The deferred
// lighting, which shades roughness 1 alone, reads it there instead of level 5 (shaders_es2/lighting/lighting.frag):
// both against the brute-force integral, at directions between texel centres.
TEST(Environment, AtRoughnessOneThePrefilteredRadianceIsTheIrradiance) {
  for (double nDotH : {0.0, 0.3, 0.7, 1.0}) EXPECT_NEAR(ggxDistribution(nDotH, 1.0), 1.0 / kPi, 1e-12) << nDotH;
  const EnvironmentImage sky = builtinSky();
  const ShIrradiance sh = ShIrradiance::project(sky);
  const PrefilteredEnvironment prefiltered = PrefilteredEnvironment::of(sky, 1024);
  float worstSh = 0.0f, worstLevel = 0.0f, sumSh = 0.0f, sumLevel = 0.0f;
  const std::vector<glm::vec3> directions = testDirections(24);
  for (const glm::vec3& r : directions) {
    const glm::vec3 reference = prefilterReference(sky, r, 1.0);
    const float errorSh = relativeError(sh.reflectedRadiance(r), reference);
    const float errorLevel = relativeError(prefiltered.sample(r, 1.0f), reference);
    worstSh = std::max(worstSh, errorSh);
    worstLevel = std::max(worstLevel, errorLevel);
    sumSh += errorSh;
    sumLevel += errorLevel;
  }
  const float count = static_cast<float>(directions.size());
  std::printf("roughness 1 against the integral: nine SH terms worst %.4f, mean %.4f; level 5 worst %.4f, mean %.4f "
              "(of the reference's brightest channel)\n",
              worstSh, sumSh / count, worstLevel, sumLevel / count);
  // ShIrradianceOfTheSkyMatchesTheIntegratedIrradiance's bound: R&H's order-2 error with the sun.
  EXPECT_LT(worstSh, 0.06f);
}

// Why the shader filters by hand: the hardware's bilinear filter over RGB9E5 bytes, at the midpoint of two
// neighbouring texels of the prefiltered sky, against the mean of the decoded texels.
TEST(Environment, HardwareFilteringOfTheEncodedTexelsWouldBeWrong) {
  const PrefilteredEnvironment prefiltered = PrefilteredEnvironment::of(builtinSky(), 256);
  double sum = 0.0, worst = 0.0;
  int count = 0, wrong = 0;
  for (int level = 0; level < kEnvironmentLevels; ++level) {
    const std::vector<HdrTexel> texels = prefiltered.encodedLevel(level);
    const int w = prefiltered.levels[level].width;
    for (size_t i = 0; i + 1 < texels.size(); ++i) {
      if (static_cast<int>((i + 1) % static_cast<size_t>(w)) == 0) continue;
      HdrTexel blended;
      for (int c = 0; c < 4; ++c) blended[c] = static_cast<std::uint8_t>((texels[i][c] + texels[i + 1][c] + 1) / 2);
      const glm::vec3 expected = 0.5f * (decodeHdr(texels[i]) + decodeHdr(texels[i + 1]));
      const double error = relativeError(decodeHdr(blended), expected);
      sum += error;
      worst = std::max(worst, error);
      wrong += error > 0.01;
      ++count;
    }
  }
  std::printf("hardware bilinear over RGB9E5 texels of the prefiltered sky: mean %.4f, worst %.3f relative error; "
              "%d of %d neighbour pairs off by more than 1 %%\n",
              sum / count, worst, wrong, count);
  // Right where neighbours share an exponent, off by up to the whole value where it changes: seams along every
  // exponent boundary of the smooth sky.
  EXPECT_GT(worst, 0.25) << "if the bytes blended harmlessly, the hand filter would cost for nothing";
  EXPECT_GT(wrong, 100);
}

// The two file forms: a Radiance .hdr (stb_image's loader) and a PNG of RGBE bytes, both of the sky, against it.
TEST(Environment, LoadsRadianceHdrAndRgbePng) {
  const EnvironmentImage sky = ProceduralSky{}.image(64, 32);
  std::vector<float> rgb;
  Image png;
  png.width = sky.width;
  png.height = sky.height;
  for (const glm::vec3& c : sky.texels) {
    rgb.insert(rgb.end(), {c.r, c.g, c.b});
    const HdrTexel t = encodeHdr(c, HdrEncoding{HdrEncodingKind::Rgbe, 0.0f});
    png.rgba.insert(png.rgba.end(), t.begin(), t.end());
  }
  const std::string hdrPath = test::tempPath("sky.hdr"), pngPath = test::tempPath("sky-rgbe.png");
  ASSERT_TRUE(stbi_write_hdr(hdrPath.c_str(), sky.width, sky.height, 3, rgb.data()));
  writePng(pngPath, png);
  for (const std::string& path : {hdrPath, pngPath}) {
    const EnvironmentImage loaded = loadEnvironmentImage(path);
    ASSERT_EQ(loaded.width, sky.width) << path;
    ASSERT_EQ(loaded.height, sky.height) << path;
    float worst = 0.0f;
    for (size_t i = 0; i < sky.texels.size(); ++i)
      worst = std::max(worst, relativeError(loaded.texels[i], sky.texels[i]));
    // RGBE keeps 8 bits of the brightest channel: a step of 1/128 .. 1/256 of it.
    EXPECT_LT(worst, 1.0f / 120.0f) << path;
  }
  EXPECT_THROW(loadEnvironmentImage(test::tempPath("no-such.hdr")), InputError);
}

// The split sum's (A, B) as the shader reads them (the 32 x 32 table, bilinear) and Karis 2014's analytic fit, against
// the integral (Karis 2013) between the table's texel centres, over roughness 0 .. 1 and n.v 0.05 .. 1.
TEST(Environment, TheBrdfTableIsCloseToTheIntegratedSplitSum) {
  struct Worst {
    float a = 0.0f, b = 0.0f, dielectric = 0.0f, metal = 0.0f;
    void add(const glm::vec2& got, const glm::vec2& expected) {
      a = std::max(a, std::abs(got.x - expected.x));
      b = std::max(b, std::abs(got.y - expected.y));
      dielectric = std::max(dielectric, std::abs(0.04f * (got.x - expected.x) + got.y - expected.y));
      metal = std::max(metal, std::abs(0.9f * (got.x - expected.x) + got.y - expected.y));
    }
  } table, fit;
  for (int i = 0; i <= 20; ++i)
    for (int j = 1; j <= 40; ++j) {
      const float roughness = 0.05f * static_cast<float>(i), nDotV = 0.025f * static_cast<float>(j);
      if (nDotV < 0.05f) continue;
      const glm::vec2 integrated = envBrdfIntegrated(roughness, nDotV);
      table.add(environmentBrdf(roughness, nDotV), integrated);
      fit.add(envBrdfApprox(roughness, nDotV), integrated);
    }
  for (const auto& [name, w] : {std::make_pair("table", table), std::make_pair("EnvBRDFApprox", fit)})
    std::printf("(A, B) %s against the integral: worst |A| %.4f, |B| %.4f; reflectance F0 0.04 %.4f, F0 0.9 %.4f\n",
                name, w.a, w.b, w.dielectric, w.metal);
  EXPECT_LT(table.a, 0.03f);
  EXPECT_LT(table.b, 0.03f);
  EXPECT_LT(table.dielectric, 0.03f);
  EXPECT_GT(fit.metal, 2.0f * table.metal) << "the fit would do: no table, no texture unit";
  // The integral itself: a mirror seen head-on reflects F0 (A = 1, B = 0).
  const glm::vec2 mirror = envBrdfIntegrated(0.0f, 1.0f);
  EXPECT_NEAR(mirror.x, 1.0f, 1e-3f);
  EXPECT_NEAR(mirror.y, 0.0f, 1e-3f);
}

// The white furnace on the CPU: radiance 1 everywhere, a white rough dielectric reflects 1.
TEST(Environment, AWhiteDielectricInAWhiteFurnaceReflectsOne) {
  const EnvironmentImage furnace = uniformEnvironment(glm::vec3(1.0f));
  const ShIrradiance sh = ShIrradiance::project(furnace);
  const PrefilteredEnvironment specular = PrefilteredEnvironment::of(furnace, 256);
  float worst = 0.0f;
  for (float roughness : {0.3f, 0.6f, 1.0f})
    for (const glm::vec3& n : testDirections(12))
      for (float nDotV : {0.1f, 0.5f, 1.0f}) {
        const glm::vec3 other = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 side = glm::normalize(glm::cross(n, other));
        const glm::vec3 v = nDotV * n + std::sqrt(1.0f - nDotV * nDotV) * side;
        const glm::vec3 c = ambientLightMirror(sh, specular, n, v, glm::vec3(1.0f), glm::vec3(0.04f), roughness);
        worst = std::max(worst, relativeError(c, glm::vec3(1.0f)));
      }
  std::printf("white furnace (CPU mirror): worst |c - 1| %.2e\n", worst);
  EXPECT_LT(worst, 2e-3f);
}

namespace {

// environmentSpecular() on the GPU, one point per (direction, roughness), its result RGB9E5-encoded.
std::vector<glm::vec3> gpuSpecular(const GpuEnvironment& environment, const std::vector<glm::vec4>& queries) {
  auto defines = GpuEnvironment::shaderDefines(environment.layout(), environment.filteredFrom());
  std::vector<std::string> extensions;
  if (environment.layout() == EnvironmentLayout::MipChain) extensions.push_back("GL_EXT_shader_texture_lod");
  const gl::Program program("environment-specular[" + std::string(environmentLayoutName(environment.layout())) + "]",
                            ShaderLibrary::composeText(test::kTwoValuePointVertex, defines, {}),
                            ShaderLibrary::composeText(R"(
#include "lib/precision.glsl"
#include "lib/hdr.glsl"
#include "lib/environment.glsl"
varying vec4 v_first;
void main() { gl_FragColor = encodeHdr(environmentSpecular(v_first.xyz, v_first.w)); }
)",
                                                       defines, extensions));
  program.use();
  // Units 3 and 4, not 0: drawPoints makes its target on unit 0 (and unbinds every unit after drawing).
  glActiveTexture(GL_TEXTURE3);
  glBindTexture(GL_TEXTURE_2D, environment.texture());
  glActiveTexture(GL_TEXTURE4);
  glBindTexture(GL_TEXTURE_2D, environment.filteredTexture());
  glActiveTexture(GL_TEXTURE0);
  gl::Program::set(program.uniform("u_environment"), 3);
  gl::Program::set(program.optionalUniform("u_environmentFiltered"), 4);
  gl::Program::set(program.optionalUniform("u_environmentFilteredScale"), environment.filteredScale());
  gl::Program::set(program.uniform("u_environmentIntensity"), 1.0f);
  const std::vector<std::uint8_t> bytes = test::drawPoints(program, queries);
  std::vector<glm::vec3> out;
  for (size_t i = 0; i < queries.size(); ++i)
    out.push_back(decodeHdr(HdrTexel{bytes[4 * i], bytes[4 * i + 1], bytes[4 * i + 2], bytes[4 * i + 3]}));
  return out;
}

}  // namespace

// The shader against its CPU mirror, in the mip chain (where the context has EXT_shader_texture_lod) and in the atlas
// (the fallback, forced), and the two layouts against each other; with every level filtered by hand, and with levels
// 2 .. 5 read through the hardware's filter (RGBM).
TEST(Environment, TheShaderMatchesItsMirrorInBothLayouts) {
  test::context();
  const EnvironmentImage sky = builtinSky();
  const ShIrradiance sh = ShIrradiance::project(sky);
  std::vector<glm::vec4> queries;
  for (const glm::vec3& d : testDirections(200))
    for (float roughness : {0.0f, 0.1f, 0.2f, 0.3f, 0.5f, 0.73f, 1.0f}) queries.emplace_back(d, roughness);
  const EnvironmentLayout lodLayout = GpuEnvironment::layoutFor(test::context().caps(), EnvironmentLayout::MipChain);
  if (lodLayout != EnvironmentLayout::MipChain)
    std::printf("this context lacks EXT_shader_texture_lod: the mip chain is not tested here\n");
  for (EnvironmentFiltering filtering : {EnvironmentFiltering::ByHand, EnvironmentFiltering::Hardware}) {
    const bool byHand = filtering == EnvironmentFiltering::ByHand;
    const PrefilteredEnvironment prefiltered = PrefilteredEnvironment::of(sky, 256, filtering);
    ASSERT_EQ(prefiltered.filteredFrom(), byHand ? kEnvironmentLevels : kEnvironmentFilteredLevel);
    const GpuEnvironment atlas(EnvironmentLayout::Atlas, prefiltered, sh);
    const GpuEnvironment mips(lodLayout, prefiltered, sh);
    const std::vector<glm::vec3> fromAtlas = gpuSpecular(atlas, queries), fromMips = gpuSpecular(mips, queries);
    float worstAtlas = 0.0f, worstMips = 0.0f, worstBetween = 0.0f;
    for (size_t i = 0; i < queries.size(); ++i) {
      const glm::vec3 expected = prefiltered.sample(glm::vec3(queries[i]), queries[i].w);
      worstAtlas = std::max(worstAtlas, relativeError(fromAtlas[i], expected));
      worstMips = std::max(worstMips, relativeError(fromMips[i], expected));
      worstBetween = std::max(worstBetween, relativeError(fromMips[i], fromAtlas[i]));
    }
    std::printf("environmentSpecular, %s, %zu queries: atlas %.5f, %s %.5f of the mirror's brightest channel; "
                "between them %.5f\n",
                byHand ? "every level by hand" : "levels 2 .. 5 filtered", queries.size(), worstAtlas,
                environmentLayoutName(lodLayout), worstMips, worstBetween);
    // By hand: RGB9E5's half step (1/1024) on the result, plus the GPU's atan and acos placing the bilinear weights
    // differently. Filtered: llvmpipe's filter keeps 8 bits of each channel it blends, which the mirror does not
    // (GPUs keep more): half a step of RGBM's colour and of its multiplier, 1 % where the multiplier is about 100.
    const float bound = byHand ? 4.0f / 512.0f : 0.015f;
    EXPECT_LT(worstAtlas, bound);
    EXPECT_LT(worstMips, bound);
    EXPECT_LT(worstBetween, byHand ? 2.0f / 512.0f : 0.015f);
  }
}

// The half-float atlas (the default where the context filters half floats) against its mirror, and against the levels
// filtered by hand in RGB9E5: the same levels, one fetch through the hardware's filter.
TEST(Environment, TheHalfFloatAtlasMatchesItsMirrorAndTheLevelsFilteredByHand) {
  const gl::GlCaps& caps = test::context().caps();
  const EnvironmentLayout layout = GpuEnvironment::layoutFor(caps, std::nullopt);
  if (!caps.textureHalfFloatLinear) GTEST_SKIP() << "this context does not filter half-float textures";
  ASSERT_EQ(layout, EnvironmentLayout::HalfFloatAtlas);
  // Forcing the RGB9E5 layouts takes them (the fallback stays reachable).
  EXPECT_EQ(GpuEnvironment::layoutFor(caps, EnvironmentLayout::Atlas), EnvironmentLayout::Atlas);
  const EnvironmentImage sky = builtinSky();
  const ShIrradiance sh = ShIrradiance::project(sky);
  std::vector<glm::vec4> queries;
  for (const glm::vec3& d : testDirections(200))
    for (float roughness : {0.0f, 0.1f, 0.2f, 0.3f, 0.5f, 0.73f, 1.0f}) queries.emplace_back(d, roughness);
  const PrefilteredEnvironment prefiltered = PrefilteredEnvironment::of(sky, 256, EnvironmentFiltering::ByHand);
  const GpuEnvironment half(EnvironmentLayout::HalfFloatAtlas, prefiltered, sh, caps.desktopGl);
  const GpuEnvironment byHand(EnvironmentLayout::Atlas, prefiltered, sh);
  EXPECT_EQ(half.filteredFrom(), kEnvironmentLevels);
  const std::vector<glm::vec3> fromHalf = gpuSpecular(half, queries), fromHand = gpuSpecular(byHand, queries);
  float worstMirror = 0.0f, worstBetween = 0.0f, worstMirrors = 0.0f;
  for (size_t i = 0; i < queries.size(); ++i) {
    const glm::vec3 d(queries[i]);
    const glm::vec3 expected = prefiltered.sample(d, queries[i].w, EnvironmentLayout::HalfFloatAtlas);
    worstMirror = std::max(worstMirror, relativeError(fromHalf[i], expected));
    worstBetween = std::max(worstBetween, relativeError(fromHalf[i], fromHand[i]));
    worstMirrors = std::max(worstMirrors, relativeError(expected, prefiltered.sample(d, queries[i].w)));
  }
  std::printf("environmentSpecular, half-float atlas, %zu queries: %.5f of the mirror's brightest channel; against "
              "RGB9E5 by hand %.5f (the mirrors %.5f)\n",
              queries.size(), worstMirror, worstBetween, worstMirrors);
  // The result's RGB9E5 half step (1/1024), the GPU's atan and acos placing the weights differently, and the
  // filter's own weights (8 fractional bits on llvmpipe, where the mirror's are exact).
  EXPECT_LT(worstMirror, 4.0f / 512.0f);
  // Against RGB9E5: both roundings (1/1024 and 1/4096 of the value) and both filters.
  EXPECT_LT(worstBetween, 6.0f / 512.0f);
  EXPECT_LT(worstMirrors, 2.0f / 512.0f);
}

// The background's cube map (Environment.h: skyCubeFaces): the GPU's textureCube against its mirror, the mirror's
// faces against GL's face table, and the cube against the equirectangular level 0 it resamples.
TEST(Environment, TheSkyCubeMatchesItsMirrorAndLevelZero) {
  const gl::GlCaps& caps = test::context().caps();
  if (!caps.textureHalfFloatLinear) GTEST_SKIP() << "this context does not filter half-float textures";
  const EnvironmentImage sky = builtinSky();
  const PrefilteredEnvironment prefiltered = PrefilteredEnvironment::of(sky, 256, EnvironmentFiltering::ByHand);
  const auto start = std::chrono::steady_clock::now();
  const std::array<std::vector<glm::vec3>, 6> faces = skyCubeFaces(prefiltered);
  const double facesMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const GpuEnvironment half(EnvironmentLayout::HalfFloatAtlas, prefiltered, ShIrradiance::project(sky),
                            caps.desktopGl);
  ASSERT_NE(half.skyTexture(), 0u);
  // Each texel centre's direction finds that texel (the mirror's face table is GL's, as the faces were made).
  for (int face = 0; face < 6; ++face)
    for (glm::ivec2 texel : {glm::ivec2(0, 0), glm::ivec2(17, kEnvironmentSkyFace - 50),
                             glm::ivec2(kEnvironmentSkyFace - 1, 3),
                             glm::ivec2(kEnvironmentSkyFace / 2, kEnvironmentSkyFace - 1)}) {
      const glm::vec3 d = cubeFaceDirection(face, (glm::vec2(texel) + 0.5f) / float(kEnvironmentSkyFace));
      EXPECT_EQ(skyCubeSample(faces, d),
                faces[size_t(face)][size_t(texel.y) * kEnvironmentSkyFace + size_t(texel.x)]) << face;
    }
  // The GPU at directions of every length (the vertex stage's ray is not unit).
  std::mt19937 random(5);
  std::uniform_real_distribution<float> length(0.05f, 20.0f);
  std::vector<glm::vec4> queries;
  for (const glm::vec3& d : testDirections(2000)) queries.emplace_back(d * length(random), 0.0f);
  const gl::Program program("sky-cube", ShaderLibrary::composeText(test::kTwoValuePointVertex, {}, {}),
                            ShaderLibrary::composeText(R"(
#include "lib/precision.glsl"
#include "lib/hdr.glsl"
uniform highp samplerCube u_sky;
varying vec4 v_first;
void main() { gl_FragColor = encodeHdr(textureCube(u_sky, v_first.xyz).rgb); }
)",
                                                       {}, {}));
  program.use();
  glActiveTexture(GL_TEXTURE3);  // not unit 0: drawPoints makes its target there
  glBindTexture(GL_TEXTURE_CUBE_MAP, half.skyTexture());
  glActiveTexture(GL_TEXTURE0);
  gl::Program::set(program.uniform("u_sky"), 3);
  const std::vector<std::uint8_t> bytes = test::drawPoints(program, queries);
  glActiveTexture(GL_TEXTURE3);
  glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
  glActiveTexture(GL_TEXTURE0);
  float worstMirror = 0.0f;
  for (size_t i = 0; i < queries.size(); ++i) {
    const glm::vec3 gpu = decodeHdr(HdrTexel{bytes[4 * i], bytes[4 * i + 1], bytes[4 * i + 2], bytes[4 * i + 3]});
    worstMirror = std::max(worstMirror, relativeError(gpu, skyCubeSample(faces, glm::vec3(queries[i]))));
  }
  // The cube against level 0 through the half-float atlas, as the background read it before (the mirror, 100,000
  // directions): the resampling's error, largest where the sun's disc has an edge.
  std::vector<float> errors;
  for (const glm::vec3& d : testDirections(100000))
    errors.push_back(
        relativeError(skyCubeSample(faces, d), prefiltered.sample(d, 0.0f, EnvironmentLayout::HalfFloatAtlas)));
  std::sort(errors.begin(), errors.end());
  const float median = errors[errors.size() / 2], p99 = errors[errors.size() * 99 / 100], worst = errors.back();
  const double overFivePercent =
      double(errors.end() - std::upper_bound(errors.begin(), errors.end(), 0.05f)) / double(errors.size());
  std::printf("sky cube: %d x %d x 6 texels made in %.0f ms; GPU against the mirror %.5f of the brightest channel "
              "(%zu directions); against level 0: median %.5f, 99th percentile %.5f, worst %.4f, over 5 %%: %.3f %% of "
              "directions\n",
              kEnvironmentSkyFace, kEnvironmentSkyFace, facesMs, worstMirror, queries.size(), median, p99, worst,
              100.0 * overFivePercent);
  // The output's RGB9E5 half step (1/1024) and the filter's weights (8 fractional bits on llvmpipe).
  EXPECT_LT(worstMirror, 4.0f / 512.0f);
  // Where the sky is smooth the two agree to a few ten-thousandths; the worst is beside the sun's disc, 40 times the
  // sky's brightness, where resampling spreads the disc's edge by part of a texel: a pixel just outside it takes
  // some of its light (the error is relative to the darker sky there).
  EXPECT_LT(median, 0.0005f);
  EXPECT_LT(p99, 0.01f);
  EXPECT_LT(overFivePercent, 0.002);
}

namespace {

// One pixel of a frame in the white furnace: its HDR colour, and whether the G-buffer holds the far depth there.
struct FurnacePixel {
  glm::vec3 color;
  bool background;
};
// The scene in the white furnace (the uniform environment of radiance 1 alone: AO, FXAA and the sun off) in lighting
// tier `quality`, every pixel.
std::vector<FurnacePixel> renderFurnace(Renderer& renderer, const Camera& camera, const char* quality) {
  RenderSettings settings;
  settings.set("ao", "off");
  settings.set("fxaa", "off");
  settings.set("lighting.environment", "uniform");
  settings.set("lighting.sun-intensity", "0");
  settings.set("lighting.quality", quality);
  test::render(renderer, camera, settings, View::Final, test::retaining({"scene-color", "gbuffer"}));
  const std::vector<std::uint8_t> color = renderer.retained("scene-color").readRgba();
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  std::vector<FurnacePixel> pixels;
  for (size_t i = 0; i < color.size(); i += 4)
    pixels.push_back({decodeHdr(HdrTexel{color[i], color[i + 1], color[i + 2], color[i + 3]}),
                      gbuffer[i + 2] == 255 && gbuffer[i + 3] == 255});
  return pixels;
}

// A white sphere and a white floor under the uniform environment of radiance 1 (AO off, the sun off): each lit pixel
// must be 1, and the background 1. Returns the worst error, and counts the pixels.
float furnaceError(const RendererOptions& options, int& lit, int& background, const char* quality = "medium") {
  Scene scene = test::sceneOf({makeSphere(1.0f, 48, 24), test::makeRectangle({-6, -1, 6}, {12, 0, 0}, {0, 0, -12})});
  Renderer renderer = test::makeRenderer(options);
  renderer.setScene(std::move(scene));
  const Camera camera = test::makeCamera({0.5f, 1.5f, 4.0f}, {0, 0, 0}, 96, 64);
  float worst = 0.0f;
  lit = background = 0;
  for (const FurnacePixel& pixel : renderFurnace(renderer, camera, quality)) {
    worst = std::max(worst, relativeError(pixel.color, glm::vec3(1.0f)));
    (pixel.background ? background : lit) += 1;
  }
  return worst;
}

}  // namespace

// The white furnace through the frame: deferred and forward, the half-float atlas, the mip chain and the atlas, and
// every tier (each keeps the energy its specular lobe takes from the diffuse: the low tier's irradiance towards r, the
// high tier's multiple scattering).
TEST(Environment, TheWhiteFurnaceGivesOneThroughTheFrame) {
  for (const char* quality : {"medium", "low", "high"})
    for (bool drawBuffers : {true, false})
      for (EnvironmentLayout layout :
           {EnvironmentLayout::HalfFloatAtlas, EnvironmentLayout::MipChain, EnvironmentLayout::Atlas}) {
        if (std::string(quality) != "medium" && layout == EnvironmentLayout::MipChain) continue;
        RendererOptions options;
        options.allowDrawBuffers = drawBuffers;
        options.environmentLayout = layout;
        int lit = 0, background = 0;
        const float worst = furnaceError(options, lit, background, quality);
        const EnvironmentLayout used = GpuEnvironment::layoutFor(test::context().caps(), layout);
        std::printf("white furnace, %s tier, %s, %s: worst |ambient - 1| %.4f over %d lit and %d background pixels\n",
                    quality, drawBuffers ? "deferred" : "forward", environmentLayoutName(used), worst, lit,
                    background);
        EXPECT_GT(lit, 1000);
        EXPECT_GT(background, 200);
        // The G-buffer's 8-bit octahedral normal (0.5 x 1 % at most) and RGB9E5 (or half floats).
        EXPECT_LT(worst, 0.01f) << quality << ", " << (drawBuffers ? "deferred" : "forward") << " "
                                << environmentLayoutName(layout);
      }
}

// The intensity scales the whole environment, the background included.
TEST(Environment, TheIntensityScalesAmbientAndBackground) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(64, 48);
  RenderSettings settings;
  settings.set("ao", "off");
  auto mean = [&](const char* intensity) {
    settings.set("lighting.environment-intensity", intensity);
    test::render(renderer, camera, settings, View::Final, test::retaining({"scene-color"}));
    const std::vector<std::uint8_t> c = renderer.retained("scene-color").readRgba();
    double sum = 0.0;
    for (size_t i = 0; i < c.size(); i += 4) sum += decodeHdr(HdrTexel{c[i], c[i + 1], c[i + 2], c[i + 3]}).g;
    return sum;
  };
  settings.set("bloom", "off");
  const double one = mean("1"), two = mean("2"), none = mean("0");
  EXPECT_GT(two - one, 0.5 * (one - none)) << "doubling the environment adds its share again";
  EXPECT_NEAR(two - one, one - none, 0.01 * (one - none));
}

// The built-in sky's sun stands where lighting.sun-* put the direct light: a narrow camera looking along
// directionToSun() sees the sun's disc (radiance 40, 1.5 degrees across) centred, for the default sun, a sun turned
// in azimuth (the sky turned about the vertical) and suns raised or lowered (the sky made again); the default sun's
// place is then empty.
TEST(Environment, TheSkysSunFollowsTheSunParameters) {
  Renderer renderer = test::makeRenderer();
  // Something to draw, out of sight below the camera.
  renderer.setScene(test::sceneOf({test::makeRectangle({-1, -50, -1}, {2, 0, 0}, {0, 0, 2})}));
  const int side = 65;
  auto disc = [&](const char* elevation, const char* azimuth, const glm::vec3& lookAlong) {
    RenderSettings settings;
    settings.set("ao", "off");
    settings.set("bloom", "off");
    settings.set("lighting.sun-elevation", elevation);
    settings.set("lighting.sun-azimuth", azimuth);
    const Camera camera = test::makeCamera({0, 0, 0}, lookAlong, side, side, 0.1f, 100.0f, 10.0f);
    test::render(renderer, camera, settings, View::Final, test::retaining({"scene-color"}));
    const std::vector<std::uint8_t> c = renderer.retained("scene-color").readRgba();
    glm::dvec2 sum(0.0);
    int count = 0;
    for (int row = 0; row < side; ++row)
      for (int x = 0; x < side; ++x) {
        const size_t i = (static_cast<size_t>(row) * side + x) * 4;
        if (decodeHdr(HdrTexel{c[i], c[i + 1], c[i + 2], c[i + 3]}).g > 10.0f) {
          sum += glm::dvec2(x + 0.5, row + 0.5);
          ++count;
        }
      }
    return std::make_pair(count, count ? sum / static_cast<double>(count) : glm::dvec2(-1.0));
  };
  struct Case {
    const char *elevation, *azimuth;
  };
  const LightingSettings defaults;
  for (const Case& c : {Case{"54.525961", "52.125016"}, Case{"54.525961", "140"}, Case{"20", "52.125016"},
                        Case{"30", "-100"}}) {
    LightingSettings sun;
    sun.sunElevation = std::stof(c.elevation);
    sun.sunAzimuth = std::stof(c.azimuth);
    const auto [count, centre] = disc(c.elevation, c.azimuth, sun.directionToSun());
    std::printf("sun at elevation %s, azimuth %s: %d disc pixels centred at (%.2f, %.2f) of (%.1f, %.1f)\n",
                c.elevation, c.azimuth, count, centre.x, centre.y, side / 2.0, side / 2.0);
    // 3 degrees across in a 10-degree frame of 65 pixels: about 19 pixels across, 280 in all.
    EXPECT_GT(count, 200) << c.elevation << " " << c.azimuth;
    EXPECT_LT(glm::length(centre - glm::dvec2(side / 2.0)), 0.5) << c.elevation << " " << c.azimuth;
    if (sun.sunAzimuth != defaults.sunAzimuth || sun.sunElevation != defaults.sunElevation) {
      EXPECT_EQ(disc(c.elevation, c.azimuth, defaults.directionToSun()).first, 0) << "the default sun's place";
    }
  }
}

// The environment cache (environment/EnvironmentCache.h), through the frame: a file that cannot be read fails the
// frame that first asks for it, once; the environment in use stays (the same image), and later frames asking for the
// same file draw without an error, until another environment is asked for. The Renderer prepares the environment
// before planning (Effect::prepare), so a changed environment shows in the very frame that asks for it.
TEST(Environment, AnUnreadableFileFailsOnceAndTheEnvironmentInUseStays) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene());
  const Camera camera = builtinSceneCamera(48, 32);
  RenderSettings settings;
  settings.set("ao", "off");
  auto frame = [&] {
    test::render(renderer, camera, settings, View::Final, test::retaining({"scene-color"}));
    return renderer.retained("scene-color").readRgba();
  };
  settings.set("lighting.environment", "uniform");
  const std::vector<std::uint8_t> furnace = frame();
  settings.set("lighting.environment", test::tempPath("no-such-environment.hdr"));
  EXPECT_THROW(frame(), InputError);
  EXPECT_EQ(frame(), furnace) << "the furnace stays in use, and the same name is not tried again";
  settings.set("lighting.environment", "sky");
  const std::vector<std::uint8_t> sky = frame();
  EXPECT_NE(sky, furnace) << "the sky in the frame that asked for it";
  settings.set("lighting.environment", test::tempPath("no-such-environment.hdr"));
  EXPECT_THROW(frame(), InputError) << "asked for again after another environment";
  EXPECT_EQ(frame(), sky);
}

// The high tier's multiple scattering (Fdez-Aguera 2019) restores what the single-scattering lobe loses: a white rough
// metal in the white furnace (F0 1: every bounce reflects) reflects 1 in the high tier, where the medium tier's split
// sum reflects only A + B, which falls well short at roughness 1; at roughness 0.1 both are close to 1.
TEST(Environment, TheHighTierKeepsTheEnergyOfAWhiteRoughMetalInTheFurnace) {
  const int width = 96, height = 64;
  for (float roughness : {1.0f, 0.1f}) {
    Scene scene;
    Mesh sphere = makeSphere(1.0f, 48, 24);
    const int material = test::addMaterial(scene, glm::vec3(1.0f));
    scene.materials[static_cast<size_t>(material)].metallicFactor = 1.0f;
    scene.materials[static_cast<size_t>(material)].roughnessFactor = roughness;
    sphere.material = material;
    scene.meshes.push_back(std::move(sphere));
    scene.instances.push_back({static_cast<int>(scene.meshes.size()) - 1, glm::mat4(1.0f)});
    Renderer renderer = test::makeRenderer();
    renderer.setScene(std::move(scene));
    const Camera camera = test::makeCamera({0.0f, 0.5f, 3.5f}, {0, 0, 0}, width, height);
    std::map<std::string, std::pair<float, float>> range;  // tier -> (least, most) over the sphere
    for (const char* quality : {"medium", "high"}) {
      float least = 10.0f, most = 0.0f;
      for (const FurnacePixel& pixel : renderFurnace(renderer, camera, quality)) {
        if (pixel.background) continue;
        least = std::min(least, pixel.color.g);
        most = std::max(most, pixel.color.g);
      }
      range[quality] = {least, most};
      std::printf("white metal, roughness %.1f, %s tier, furnace: %.4f .. %.4f\n", roughness, quality, least, most);
    }
    EXPECT_GT(range["high"].first, 0.99f) << roughness;
    EXPECT_LT(range["high"].second, 1.01f) << roughness;
    if (roughness == 1.0f) EXPECT_LT(range["medium"].second, 0.9f) << "the single-scattering lobe loses energy";
    else EXPECT_GT(range["medium"].first, 0.85f);
  }
}
