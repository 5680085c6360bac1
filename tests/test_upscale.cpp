// The render scale (frame/Resolution.h) and its upscale (effects/resolution, shaders_es2/lib/upscale.glsl), measured
// against rendering at the full size:
//   - the upscale filters alone on images made on the CPU: bilinear is exactly bilinear, the edge upscale keeps a
//     flat image flat and a step within its two values, and brings an edge rendered small closer to the same edge
//     rendered large than bilinear does; the sharpening steepens a step without overshooting it;
//   - the frame: the effects run at the scaled size and one pass writes the output (FXAA's, where FXAA runs); the
//     built-in scene at scale 0.5 upscaled by the edge filter is closer to the frame rendered at full size than the
//     bilinear upscale (the bound: its MAE at most 0.8 x bilinear's);
//   - history across a scale change: the frame after one shows nothing of the frames before it (dropped cleanly);
//   - dynamic resolution in the viewer: the frame is drawn at the scale the controller chose.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "effects/fxaa/FxaaEffect.h"
#include "effects/resolution/ResolutionEffect.h"
#include "frame/FullscreenPass.h"
#include "frame/Resolution.h"
#include "gl/GlObjects.h"
#include "gl/PipelineState.h"
#include "metrics/UpscaleMetrics.h"
#include "platform/Viewer.h"
#include "scene/BuiltinScene.h"

using namespace obscura;

namespace {

// An RGBA8 image, rows from the bottom (GL's order).
struct Bytes {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  std::uint8_t at(int x, int y, int c) const { return rgba[(static_cast<size_t>(y) * width + x) * 4 + c]; }
};

// One of the upscale pass's programs, by its settings.
ProgramSpec upscaleSpec(UpscaleFilter filter, bool sharpen) {
  for (const ProgramSpec& spec : ResolutionEffect::programSpecs()) {
    ResolutionSettings settings;
    settings.upscale = filter;
    settings.sharpness = sharpen ? 1.0f : 0.0f;
    if (spec.name == "upscale[" + upscaleVariantName(settings) + "]") return spec;
  }
  throw std::runtime_error("no upscale program");
}

// The upscale pass's program run on `source` into a width x height target.
Bytes upscale(const Bytes& source, int width, int height, UpscaleFilter filter, float sharpness = 0.0f) {
  test::context();  // current before the first GL object
  const gl::Program program = upscaleSpec(filter, sharpness > 0.0f).build(true);
  const gl::Texture2D input(source.width, source.height, GL_NEAREST, source.rgba.data());
  const gl::RenderTarget output("upscale test", width, height, GL_NEAREST, gl::RenderTarget::Depth::None, false);
  output.bindForDrawing();
  input.bind(0);
  program.use();
  gl::Program::set(program.uniform("u_color"), 0);
  const glm::vec2 size(static_cast<float>(source.width), static_cast<float>(source.height));
  gl::Program::set(program.uniform("u_size"), size);
  gl::Program::set(program.uniform("u_texel"), 1.0f / size);
  if (sharpness > 0.0f) gl::Program::set(program.uniform("u_sharpness"), sharpness);
  test::effectResources().triangle.draw();
  gl::restoreBaselineState();
  Bytes out{width, height, output.readRgba()};
  // readRgba gives rows from the top: back to GL's order.
  const size_t row = static_cast<size_t>(width) * 4;
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(out.rgba.begin() + static_cast<std::ptrdiff_t>(y * row),
                     out.rgba.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                     out.rgba.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row));
  return out;
}

// An image of coverage `inside(x, y)` (x, y in [0, 1]^2) at width x height, each pixel the mean of 8 x 8 samples:
// grey 40 outside, a colour inside; luma in alpha as the display colour holds it.
template <typename Inside>
Bytes coverage(int width, int height, Inside inside) {
  Bytes image{width, height, std::vector<std::uint8_t>(static_cast<size_t>(width) * height * 4)};
  const float in[3] = {230.0f, 120.0f, 60.0f}, out[3] = {40.0f, 40.0f, 40.0f};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      int hits = 0;
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i)
          hits += inside(static_cast<float>((x + (i + 0.5) / 8.0) / width),
                         static_cast<float>((y + (j + 0.5) / 8.0) / height))
                      ? 1
                      : 0;
      const float f = static_cast<float>(hits) / 64.0f;
      float rgb[3];
      for (int c = 0; c < 3; ++c) rgb[c] = out[c] + (in[c] - out[c]) * f;
      std::uint8_t* p = &image.rgba[(static_cast<size_t>(y) * width + x) * 4];
      for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>(std::lround(rgb[c]));
      p[3] = static_cast<std::uint8_t>(std::lround(0.299f * rgb[0] + 0.587f * rgb[1] + 0.114f * rgb[2]));
    }
  return image;
}

double meanAbsoluteError(const Bytes& a, const Bytes& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.rgba.size(); ++i)
    if (i % 4 != 3) sum += std::abs(a.rgba[i] - b.rgba[i]);
  return sum / (3.0 * a.width * a.height);
}

Image topDown(const test::RenderedImage& image) { return Image{image.width, image.height, image.rgba}; }

std::vector<std::string> running(const Renderer& renderer) {
  std::vector<std::string> out;
  for (const PlannedPass& pass : renderer.lastPlan().passes())
    if (pass.live) out.push_back(pass.decl.name);
  return out;
}

RenderSettings scaled(float scale, UpscaleFilter filter = UpscaleFilter::Edge) {
  RenderSettings settings;
  settings.of<ResolutionSettings>().scale = scale;
  settings.of<ResolutionSettings>().upscale = filter;
  return settings;
}

}  // namespace

TEST(Resolution, TheRenderSizeRoundsEachSideAndTheParametersAreTheTables) {
  EXPECT_EQ(renderSize({1280, 720}, 0.5f), glm::ivec2(640, 360));
  EXPECT_EQ(renderSize({1281, 721}, 0.5f), glm::ivec2(641, 361));  // 640.5 rounds away from zero
  EXPECT_EQ(renderSize({3, 1}, 0.25f), glm::ivec2(1, 1));             // never empty
  EXPECT_EQ(renderSize({1280, 720}, 1.0f), glm::ivec2(1280, 720));
  RenderSettings settings;
  EXPECT_EQ(settings.get("resolution.scale"), "1");
  EXPECT_EQ(settings.get("resolution.upscale"), "edge");
  EXPECT_EQ(settings.get("resolution.dynamic"), "off");
  EXPECT_EQ(settings.get("resolution.max-pixel-ratio"), "2");
  EXPECT_THROW(settings.set("resolution.scale", "0.2"), InputError);
  EXPECT_THROW(settings.set("resolution.upscale", "lanczos"), InputError);
}

TEST(Upscale, BilinearIsExactlyBilinear) {
  Bytes source{7, 5, std::vector<std::uint8_t>(7 * 5 * 4)};
  for (size_t i = 0; i < source.rgba.size(); ++i) source.rgba[i] = static_cast<std::uint8_t>((i * 37 + 11) % 256);
  const Bytes out = upscale(source, 17, 11, UpscaleFilter::Bilinear);
  int worst = 0;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      // The output pixel's centre in source texels, clamped at the borders like a clamped texture.
      const double sx = (x + 0.5) * source.width / out.width - 0.5, sy = (y + 0.5) * source.height / out.height - 0.5;
      const int x0 = static_cast<int>(std::floor(sx)), y0 = static_cast<int>(std::floor(sy));
      const float fx = static_cast<float>(sx - x0), fy = static_cast<float>(sy - y0);
      auto texel = [&](int tx, int ty, int c) {
        const int cx = std::clamp(tx, 0, source.width - 1), cy = std::clamp(ty, 0, source.height - 1);
        return static_cast<float>(source.at(cx, cy, c));
      };
      for (int c = 0; c < 3; ++c) {
        const float top = texel(x0, y0, c) + (texel(x0 + 1, y0, c) - texel(x0, y0, c)) * fx;
        const float bottom = texel(x0, y0 + 1, c) + (texel(x0 + 1, y0 + 1, c) - texel(x0, y0 + 1, c)) * fx;
        worst = std::max(worst, std::abs(static_cast<int>(std::lround(top + (bottom - top) * fy)) - out.at(x, y, c)));
      }
    }
  EXPECT_LE(worst, 1);
}

// An edge rendered small (a disc and a slanted half-plane, antialiased) and upscaled 2x, against the same edge rendered
// at the large size: the edge upscale comes closer than bilinear, keeps a flat image flat and never leaves the
// range of the texels it reads; the sharpening brings it closer still and also stays within that range.
TEST(Upscale, TheEdgeUpscaleIsCloserToTheLargeRenderingThanBilinear) {
  auto disc = [](float x, float y) { return (x - 0.45f) * (x - 0.45f) + (y - 0.55f) * (y - 0.55f) < 0.09f; };
  auto slant = [](float x, float y) { return y < 0.3f + 0.37f * x; };
  for (const auto& [name, small, large] :
       {std::make_tuple("disc", coverage(48, 48, disc), coverage(96, 96, disc)),
        std::make_tuple("slant", coverage(48, 48, slant), coverage(96, 96, slant))}) {
    const double bilinear = meanAbsoluteError(upscale(small, 96, 96, UpscaleFilter::Bilinear), large);
    const Bytes edgeImage = upscale(small, 96, 96, UpscaleFilter::Edge);
    const double edge = meanAbsoluteError(edgeImage, large);
    const Bytes sharpImage = upscale(small, 96, 96, UpscaleFilter::Edge, 1.0f);
    const double sharp = meanAbsoluteError(sharpImage, large);
    std::printf("%s, 48 -> 96: MAE bilinear %.3f, edge %.3f, edge sharpened %.3f\n", name, bilinear, edge, sharp);
    EXPECT_LT(edge, 0.9 * bilinear) << name;
    EXPECT_LT(sharp, edge) << name;
    for (const Bytes* image : {&edgeImage, &sharpImage})
      for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x)
          for (int c = 0; c < 3; ++c) {
            const int inside = c == 0 ? 230 : c == 1 ? 120 : 60;
            EXPECT_GE(image->at(x, y, c), std::min(40, inside)) << name;
            EXPECT_LE(image->at(x, y, c), std::max(40, inside)) << name;
          }
  }
  const Bytes flat = coverage(9, 7, [](float, float) { return true; });
  for (float sharpness : {0.0f, 1.0f}) {
    const Bytes out = upscale(flat, 23, 15, UpscaleFilter::Edge, sharpness);
    for (size_t i = 0; i < out.rgba.size(); ++i) {
      if (i % 4 == 3) continue;
      EXPECT_EQ(out.rgba[i], flat.rgba[i % 4]) << "sharpness " << sharpness;
    }
  }
}

// Where FXAA leaves the image alone, its pass with the upscale fused (fxaa.frag, UPSCALE) writes what the upscale's
// own pass writes: one upscale at the pixel's own point, with the same size and texel. A smooth image whose local
// contrast stays below FXAA's threshold everywhere but whose quads differ by more than the edge upscale's flat limit
// (2 levels), so that its kernel runs; at 2x and at a scale that is not.
TEST(Upscale, FxaasFusedUpscaleIsTheUpscaleWhereFxaaLeavesTheImageAlone) {
  test::context();
  Bytes smooth{29, 17, std::vector<std::uint8_t>(29 * 17 * 4)};
  for (int y = 0; y < smooth.height; ++y)
    for (int x = 0; x < smooth.width; ++x) {
      std::uint8_t* p = &smooth.rgba[(static_cast<size_t>(y) * smooth.width + x) * 4];
      float rgb[3];
      for (int c = 0; c < 3; ++c) {
        rgb[c] = std::round(110.0f + 5.0f * std::sin(0.9f * static_cast<float>(x) + static_cast<float>(c)) +
                            5.0f * std::cos(0.7f * static_cast<float>(y) + 2.0f * static_cast<float>(c)));
        p[c] = static_cast<std::uint8_t>(rgb[c]);
      }
      p[3] = static_cast<std::uint8_t>(std::lround(0.299f * rgb[0] + 0.587f * rgb[1] + 0.114f * rgb[2]));
    }
  const FxaaSettings fxaa;
  for (const auto& [filter, sharpness] : {std::make_pair(UpscaleFilter::Bilinear, 0.0f),
                                          std::make_pair(UpscaleFilter::Edge, 0.0f),
                                          std::make_pair(UpscaleFilter::Edge, 1.0f)}) {
    ResolutionSettings resolution;
    resolution.upscale = filter;
    resolution.sharpness = sharpness;
    const std::string name = "fxaa[quality=" + std::to_string(fxaa.quality) + ",upscale=" +
                             upscaleVariantName(resolution) + "]";
    const std::vector<ProgramSpec> specs = FxaaEffect::programSpecs();
    const auto spec = std::find_if(specs.begin(), specs.end(), [&](const ProgramSpec& s) { return s.name == name; });
    ASSERT_NE(spec, specs.end()) << name;
    const gl::Program program = spec->build(true);
    const gl::Texture2D input(smooth.width, smooth.height, GL_NEAREST, smooth.rgba.data());
    for (const glm::ivec2 size : {glm::ivec2(58, 34), glm::ivec2(71, 40)}) {
      SCOPED_TRACE(name + " to " + std::to_string(size.x) + "x" + std::to_string(size.y));
      const gl::RenderTarget output("fused upscale test", size.x, size.y, GL_NEAREST, gl::RenderTarget::Depth::None,
                                    false);
      output.bindForDrawing();
      {
        const glm::vec2 source(static_cast<float>(smooth.width), static_cast<float>(smooth.height));
        FullscreenDraw draw(program, test::effectResources().triangle);
        draw.texture("u_color", input);
        draw.set("u_texel", 1.0f / source).set("u_size", source).set("u_subpix", fxaa.subpix);
        draw.set("u_edgeThreshold", fxaa.edgeThreshold).set("u_edgeThresholdMin", fxaa.edgeThresholdMin);
        const std::vector<float>& steps = fxaaSearchSteps(fxaa.quality);
        draw.set("u_searchSteps", steps.data(), static_cast<int>(steps.size()));
        if (program.has("u_sharpness")) draw.set("u_sharpness", sharpness);
        draw.draw();
      }
      gl::restoreBaselineState();
      std::vector<std::uint8_t> fused = output.readRgba();
      const Bytes alone = upscale(smooth, size.x, size.y, filter, sharpness);
      // readRgba's rows run from the top, upscale()'s from the bottom.
      int worst = 0, kernelPixels = 0;
      for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x)
          for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(fused[(static_cast<size_t>(size.y - 1 - y) * size.x + x) * 4 + c] -
                                             alone.at(x, y, c)));
      for (int y = 0; y + 1 < smooth.height; ++y)
        for (int x = 0; x + 1 < smooth.width; ++x) {
          int low = 255, high = 0;
          for (int q = 0; q < 4; ++q) {
            const int v = smooth.at(x + q % 2, y + q / 2, 0);
            low = std::min(low, v);
            high = std::max(high, v);
          }
          kernelPixels += high - low > 2 ? 1 : 0;
        }
      EXPECT_GT(kernelPixels, 200) << "most quads take the edge upscale's kernel";
      // Within a level: the two programs' arithmetic is the same, but a compiler may contract it differently (a
      // fused multiply-add), which moves a value at a rounding boundary. A texel read from the wrong place is off by
      // several (neighbours here differ by up to 9 levels).
      EXPECT_LE(worst, 1);
    }
  }
}

TEST(Upscale, TheEffectsRunAtTheScaledSizeAndOnePassWritesTheOutput) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const Camera camera = builtinSceneCamera(320, 180);
  const test::RenderedImage image = test::render(renderer, camera, scaled(0.5f), View::Final);
  EXPECT_EQ(renderer.lastFrame().camera.width, 160);
  EXPECT_EQ(renderer.lastFrame().camera.height, 90);
  EXPECT_EQ(renderer.lastFrame().outputWidth, 320);
  EXPECT_EQ(image.width, 320);
  // FXAA's pass does the upscale: one pass over the output.
  std::vector<std::string> passes = running(renderer);
  EXPECT_EQ(passes.back(), "fxaa");
  EXPECT_EQ(std::count(passes.begin(), passes.end(), "upscale"), 0);
  bool absorbed = false;
  for (const PlannedPass& pass : renderer.lastPlan().passes())
    absorbed = absorbed || (pass.live && pass.absorbed == std::vector<std::string>{"upscale"});
  EXPECT_TRUE(absorbed);
  // Without FXAA the resolution effect's own pass; with the display colour retained, both (FXAA at the scaled size).
  RenderSettings noFxaa = scaled(0.5f);
  noFxaa.set("fxaa", "off");
  test::render(renderer, camera, noFxaa, View::Final);
  EXPECT_EQ(running(renderer).back(), "upscale");
  test::render(renderer, camera, scaled(0.5f), View::Final, test::retaining({"display-color"}));
  passes = running(renderer);
  EXPECT_EQ(passes.back(), "upscale");
  EXPECT_NE(std::find(passes.begin(), passes.end(), "fxaa"), passes.end());
  EXPECT_EQ(renderer.retained("display-color").width(), 160);
  // A debug view shows its target at the scaled size over the whole output; split screen draws both halves.
  for (const View& view : {View::Ao, View::Split}) {
    const test::RenderedImage shown = test::render(renderer, camera, scaled(0.5f), view);
    EXPECT_EQ(shown.width, 320);
    EXPECT_EQ(renderer.lastFrame().camera.width, 160);
    int dark = 0;
    for (int x = 0; x < shown.width; x += 8) dark += shown.channel(x, 120, 0) < 250 ? 1 : 0;
    EXPECT_GT(dark, 4) << view.name;  // drawn across the output, not in its lower-left quarter only
  }
}

// The built-in scene at scale 0.5, upscaled by the edge filter (with FXAA, as by default), is closer to the frame
// rendered at full size than the bilinear upscale, over the whole image and over its edges. The bound (MAE at
// most 0.8 x bilinear's) is for the default 1280 x 720 frame, which obscura-bench measures (section 10: 0.75); at the
// 640 x 360 tested here the scene's details are finer against the pixels and both upscales lose more of them: 0.85,
// held within 0.9.
TEST(Upscale, AtHalfScaleTheEdgeUpscaleIsCloserToTheFullSizeFrameThanBilinear) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const Camera camera = builtinSceneCamera(640, 360);
  const Image full = topDown(test::render(renderer, camera, RenderSettings{}, View::Final));
  const UpscaleError bilinear =
      upscaleError(full, topDown(test::render(renderer, camera, scaled(0.5f, UpscaleFilter::Bilinear), View::Final)));
  const UpscaleError edge = upscaleError(full, topDown(test::render(renderer, camera, scaled(0.5f), View::Final)));
  RenderSettings unsharpened = scaled(0.5f);
  unsharpened.of<ResolutionSettings>().sharpness = 0.0f;
  const UpscaleError soft = upscaleError(full, topDown(test::render(renderer, camera, unsharpened, View::Final)));
  std::printf("640x360 at scale 0.5 against full size: MAE (edge pixels, %zu of %zu) bilinear %.3f (%.2f), "
              "edge %.3f (%.2f), edge unsharpened %.3f (%.2f); edge / bilinear %.3f\n",
              edge.edgePixels, edge.pixels, bilinear.mae, bilinear.edgeMae, edge.mae, edge.edgeMae, soft.mae,
              soft.edgeMae, edge.mae / bilinear.mae);
  EXPECT_LE(edge.mae, 0.9 * bilinear.mae);
  EXPECT_LT(edge.edgeMae, bilinear.edgeMae);
  EXPECT_LT(soft.mae, bilinear.mae);
}

// A new render scale drops the history targets (TAA's colour and depth, the temporal AO's) with the old size, and
// keeps the previous camera: the frame after a change is the same whatever scale the frames before it had.
TEST(Upscale, TheFrameAfterAScaleChangeShowsNothingOfTheFramesBefore) {
  RenderSettings settings = scaled(0.5f);
  settings.set("taa", "on");
  settings.set("ao.temporal", "on");
  const Camera camera = builtinSceneCamera(240, 136);
  std::vector<std::vector<std::uint8_t>> after;
  for (float before : {1.0f, 0.75f}) {
    Renderer renderer = test::makeRenderer();
    renderer.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
    RenderSettings first = settings;
    first.of<ResolutionSettings>().scale = before;
    for (int frame = 0; frame < 6; ++frame) test::render(renderer, camera, first, View::Final);
    const int drops = renderer.historyDrops();
    after.push_back(test::render(renderer, camera, settings, View::Final).rgba);
    EXPECT_GT(renderer.historyDrops(), drops);
    EXPECT_EQ(renderer.lastFrame().historyFrames, 0);
    EXPECT_TRUE(renderer.lastFrame().hasPrevious) << "the camera's history stays: motion vectors need it";
  }
  EXPECT_EQ(after[0], after[1]);
}

TEST(Upscale, DynamicResolutionDrawsTheViewersFramesAtTheScaleItChose) {
  Viewer viewer(test::context().caps());
  viewer.state().setDefault("resolution.dynamic", "on");
  EXPECT_EQ(viewer.state().toQuery().find("resolution.dynamic"), std::string::npos) << "the viewer's own default";
  const gl::RenderTarget output("viewer output", 320, 180, GL_NEAREST, gl::RenderTarget::Depth::None, false);
  // The first frame is the cheapest: the smallest scale (resolution.min-scale).
  viewer.render(output.framebuffer(), 320, 180);
  EXPECT_EQ(viewer.renderScale(), 0.5f);
  EXPECT_EQ(viewer.renderer()->lastFrame().camera.width, 160);
  EXPECT_EQ(viewer.renderer()->lastFrame().outputWidth, 320);
  // Frames far under the target (33.3 ms): up to the largest scale.
  while (viewer.dynamicResolution().refining()) viewer.frameMeasured(2.0, viewer.renderScale());
  viewer.render(output.framebuffer(), 320, 180);
  EXPECT_EQ(viewer.renderScale(), 1.0f);
  // Frames far over it: down, and the next frame is drawn smaller.
  for (int frame = 0; frame < 4; ++frame) viewer.frameMeasured(200.0, viewer.renderScale());
  viewer.render(output.framebuffer(), 320, 180);
  EXPECT_LT(viewer.renderScale(), 1.0f);
  EXPECT_EQ(viewer.renderer()->lastFrame().camera.width, renderSize({320, 180}, viewer.renderScale()).x);
  viewer.state().settings.set("resolution.dynamic", "off");
  viewer.render(output.framebuffer(), 320, 180);
  EXPECT_EQ(viewer.renderScale(), 1.0f);
  EXPECT_NE(viewer.state().toQuery().find("resolution.dynamic=off"), std::string::npos);
}

// Quick start (resolution.quick-start): the Renderer's first frame is the lit scene without the effects that add
// passes of their own; the next frames warm the full frame's passes, and the full frame that follows by itself is the
// one a Renderer without quick start draws.
TEST(Upscale, QuickStartDrawsTheLitSceneFirstThenTheFullFrameAsWithoutIt) {
  const Camera camera = builtinSceneCamera(320, 180);
  RenderSettings settings = scaled(0.5f);  // the page's first frames: scale 0.5
  Renderer plain = test::makeRenderer();
  plain.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const test::RenderedImage full = test::render(plain, camera, settings, View::Final);
  EXPECT_FALSE(plain.lastFrameCheap());
  EXPECT_EQ(plain.quickStart().firstFullFrame, 0) << "without quick start the first frame is the full one";
  EXPECT_EQ(plain.quickStart().cheapFrames, 0);

  settings.set("resolution.quick-start", "on");
  ASSERT_TRUE(Renderer::quickStartSettings(settings).has_value());
  Renderer quick = test::makeRenderer();
  quick.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const test::RenderedImage cheap = test::render(quick, camera, settings, View::Final);
  EXPECT_TRUE(quick.lastFrameCheap());
  const std::vector<std::string> cheapPasses = running(quick);
  for (const char* pass : {"sao", "blur-h", "fxaa"})
    EXPECT_EQ(std::count(cheapPasses.begin(), cheapPasses.end(), pass), 0) << pass;
  EXPECT_EQ(cheapPasses.back(), "upscale") << "the bilinear upscale writes the output";
  EXPECT_TRUE(quick.quickStart().warmed.empty()) << "the first frame warms nothing";
  // A real, lit image: the same scene as the full frame, a little lighter (no AO) and not antialiased.
  double sum = 0.0, lighter = 0.0;
  for (size_t i = 0; i < cheap.rgba.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) {
      sum += std::abs(static_cast<int>(cheap.rgba[i + c]) - static_cast<int>(full.rgba[i + c]));
      lighter += static_cast<int>(cheap.rgba[i + c]) - static_cast<int>(full.rgba[i + c]);
    }
  const double pixels = static_cast<double>(cheap.rgba.size() / 4) * 3.0;
  EXPECT_GT(sum / pixels, 0.1) << "the cheap frame is not the full one";
  EXPECT_LT(sum / pixels, 12.0) << "the cheap frame shows the scene the full one shows";
  EXPECT_GT(lighter, 0.0) << "without the AO's darkening";

  int frames = 1;
  test::RenderedImage last;
  while (quick.lastFrameCheap() && frames < Renderer::kMaxCheapFrames + 2) {
    last = test::render(quick, camera, settings, View::Final);
    ++frames;
  }
  const QuickStartReport& report = quick.quickStart();
  EXPECT_FALSE(quick.lastFrameCheap());
  EXPECT_GE(report.cheapFrames, 2);
  EXPECT_LT(report.cheapFrames, Renderer::kMaxCheapFrames) << "every pass warmed before the cap";
  EXPECT_EQ(report.firstFullFrame, report.cheapFrames);
  std::vector<std::string> warmed;
  for (const QuickStartReport::Warmed& w : report.warmed) {
    warmed.push_back(w.pass);
    EXPECT_GE(w.frame, 1u);
  }
  EXPECT_EQ(warmed, running(quick)) << "each pass of the full frame warmed once, in order";
  // Warming left nothing behind: the full frame is the one drawn without quick start, to the bit.
  EXPECT_EQ(test::worstByteDifference(last, full), 0);
  // Later frames are full ones.
  test::render(quick, camera, settings, View::Final);
  EXPECT_FALSE(quick.lastFrameCheap());
}

// The same into an output with a depth buffer of its own (the canvas's, the window's: FrameContext::outputDepth), at
// scale 1, where the cheap frame's lighting may draw straight into the output: the warm output has one too, and the
// full frame after quick start is still the one drawn without it.
TEST(Upscale, QuickStartIntoAnOutputWithDepthEndsInTheFullFrameAsWithoutIt) {
  const Camera camera = builtinSceneCamera(160, 90);
  const gl::GlCaps& caps = test::context().caps();
  const gl::RenderTarget output("output with depth", camera.width, camera.height, GL_NEAREST,
                                gl::RenderTarget::Depth::Renderbuffer, caps.depth24);
  auto draw = [&](Renderer& renderer, const RenderSettings& settings) {
    renderer.render(camera, settings, View::Final, OutputTarget{output.framebuffer(), camera.width, camera.height, {}});
    return test::RenderedImage{camera.width, camera.height, output.readRgba()};
  };
  RenderSettings settings;
  Renderer plain = test::makeRenderer();
  plain.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const test::RenderedImage full = draw(plain, settings);
  EXPECT_TRUE(plain.lastFrame().outputDepth);

  settings.set("resolution.quick-start", "on");
  Renderer quick = test::makeRenderer();
  quick.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  test::RenderedImage last = draw(quick, settings);
  EXPECT_TRUE(quick.lastFrameCheap());
  const int frames = quick.quickStart().cheapFrames;
  for (int frame = 0; frame < Renderer::kMaxCheapFrames && quick.lastFrameCheap(); ++frame)
    last = draw(quick, settings);
  EXPECT_FALSE(quick.lastFrameCheap());
  EXPECT_GE(quick.quickStart().cheapFrames, frames + 1);
  EXPECT_EQ(test::worstByteDifference(last, full), 0);
}

// Renderer::prepare (what the page does at start-up): the programs of the frame the next render() draws are begun, a
// rehearsal drawing nothing; that frame then builds no program of its own and is, to the bit, the frame drawn without
// it. With quick start, the cheap frame's programs; without, the full frame's; the animated built-in scene too (its
// skinned and CPU-deformed draws rehearsed before any frame posed it).
TEST(Upscale, PrepareBeginsTheNextFramesProgramsAndChangesNothingElse) {
  test::context();
  const Camera camera = builtinSceneCamera(320, 180);
  const gl::RenderTarget output("prepared output", camera.width, camera.height, GL_NEAREST,
                                gl::RenderTarget::Depth::None, false);
  const OutputTarget target{output.framebuffer(), camera.width, camera.height, {}};
  for (const bool quickStart : {true, false})
    for (const bool animated : {false, true}) {
      SCOPED_TRACE(std::string(quickStart ? "quick start" : "no quick start") + (animated ? ", animated" : ""));
      RenderSettings settings = scaled(0.5f);
      settings.set("resolution.quick-start", quickStart ? "on" : "off");
      const Scene scene = makeBuiltinScene(animated ? BuiltinSceneOptions{} : BuiltinSceneOptions::still());
      FrameOptions options;
      options.time = 0.25;
      Renderer plain = test::makeRenderer();
      plain.setScene(scene);
      const test::RenderedImage expected = test::render(plain, camera, settings, View::Final, options);

      Renderer prepared = test::makeRenderer();
      prepared.setScene(scene);
      const size_t before = prepared.programs().size();  // the Renderer builds one for itself (velocity[camera])
      const size_t begun = prepared.prepare(camera, settings, target, options);
      EXPECT_GE(begun, quickStart ? 3u : 6u) << "the G-buffer's, the lighting's and the upscale's at least";
      EXPECT_EQ(prepared.programs().pending(), begun);
      EXPECT_EQ(prepared.programs().size(), before + begun) << "a rehearsal builds nothing else";
      EXPECT_TRUE(prepared.quickStart().warmed.empty());
      const test::RenderedImage first = test::render(prepared, camera, settings, View::Final, options);
      EXPECT_EQ(prepared.lastFrameCheap(), quickStart);
      EXPECT_EQ(prepared.programs().pending(), 0u);
      EXPECT_EQ(prepared.programs().size(), before + begun) << "the frame drew with the programs begun, no other";
      EXPECT_EQ(test::worstByteDifference(first, expected), 0);
    }
  // Prepared for one frame, another drawn (another view): what it did not use is dropped after it.
  RenderSettings settings = scaled(0.5f);
  Renderer changed = test::makeRenderer();
  changed.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const int programsBefore = gl::liveObjects().programs;
  EXPECT_GT(changed.prepare(camera, settings, target), 0u);
  test::render(changed, camera, settings, View::Ao);
  EXPECT_EQ(changed.programs().pending(), 0u);
  const int programsAfter = gl::liveObjects().programs;
  Renderer unprepared = test::makeRenderer();
  unprepared.setScene(makeBuiltinScene(BuiltinSceneOptions::still()));
  const int programsUnprepared = gl::liveObjects().programs;
  test::render(unprepared, camera, settings, View::Ao);
  EXPECT_EQ(programsAfter - programsBefore, gl::liveObjects().programs - programsUnprepared)
      << "as many programs as a Renderer that was not prepared";
}
