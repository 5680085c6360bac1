// Depth of field (effects/dof/DepthOfFieldEffect.h) against its brute-force reference
// (renderer/AccumulationReference.h: the mean of 64 pinhole renders from points on the lens, each sheared to keep the
// focus plane): the CoC's packing on the GPU against its CPU mirror, the CoC target against the thin lens, the
// autofocus, and on a scene with near, in-focus and far objects: the whole frame towards the reference, the focus plane
// unchanged, a blurred foreground covering the in-focus edge behind it, and no halo around an in-focus object over a
// blurred background. The AO and FXAA are off, so the figures are the depth of field's alone. Every figure is over the
// RGB channels, 0 .. 255.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <tuple>

#include "TestSupport.h"
#include "effects/dof/DepthOfFieldEffect.h"
#include "encoding/CocPacking.h"
#include "encoding/LinearDepthPacking.h"
#include "gl/ShaderLibrary.h"
#include "renderer/AccumulationReference.h"
#include "encoding/ToneMapping.h"
#include "scene/BuiltinScene.h"
#include "scene/ImageIo.h"
#include "scene/Primitives.h"

namespace obscura {
namespace {

namespace cp = CocPacking;

constexpr int kWidth = 960, kHeight = 540;
constexpr float kFocus = 4.0f;  // the in-focus panel's depth

TEST(GpuCocPacking, TheShaderPacksLikeTheCpuMirrorAndDecodesWhatItPacks) {
  test::context();
  const float range = 32.0f;
  std::vector<glm::vec4> values = {{0, 0, 0, 0}, {range, 0, 0, 0}, {-range, 0, 0, 0}, {2 * range, 0, 0, 0},
                                   {-1e-4f, 0, 0, 0}, {0.5f, 0, 0, 0}, {-0.5f, 0, 0, 0}};
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> uniform(-1.1f * range, 1.1f * range);
  while (values.size() < test::kPointSide * test::kPointSide) {
    const float c = uniform(rng);
    // Skip values within a hair of a rounding boundary of either code, where evaluation order may differ.
    const float s16 = c / range * cp::kSteps16, s8 = c / range * cp::kSteps8;
    if (std::abs(s16 - std::floor(s16) - 0.5f) < 1e-2f || std::abs(s8 - std::floor(s8) - 0.5f) < 1e-3f) continue;
    values.emplace_back(c, 0.0f, 0.0f, 0.0f);
  }
  for (bool roundTrip : {false, true}) {
    // RG: the 16-bit code; B: the 8-bit half code; A: the 8-bit code of the 16-bit code's decoded value. Round trip:
    // packed, decoded and packed again, which must give the same codes.
    const std::string fragment = std::string(R"(
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "dof/coc.glsl"
uniform float u_range;
varying vec4 v_first;  // the CoC in x (test::kTwoValuePointVertex)
void main() {
  float v_value = v_first.x;
  vec4 texel = packCoc(v_value, u_range);
  float halfCode = packHalfCoc(v_value, u_range);
)") + (roundTrip ? "  texel = packCoc(unpackCoc(texel, u_range), u_range);\n"
                    "  halfCode = packHalfCoc(unpackHalfCoc(halfCode, u_range), u_range);\n"
                  : "") +
                                   "  gl_FragColor = vec4(texel.rg, halfCode, packHalfCoc(unpackCoc(texel, u_range), "
                                   "u_range));\n}\n";
    const gl::Program program("pack cocs", ShaderLibrary::composeText(test::kTwoValuePointVertex, {}, {}),
                              ShaderLibrary::composeText(fragment, {}, {}));
    program.use();
    gl::Program::set(program.uniform("u_range"), range);
    const std::vector<std::uint8_t> pixels = test::drawPoints(program, values);
    int mismatches = 0;
    for (size_t i = 0; i < values.size(); ++i) {
      const auto full = cp::bytesFromCoc(values[i].x, range);
      const std::uint8_t expected[4] = {full[0], full[1], cp::halfCodeFromCoc(values[i].x, range),
                                        cp::halfCodeFromCoc(cp::cocFromBytes(full.data(), range), range)};
      for (size_t c = 0; c < 4; ++c)
        if (pixels[i * 4 + c] != expected[c] && ++mismatches < 5)
          ADD_FAILURE() << "CoC " << values[i].x << " byte " << c << ": GPU " << int(pixels[i * 4 + c]) << " CPU "
                        << int(expected[c]) << (roundTrip ? " (round trip)" : "");
    }
    EXPECT_EQ(mismatches, 0);
  }
}

// A checkerboard facing +z at depth `z`, from (x0, y0) to (x1, y1) in squares of `side`, in two colours.
void addChecker(Scene& scene, float z, float x0, float y0, float x1, float y1, float side, const glm::vec3& a,
                const glm::vec3& b) {
  Mesh meshes[2];
  const int nx = static_cast<int>(std::lround((x1 - x0) / side)), ny = static_cast<int>(std::lround((y1 - y0) / side));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const float x = x0 + side * static_cast<float>(i), y = y0 + side * static_cast<float>(j);
      addQuad(meshes[(i + j) % 2], {x, y, z}, {x + side, y, z}, {x + side, y + side, z}, {x, y + side, z});
    }
  test::addStill(scene, std::move(meshes[0]), a);
  test::addStill(scene, std::move(meshes[1]), b);
}

// Camera at the origin looking down -z. Far: a checkered wall at 12 m. In focus: a checkered panel at 4 m around the
// centre. Near: a dark bar at 1.5 m, upright, right of the centre, over the panel and the wall.
Scene lensScene() {
  Scene scene;
  addChecker(scene, -12.0f, -8.0f, -5.0f, 8.0f, 5.0f, 0.5f, {0.9f, 0.85f, 0.7f}, {0.15f, 0.3f, 0.5f});
  addChecker(scene, -kFocus, -0.6f, -0.5f, 0.6f, 0.5f, 0.1f, {0.9f, 0.2f, 0.15f}, {0.95f, 0.95f, 0.95f});
  test::addStill(scene, makeBox({0.05f, -1.0f, -1.55f}, {0.15f, 1.0f, -1.45f}), {0.1f, 0.45f, 0.15f});
  return scene;
}

Camera lensCamera() {
  Camera camera = test::makeCamera({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, kWidth, kHeight, 0.5f, 20.0f, 27.0f);
  return camera;
}

RenderSettings lensSettings(bool dof) {
  RenderSettings settings;
  settings.set("ao", "off");
  settings.set("fxaa", "off");
  settings.set("dof", dof ? "on" : "off");
  settings.set("dof.focus", std::to_string(kFocus));
  settings.set("dof.fstop", "1.4");
  settings.set("dof.focal-length", "50");
  settings.set("dof.sensor-height", "24");
  return settings;
}

// The retained dof-coc target of the last frame, decoded (rows top to bottom).
std::vector<float> readCoc(Renderer& renderer, float range) {
  const std::vector<std::uint8_t> bytes = renderer.retained("dof-coc").readRgba();
  std::vector<float> out(bytes.size() / 4);
  for (size_t p = 0; p < out.size(); ++p) out[p] = cp::cocFromBytes(&bytes[p * 4], range);
  return out;
}

float cocRange(const RenderSettings& settings) {
  return 2.0f * settings.of<DofSettings>().maxRadiusPixels(kHeight);
}

TEST(DepthOfField, TheCocTargetIsTheThinLensOfTheGBuffersDepth) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(lensScene());
  const Camera camera = lensCamera();
  const RenderSettings settings = lensSettings(true);
  test::render(renderer, camera, settings, View::Final, test::retaining({"dof-coc", "gbuffer"}));
  const float range = cocRange(settings);
  const std::vector<float> coc = readCoc(renderer, range);
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  const ThinLens lens = ThinLens::of(settings.of<DofSettings>(), kHeight);
  double worst = 0.0;
  float nearest = 0.0f, farthest = 0.0f;
  for (size_t p = 0; p < coc.size(); ++p) {
    const float d = LinearDepthPacking::depthFromCode(
        LinearDepthPacking::codeFromBytes(gbuffer[p * 4 + 2], gbuffer[p * 4 + 3]));
    const float depth = camera.near + d * (camera.far - camera.near);
    const float expected = std::clamp(lens.coc(depth, kFocus), -range, range);
    worst = std::max(worst, static_cast<double>(std::abs(coc[p] - expected)));
    nearest = std::min(nearest, coc[p]);
    farthest = std::max(farthest, coc[p]);
  }
  std::printf("[ dof ] CoC target against the thin lens: worst %.5f px (code step %.5f px); near %.2f, far %.2f px\n",
              worst, range / cp::kSteps16, nearest, farthest);
  // The 16-bit code's half step, plus float evaluation order.
  EXPECT_LE(worst, 0.5 * range / cp::kSteps16 + 1e-3 * range);
  // The deck's formula, by hand: s = (F / N) F H / h, C = s (D - P) / (D (P - F)).
  const double s = (0.05 / 1.4) * 0.05 * kHeight / 0.024;
  EXPECT_NEAR(lens.coc(12.0f, kFocus), s * (12.0 - 4.0) / (12.0 * (4.0 - 0.05)), 1e-3);
  EXPECT_NEAR(lens.coc(1.5f, kFocus), s * (1.5 - 4.0) / (1.5 * (4.0 - 0.05)), 1e-3);
  EXPECT_LT(nearest, -15.0f);  // the bar: -16.9 px
  EXPECT_GT(farthest, 6.0f);   // the wall: 6.8 px
}

TEST(DepthOfField, AutofocusFocusesOnTheDepthAtTheFocusPoint) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(lensScene());
  const Camera camera = lensCamera();
  RenderSettings settings = lensSettings(true);
  settings.set("dof.focus", "auto");
  const float range = cocRange(settings);
  // The centre: the panel at 4 m. A point top left: the wall at 12 m.
  for (const auto& [x, y, depth] : {std::tuple{0.5f, 0.5f, kFocus}, std::tuple{0.05f, 0.05f, 12.0f}}) {
    settings.set("dof.focus-x", std::to_string(x));
    settings.set("dof.focus-y", std::to_string(y));
    EXPECT_NEAR(autofocusDistance(renderer, camera, settings), depth, 0.01f) << x << ", " << y;
    test::render(renderer, camera, settings, View::Final, test::retaining({"dof-coc"}));
    const std::vector<float> coc = readCoc(renderer, range);
    const glm::ivec2 focus = settings.of<DofSettings>().focusPixel(kWidth, kHeight);
    EXPECT_NEAR(coc[static_cast<size_t>(focus.y) * kWidth + focus.x], 0.0f, 0.01f) << x << ", " << y;
    // Focused on the wall, the panel is in front of the focus: negative.
    const float panel = coc[static_cast<size_t>(kHeight / 2) * kWidth + kWidth / 2 - 100];
    if (depth > kFocus) {
      EXPECT_LT(panel, -2.0f);
    } else {
      EXPECT_NEAR(panel, 0.0f, 0.01f);
    }
  }
}

struct Frames {
  test::RenderedImage dof, pinhole;
  LinearImage reference;
  std::vector<float> coc;  // the DoF frame's, pixels, rows top to bottom
};

Frames renderFrames(const char* what) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(lensScene());
  const Camera camera = lensCamera();
  Frames frames;
  ApertureOptions aperture;
  aperture.samples = 64;
  frames.reference = accumulateAperture(renderer, camera, lensSettings(true), aperture);
  frames.pinhole = test::render(renderer, camera, lensSettings(false), View::Final);
  frames.dof = test::render(renderer, camera, lensSettings(true), View::Final, test::retaining({"dof-coc"}));
  frames.coc = readCoc(renderer, cocRange(lensSettings(true)));
  // OBSCURA_TEST_DUMP=DIR writes the three frames, to look at.
  if (const char* dir = std::getenv("OBSCURA_TEST_DUMP")) {
    const std::string base = std::string(dir) + "/" + what;
    writePng(base + "-dof.png", Image{kWidth, kHeight, frames.dof.rgba});
    writePng(base + "-pinhole.png", Image{kWidth, kHeight, frames.pinhole.rgba});
    writePng(base + "-reference.png", frames.reference.toImage());
  }
  return frames;
}

const Frames& lensFrames() {
  static const Frames frames = renderFrames("lens");
  return frames;
}

// Mean |a - reference| over the RGB channels of the pixels `where` holds, 0 .. 255, and how many.
std::pair<double, size_t> meanError(const test::RenderedImage& a, const LinearImage& reference,
                                    const std::function<bool(int, int)>& where) {
  double sum = 0.0;
  size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!where(x, y)) continue;
      for (int c = 0; c < 3; ++c) sum += std::abs(a.channel(x, y, c) - 255.0 * reference.at(x, y, c));
      ++n;
    }
  return {n ? sum / (3.0 * static_cast<double>(n)) : 0.0, n};
}

// Whether any pixel within `radius` (a square) of (x, y) satisfies `test`.
bool anyWithin(int x, int y, int radius, const std::function<bool(int, int)>& test) {
  for (int j = std::max(0, y - radius); j <= std::min(kHeight - 1, y + radius); ++j)
    for (int i = std::max(0, x - radius); i <= std::min(kWidth - 1, x + radius); ++i)
      if (test(i, j)) return true;
  return false;
}

float cocAt(const Frames& f, int x, int y) { return f.coc[static_cast<size_t>(y) * kWidth + x]; }

TEST(DepthOfField, TheFrameMovesTowardsTheApertureReference) {
  const Frames& f = lensFrames();
  const auto all = [](int, int) { return true; };
  // The pixels the lens blurs: where the reference, the pinhole frame or the DoF frame differ by more than 2/255.
  const auto blurred = [&f](int x, int y) {
    for (int c = 0; c < 3; ++c) {
      const double r = 255.0 * f.reference.at(x, y, c);
      if (std::abs(r - f.dof.channel(x, y, c)) > 2.0 || std::abs(r - f.pinhole.channel(x, y, c)) > 2.0) return true;
    }
    return false;
  };
  const auto [pinholeAll, n] = meanError(f.pinhole, f.reference, all);
  const auto [dofAll, n2] = meanError(f.dof, f.reference, all);
  const auto [pinhole, m] = meanError(f.pinhole, f.reference, blurred);
  const auto [dof, m2] = meanError(f.dof, f.reference, blurred);
  std::printf("[ dof ] MAE against the 64-point aperture reference: whole frame pinhole %.3f, dof %.3f (ratio %.2f); "
              "over the %zu pixels that blur: pinhole %.3f, dof %.3f (ratio %.2f)\n",
              pinholeAll, dofAll, dofAll / pinholeAll, m, pinhole, dof, dof / pinhole);
  EXPECT_GT(m, static_cast<size_t>(kWidth * kHeight / 5)) << "the scene should blur";
  EXPECT_LE(dofAll, 0.5 * pinholeAll);
  EXPECT_LE(dof, 0.5 * pinhole);
}

// An orthographic camera (DepthOfFieldEffect.h): the CoC is the thin lens's linearised at its focus, so it grows
// linearly with the distance from the focal plane; the frame moves towards its own aperture reference (parallel rays
// tilted about the focal plane), as the perspective one does, at a quarter of the pixels.
TEST(DepthOfField, AnOrthographicCameraBlursLinearlyWithDistanceFromTheFocalPlane) {
  constexpr int width = kWidth / 2, height = kHeight / 2;
  Renderer renderer = test::makeRenderer();
  renderer.setScene(lensScene());
  Camera camera = lensCamera();
  camera.width = width;
  camera.height = height;
  camera.orthographic = true;
  camera.ymag = 1.2f;
  const RenderSettings settings = lensSettings(true);
  test::render(renderer, camera, settings, View::Final, test::retaining({"dof-coc", "gbuffer"}));
  const float range = 2.0f * settings.of<DofSettings>().maxRadiusPixels(height);
  const std::vector<float> coc = readCoc(renderer, range);
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  const ThinLens lens = ThinLens::of(settings.of<DofSettings>(), height, true);
  double worst = 0.0;
  for (size_t p = 0; p < coc.size(); ++p) {
    const float d = LinearDepthPacking::depthFromCode(
        LinearDepthPacking::codeFromBytes(gbuffer[p * 4 + 2], gbuffer[p * 4 + 3]));
    const float depth = camera.near + d * (camera.far - camera.near);
    worst = std::max(worst, static_cast<double>(std::abs(coc[p] - std::clamp(lens.coc(depth, kFocus), -range, range))));
  }
  EXPECT_LE(worst, 0.5 * range / cp::kSteps16 + 1e-3 * range);
  // Linear in D, with the perspective lens's slope at the focus: C = s (D - P) / (P (P - F)).
  const ThinLens perspective = ThinLens::of(settings.of<DofSettings>(), height);
  for (float depth : {1.5f, 3.9f, 4.1f, 12.0f}) {
    const double s = (0.05 / 1.4) * 0.05 * height / 0.024;
    EXPECT_NEAR(lens.coc(depth, kFocus), s * (depth - 4.0) / (4.0 * (4.0 - 0.05)), 1e-3);
  }
  EXPECT_NEAR((lens.coc(4.01f, kFocus) - lens.coc(3.99f, kFocus)) / 0.02f,
              (perspective.coc(4.01f, kFocus) - perspective.coc(3.99f, kFocus)) / 0.02f, 1e-2);

  ApertureOptions aperture;
  aperture.samples = 48;
  const LinearImage reference = accumulateAperture(renderer, camera, settings, aperture);
  const test::RenderedImage pinhole = test::render(renderer, camera, lensSettings(false), View::Final);
  const test::RenderedImage dof = test::render(renderer, camera, settings, View::Final);
  const auto all = [](int, int) { return true; };
  const double pinholeError = meanError(pinhole, reference, all).first, dofError = meanError(dof, reference, all).first;
  // The focal plane is sharp in the reference too: the panel's pixels match the pinhole frame's.
  const auto panel = [&](int x, int y) { return std::abs(coc[static_cast<size_t>(y) * width + x]) < 0.25f; };
  const double focusError = meanError(pinhole, reference, panel).first;
  std::printf("[ dof ] orthographic: MAE against the %d-point parallel aperture reference: pinhole %.3f, dof %.3f "
              "(ratio %.2f); the focal plane, pinhole against the reference: %.3f\n",
              aperture.samples, pinholeError, dofError, dofError / pinholeError, focusError);
  EXPECT_GT(pinholeError, 3.0) << "the reference should blur";
  EXPECT_LE(dofError, 0.5 * pinholeError);
  EXPECT_LE(focusError, 3.0);
}

TEST(DepthOfField, TheFocusPlaneStaysSharp) {
  const Frames& f = lensFrames();
  // Pixels whose |CoC| is under half a pixel, away from the near field's reach (its largest radius, 12 px, and the
  // half-size filter's).
  const auto nearField = [&f](int x, int y) { return cocAt(f, x, y) < -0.5f; };
  int worst = 0;
  glm::ivec2 worstPixel(0);
  size_t n = 0, over = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (std::abs(cocAt(f, x, y)) >= 0.5f || anyWithin(x, y, 16, nearField)) continue;
      ++n;
      int difference = 0;
      for (int c = 0; c < 3; ++c)
        difference = std::max(difference, std::abs(f.dof.channel(x, y, c) - f.pinhole.channel(x, y, c)));
      over += difference > 1;
      if (difference > worst) {
        worst = difference;
        worstPixel = {x, y};
      }
    }
  std::printf("[ dof ] focus plane: %zu pixels with |CoC| < 0.5 px, worst difference from the pinhole frame %d/255 "
              "(at %d, %d; CoC %.3f px), %zu pixels over 1\n",
              n, worst, worstPixel.x, worstPixel.y, cocAt(f, worstPixel.x, worstPixel.y), over);
  EXPECT_GT(n, static_cast<size_t>(50000));
  EXPECT_LE(worst, 1);
}

TEST(DepthOfField, ABlurredForegroundCoversTheInFocusEdgeBehindIt) {
  const Frames& f = lensFrames();
  // The band: in-focus pixels (the panel) within the bar's blur radius (8.5 px) of the bar's silhouette.
  const auto bar = [&f](int x, int y) { return cocAt(f, x, y) < -10.0f; };
  const auto band = [&f, &bar](int x, int y) { return std::abs(cocAt(f, x, y)) < 0.5f && anyWithin(x, y, 8, bar); };
  const auto [pinhole, n] = meanError(f.pinhole, f.reference, band);
  const auto [dof, m] = meanError(f.dof, f.reference, band);
  std::printf("[ dof ] in-focus band beside the blurred foreground (%zu pixels): MAE pinhole %.3f, dof %.3f "
              "(ratio %.2f)\n",
              n, pinhole, dof, dof / pinhole);
  EXPECT_GT(n, static_cast<size_t>(2000));
  EXPECT_GT(pinhole, 10.0) << "the reference should blur the bar over the panel";
  EXPECT_LE(dof, 0.5 * pinhole);
}

TEST(DepthOfField, NoHaloAroundAnInFocusObjectOverABlurredBackground) {
  const Frames& f = lensFrames();
  // The band: far pixels (the wall) within 6 px of the in-focus panel, away from the bar.
  const auto panel = [&f](int x, int y) { return std::abs(cocAt(f, x, y)) < 0.5f; };
  const auto bar = [&f](int x, int y) { return cocAt(f, x, y) < -0.5f; };
  const auto band = [&](int x, int y) {
    return cocAt(f, x, y) > 1.0f && anyWithin(x, y, 6, panel) && !anyWithin(x, y, 24, bar);
  };
  // A halo is a darkening or brightening along the silhouette: the mean signed luma difference from the reference.
  double signedSum = 0.0;
  size_t n = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (!band(x, y)) continue;
      double d = 0.0;
      const double weights[3] = {0.299, 0.587, 0.114};
      for (int c = 0; c < 3; ++c) d += weights[c] * (f.dof.channel(x, y, c) - 255.0 * f.reference.at(x, y, c));
      signedSum += d;
      ++n;
    }
  const double bias = n ? signedSum / static_cast<double>(n) : 0.0;
  const auto [pinhole, n1] = meanError(f.pinhole, f.reference, band);
  const auto [dof, n2] = meanError(f.dof, f.reference, band);
  std::printf("[ dof ] blurred band around the in-focus panel (%zu pixels): mean signed luma difference %.3f; MAE "
              "pinhole %.3f, dof %.3f\n",
              n, bias, pinhole, dof);
  EXPECT_GT(n, static_cast<size_t>(2000));
  EXPECT_LE(std::abs(bias), 2.0);
  EXPECT_LE(dof, pinhole);
}

// The lens gathers light before the tone curve: a small emitter far above display white (emission 40) behind the focus
// plane, in a dark room, makes a bokeh disc as bright as the aperture reference's (which averages linear light): the
// mean display luminance over the disc within 10 % of the reference's.
TEST(DepthOfField, ABrightEmitterMakesABokehDiscAsBrightAsTheLenss) {
  Scene scene;
  // A dim wall at 12 m and the emitter, a 6 cm square just in front of it, left of the centre.
  addChecker(scene, -12.0f, -8.0f, -5.0f, 8.0f, 5.0f, 0.5f, {0.05f, 0.05f, 0.05f}, {0.08f, 0.08f, 0.08f});
  Mesh emitter;
  addQuad(emitter, {-1.03f, 0.27f, -11.9f}, {-0.97f, 0.27f, -11.9f}, {-0.97f, 0.33f, -11.9f}, {-1.03f, 0.33f, -11.9f});
  const int material = test::addMaterial(scene, glm::vec3(0.0f));
  scene.materials[static_cast<size_t>(material)].emissiveFactor = glm::vec3(1.0f, 0.9f, 0.8f);
  scene.materials[static_cast<size_t>(material)].emissiveStrength = 40.0f;
  emitter.material = material;
  scene.meshes.push_back(std::move(emitter));
  Instance instance;
  instance.mesh = static_cast<int>(scene.meshes.size()) - 1;
  scene.instances.push_back(instance);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  const int width = 480, height = 270;
  const Camera camera = test::makeCamera({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, width, height, 0.5f, 20.0f, 27.0f);
  // At f/1.4 the disc is 3.4 pixels wide (gathered at full size), at f/0.5 9.5 (the half-size far field).
  for (const char* fstop : {"1.4", "0.5"}) {
  RenderSettings settings = lensSettings(true);
  settings.set("dof.fstop", fstop);
  settings.set("lighting.environment", "uniform");
  settings.set("lighting.environment-intensity", "0.3");
  settings.set("lighting.sun-intensity", "0");
  ApertureOptions aperture;
  aperture.samples = 64;
  const LinearImage reference = accumulateAperture(renderer, camera, settings, aperture);
  const test::RenderedImage dof = test::render(renderer, camera, settings, View::Final);
  RenderSettings pinholeSettings = settings;
  pinholeSettings.set("dof", "off");
  const test::RenderedImage pinhole = test::render(renderer, camera, pinholeSettings, View::Final);
  // The disc: where the emitter's blur lands, C = 6.8 pixels at 960 rows (3.4 here) around the emitter's pixel.
  const glm::vec4 clip =
      FrameCamera::from(camera, width, height).unjitteredProjection * glm::vec4(-1.0f, 0.3f, -11.9f, 1.0f);
  const glm::vec2 centre((clip.x / clip.w * 0.5f + 0.5f) * width, (0.5f - clip.y / clip.w * 0.5f) * height);
  const float c = ThinLens::of(settings.of<DofSettings>(), height).coc(11.9f, kFocus);
  auto luminance = [](float r, float g, float b) {
    return 0.2126 * srgbToLinear(r) + 0.7152 * srgbToLinear(g) + 0.0722 * srgbToLinear(b);
  };
  double dofSum = 0.0, referenceSum = 0.0, pinholeSum = 0.0;
  int n = 0;
  const float radius = 0.5f * c + 2.0f;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::vec2 p(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      if (glm::length(p - centre) > radius) continue;
      dofSum += luminance(dof.channel(x, y, 0) / 255.0f, dof.channel(x, y, 1) / 255.0f, dof.channel(x, y, 2) / 255.0f);
      referenceSum += luminance(reference.at(x, y, 0), reference.at(x, y, 1), reference.at(x, y, 2));
      pinholeSum += luminance(pinhole.channel(x, y, 0) / 255.0f, pinhole.channel(x, y, 1) / 255.0f,
                              pinhole.channel(x, y, 2) / 255.0f);
      ++n;
    }
  std::printf("[ dof ] bokeh of an emitter at 40x display white, C = %.2f px, %d pixels: mean display luminance %.4f, "
              "reference %.4f (%.1f %%), the pinhole frame %.4f\n",
              c, n, dofSum / n, referenceSum / n, 100.0 * dofSum / referenceSum, pinholeSum / n);
  EXPECT_GT(n, 20);
  EXPECT_NEAR(dofSum / referenceSum, 1.0, 0.10) << "f/" << fstop;
  }
}

// Small blurs (the built-in room at f/0.7 focused at 6 m: 1 .. 7 pixels at 480x270), gathered at full size where the
// CoC is under kDofSmallCoc pixels: over the pixels that blur, at most half the pinhole frame's error against the
// aperture reference.
TEST(DepthOfField, SmallBlursMoveHalfWayToTheReference) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const Camera camera = builtinSceneCamera(480, 270);
  RenderSettings settings;
  settings.set("ao", "off");
  settings.set("fxaa", "off");
  settings.set("dof.focus", "6");
  settings.set("dof.fstop", "0.7");
  ApertureOptions aperture;
  aperture.samples = 64;
  const LinearImage reference = accumulateAperture(renderer, camera, settings, aperture);
  const test::RenderedImage pinhole = test::render(renderer, camera, settings, View::Final);
  settings.set("dof", "on");
  const test::RenderedImage dof = test::render(renderer, camera, settings, View::Final, test::retaining({"dof-coc"}));
  const std::vector<float> coc = readCoc(renderer, 2.0f * settings.of<DofSettings>().maxRadiusPixels(270));
  const auto blurred = [&](int x, int y) {
    for (int c = 0; c < 3; ++c) {
      const double r = 255.0 * reference.at(x, y, c);
      if (std::abs(r - dof.channel(x, y, c)) > 2.0 || std::abs(r - pinhole.channel(x, y, c)) > 2.0) return true;
    }
    return false;
  };
  const auto all = [](int, int) { return true; };
  const auto [pinholeAll, n] = meanError(pinhole, reference, all);
  const auto [dofAll, n2] = meanError(dof, reference, all);
  const auto [pinholeBlurred, m] = meanError(pinhole, reference, blurred);
  const auto [dofBlurred, m2] = meanError(dof, reference, blurred);
  std::printf("[ dof ] the room's small blurs: whole frame pinhole %.3f, dof %.3f (ratio %.2f); over the %zu pixels "
              "that blur: pinhole %.3f, dof %.3f (ratio %.2f)\n",
              pinholeAll, dofAll, dofAll / pinholeAll, m, pinholeBlurred, dofBlurred, dofBlurred / pinholeBlurred);
  for (const auto& [label, lo, hi] : {std::tuple<const char*, float, float>{"near < -4", -1e9f, -4.0f},
                                       {"near -4 .. -0.5", -4.0f, -0.5f},
                                       {"in focus", -0.5f, 0.5f},
                                       {"far 0.5 .. 4", 0.5f, 4.0f},
                                       {"far > 4", 4.0f, 1e9f}}) {
    const auto band = [&, lo = lo, hi = hi](int x, int y) {
      const float c = coc[static_cast<size_t>(y) * 480 + static_cast<size_t>(x)];
      return blurred(x, y) && c >= lo && c < hi;
    };
    const auto [p, k] = meanError(pinhole, reference, band);
    const auto [d, k2] = meanError(dof, reference, band);
    std::printf("[ dof ]   %s: %zu pixels, pinhole %.3f, dof %.3f\n", label, k, p, d);
  }
  EXPECT_GT(m, static_cast<size_t>(480 * 270 / 10));
  EXPECT_LE(dofBlurred, 0.5 * pinholeBlurred);
}

// The composite is a stage head (frame/Stage.h: fullscreenStageHead): the tone curve and the display colour's stages
// run in its program, a pass fewer, and give the image they give as passes of their own (RendererOptions::fuseStages
// off) but for the HDR encoding the fused program skips between the composite and the tone curve.
TEST(DepthOfField, TheToneCurveAndTheDisplayStagesRunInTheCompositesPass) {
  RenderSettings settings;
  settings.set("dof", "on");
  settings.set("dof.max-radius", "6");
  settings.set("vignette", "on");
  settings.set("fxaa", "off");   // the stages' output drawn into the output by the composite
  settings.set("dither", "off");  // a step of noise would add its own differences
  const test::FusedAndSeparate frames(makeBuiltinScene(), builtinSceneCamera(160, 90), settings);
  std::vector<std::string> absorbed;
  for (const PlannedPass& pass : frames.fused.lastPlan().passes())
    if (pass.live && pass.decl.name == "dof-composite") absorbed = pass.absorbed;
  EXPECT_EQ(absorbed, (std::vector<std::string>{"tonemap", "vignette"}));
  EXPECT_EQ(test::passCount(test::livePasses(frames.fused)), test::passCount(test::livePasses(frames.separate)) - 2);
  const test::ColorDifference& d = frames.difference;
  std::printf("[ dof ] the tone curve and the vignette fused into the composite against separate passes: largest "
              "difference %d/255, mean %.4f/255\n",
              d.worst, d.mean);
  // Every pixel skips one RGB9E5 quantisation (9 bits of its largest channel): a level in about a fifth of the
  // channels (measured 1/255 at most, 0.19/255 on average).
  EXPECT_LE(d.worst, 1);
  EXPECT_LT(d.mean, 0.3);
}

}  // namespace
}  // namespace obscura
