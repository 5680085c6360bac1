// Edges from the G-buffer (effects/edges/EdgesEffect.h). The CPU mirror against eq. 1 written out on planes and steps;
// the GPU's passes read back against the mirror; and the lines of a cube on a floor against the reference, the cube's
// silhouette and crease lines projected analytically from the camera and the cube's geometry (the edges of its
// front-facing faces: a convex body on a floor hides none of them), at two distances: precision and recall of the
// drawn line pixels, no ink on the flat faces or the floor, the line width in pixels, and the image moved towards
// the reference drawn by supersampling those lines.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "effects/edges/EdgesEffect.h"
#include "encoding/NormalEncoding.h"
#include "encoding/ToneMapping.h"
#include "frame/FrameContext.h"
#include "gl/PipelineState.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

constexpr int kWidth = 320, kHeight = 180;
constexpr float kFovy = 50.0f;

// A 1 m cube standing on a floor 400 m square (so the floor fills the view: no horizon, no floor boundary).
Scene cubeOnAFloor() {
  return test::sceneOf({makeBox(glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 1.0f, 0.5f)),
                        test::makeRectangle(glm::vec3(-200.0f, 0.0f, 200.0f), glm::vec3(400.0f, 0.0f, 0.0f),
                                            glm::vec3(0.0f, 0.0f, -400.0f))});
}

// Looking at the cube's centre from 30 degrees round the y axis and 35 degrees up: its top and two sides show.
Camera cubeCamera(float distance) {
  const float azimuth = glm::radians(30.0f), elevation = glm::radians(35.0f);
  const glm::vec3 target(0.0f, 0.5f, 0.0f);
  const glm::vec3 direction(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                            std::cos(azimuth) * std::cos(elevation));
  return test::makeCamera(target + distance * direction, target, kWidth, kHeight, 0.1f, 100.0f, kFovy);
}

EdgesSettings linesOf(float width) {
  EdgesSettings s;
  s.enabled = true;
  s.width = width;
  s.color = glm::vec3(1.0f, 0.0f, 0.0f);  // red on a grey scene: the coverage can be read back
  return s;
}

RenderSettings plainFrame() {
  RenderSettings settings;
  settings.set("fxaa", "off");
  // Grey light (a uniform environment, as dim as the old hemisphere's) on the grey scene, so that the red lines'
  // coverage reads back from colour.
  settings.set("lighting.environment", "uniform");
  settings.set("lighting.environment-intensity", "0.45");
  // Undithered: the lines are measured against references that average display values, where a step of noise
  // would only add its own error.
  settings.set("dither", "off");
  return settings;
}

struct Segment {
  glm::vec2 a, b;  // image pixels, x right, y down, pixel centres at + 0.5
};

float distanceToSegment(glm::vec2 p, const Segment& s) {
  const glm::vec2 ab = s.b - s.a;
  const float t = std::clamp(glm::dot(p - s.a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
  return glm::length(p - (s.a + t * ab));
}

float distanceToLines(glm::vec2 p, const std::vector<Segment>& lines) {
  float best = 1e30f;
  for (const Segment& s : lines) best = std::min(best, distanceToSegment(p, s));
  return best;
}

// The reference: the cube's edges that border a face turned towards the camera, projected into the image.
std::vector<Segment> cubeLines(const Camera& camera) {
  const glm::vec3 lo(-0.5f, 0.0f, -0.5f), hi(0.5f, 1.0f, 0.5f);
  auto corner = [&](int i) { return glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
  const FrameCamera frame = FrameCamera::from(camera, kWidth, kHeight);
  auto project = [&](const glm::vec3& p) {
    const glm::vec4 clip = frame.unjitteredProjection * frame.view * glm::vec4(p, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return glm::vec2((ndc.x * 0.5f + 0.5f) * kWidth, (0.5f - ndc.y * 0.5f) * kHeight);
  };
  std::vector<Segment> lines;
  for (int i = 0; i < 8; ++i)
    for (int axis = 0; axis < 3; ++axis) {
      const int j = i | (1 << axis);
      if (j == i) continue;
      // The edge from corner i to corner j runs along `axis`; its two faces are normal to the other two axes, on
      // the sides corner i lies on.
      bool seen = false;
      for (int other = 0; other < 3; ++other) {
        if (other == axis) continue;
        glm::vec3 normal(0.0f), onFace = corner(i);
        normal[other] = (i >> other) & 1 ? 1.0f : -1.0f;
        seen = seen || glm::dot(normal, camera.eye - onFace) > 0.0f;
      }
      if (seen) lines.push_back({project(corner(i)), project(corner(j))});
    }
  return lines;
}

// Coverage of the red line per pixel, read from the frame with and without the lines: on = off + a (red - off).
std::vector<float> coverageOf(const test::RenderedImage& off, const test::RenderedImage& on) {
  std::vector<float> a(static_cast<size_t>(kWidth) * kHeight);
  for (size_t i = 0; i < a.size(); ++i) {
    const glm::vec3 o(off.rgba[i * 4], off.rgba[i * 4 + 1], off.rgba[i * 4 + 2]);
    const glm::vec3 n(on.rgba[i * 4], on.rgba[i * 4 + 1], on.rgba[i * 4 + 2]);
    const glm::vec3 toRed = glm::vec3(255.0f, 0.0f, 0.0f) - o;
    a[i] = glm::dot(n - o, toRed) / std::max(glm::dot(toRed, toRed), 1.0f);
  }
  return a;
}

struct LineScore {
  double precision = 0.0, recall = 0.0, meanWidth = 0.0;
  int linePixels = 0, stray = 0;
  double errorOn = 0.0, errorOff = 0.0;  // mean |image - reference| per channel, bytes
};

LineScore score(const test::RenderedImage& off, const test::RenderedImage& on, const std::vector<Segment>& lines,
                float width) {
  const std::vector<float> a = coverageOf(off, on);
  LineScore s;
  const float margin = width * 0.5f + 1.0f;
  double ink = 0.0;
  int near = 0;
  std::vector<glm::vec2> drawn;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const float coverage = a[static_cast<size_t>(y) * kWidth + x];
      const glm::vec2 centre(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const float d = distanceToLines(centre, lines);
      ink += coverage;
      if (coverage > 0.02f && d > margin + 1.0f) ++s.stray;
      if (coverage <= 0.5f) continue;
      drawn.push_back(centre);
      ++s.linePixels;
      near += d <= margin;
    }
  s.precision = s.linePixels > 0 ? static_cast<double>(near) / s.linePixels : 0.0;
  double length = 0.0;
  int samples = 0, found = 0;
  for (const Segment& segment : lines) {
    const float l = glm::length(segment.b - segment.a);
    length += l;
    const int steps = std::max(1, static_cast<int>(l * 2.0f));
    for (int k = 0; k <= steps; ++k) {
      const glm::vec2 p = segment.a + (segment.b - segment.a) * (static_cast<float>(k) / static_cast<float>(steps));
      ++samples;
      for (const glm::vec2& q : drawn)
        if (glm::length(q - p) <= margin) {
          ++found;
          break;
        }
    }
  }
  s.recall = static_cast<double>(found) / samples;
  s.meanWidth = ink / length;
  // The reference image: the lines of `width` centred on the analytic segments, coverage by 4 x 4 supersampling.
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const size_t i = static_cast<size_t>(y) * kWidth + x;
      int inside = 0;
      for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
          const glm::vec2 p(static_cast<float>(x) + (static_cast<float>(sx) + 0.5f) / 4.0f,
                            static_cast<float>(y) + (static_cast<float>(sy) + 0.5f) / 4.0f);
          inside += distanceToLines(p, lines) <= width * 0.5f;
        }
      const float c = static_cast<float>(inside) / 16.0f;
      const glm::vec3 o(off.rgba[i * 4], off.rgba[i * 4 + 1], off.rgba[i * 4 + 2]);
      const glm::vec3 n(on.rgba[i * 4], on.rgba[i * 4 + 1], on.rgba[i * 4 + 2]);
      const glm::vec3 reference = o + c * (glm::vec3(255.0f, 0.0f, 0.0f) - o);
      for (int ch = 0; ch < 3; ++ch) {
        s.errorOn += std::abs(n[ch] - reference[ch]);
        s.errorOff += std::abs(o[ch] - reference[ch]);
      }
    }
  s.errorOn /= 3.0 * kWidth * kHeight;
  s.errorOff /= 3.0 * kWidth * kHeight;
  return s;
}

}  // namespace

TEST(Edges, TheSecondDifferenceOfReciprocalDepthIsZeroOnPlanesAndTheJumpAtProfiles) {
  // A plane seen at any slant: 1/z = a + b x along a row. Its first-order relative difference grows with the slant;
  // eq. 1 stays 0.
  const EdgeDetector perspective;
  for (float slope : {0.0f, 0.01f, 0.05f, 0.2f}) {
    auto z = [slope](float x) { return 1.0f / (0.25f - slope * 0.001f * x); };
    const float d = perspective.relativeSecondDifference(z(100.0f), z(99.0f), z(101.0f));
    EXPECT_NEAR(d, 0.0f, 1e-5f) << "slope " << slope;
  }
  // A profile: a flat near side at 4 m over a far side at 5 m. The near pixel sees the relative jump, negative;
  // the far pixel the same positive; the background is 1/z = 0.
  EXPECT_NEAR(perspective.relativeSecondDifference(4.0f, 4.0f, 5.0f), 4.0f / 5.0f - 1.0f, 1e-6f);
  EXPECT_GT(perspective.relativeSecondDifference(5.0f, 4.0f, 5.0f), 0.0f);
  EXPECT_NEAR(perspective.relativeSecondDifference(4.0f, 4.0f, 0.0f), -1.0f, 1e-6f);
  // Scale-aware: the scene and camera scaled by k give the same value.
  for (float k : {0.01f, 1.0f, 300.0f})
    EXPECT_NEAR(perspective.relativeSecondDifference(4.0f * k, 4.1f * k, 6.0f * k),
                perspective.relativeSecondDifference(4.0f, 4.1f, 6.0f), 1e-5f);
  // Orthographic: depth itself is affine on a plane, so its second difference is 0 at any slant; a jump counts
  // relative to the view's height L, as the perspective measure does at z = L to first order.
  const EdgeDetector orthographic = EdgeDetector::of(EdgesSettings{}, 0.0f, 100.0f, 8.0f);
  for (float slope : {0.0f, 0.05f, 3.0f})
    EXPECT_NEAR(orthographic.relativeSecondDifference(10.0f, 10.0f - slope, 10.0f + slope), 0.0f, 1e-5f);
  EXPECT_NEAR(orthographic.relativeSecondDifference(4.0f, 4.0f, 4.08f), -0.01f, 1e-6f);
  EXPECT_NEAR(orthographic.relativeSecondDifference(4.0f, 4.0f, 4.08f),
              perspective.relativeSecondDifference(8.0f, 8.0f, 8.08f), 1e-4f);
  EXPECT_LT(orthographic.relativeSecondDifference(4.0f, 4.0f, 0.0f), -1e6f) << "a background neighbour";
}

TEST(Edges, CoverageAndToonBands) {
  EXPECT_EQ(lineRadius(1.0f), 0);
  EXPECT_EQ(lineRadius(1.5f), 1);
  EXPECT_EQ(lineRadius(3.0f), 1);
  EXPECT_EQ(lineRadius(3.5f), 2);
  EXPECT_EQ(lineRadius(8.0f), EdgesEffect::kMaxRadius);
  // Eq. 2: whole inside width / 2, a ramp one pixel wide outside it; nothing at R + 1.
  EXPECT_FLOAT_EQ(lineCoverage(0.0f, 1.0f, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(lineCoverage(1.0f, 1.0f, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(lineCoverage(1.0f, 2.0f, 0.5f), 0.25f);
  for (float width : {1.0f, 1.5f, 2.5f, 4.0f, 8.0f})
    EXPECT_EQ(lineCoverage(static_cast<float>(lineRadius(width) + 1), width, 1.0f), 0.0f) << width;
  // Toon: the luma lands on the centre of its band; the hue is kept.
  const glm::vec3 c(0.3f, 0.5f, 0.2f);
  const glm::vec3 t = toonShade(c, 4);
  EXPECT_NEAR(fxaaLuma(t), 0.375f, 1e-5f);
  EXPECT_NEAR(t.r / t.g, c.r / c.g, 1e-5f);
  EXPECT_NEAR(fxaaLuma(toonShade(glm::vec3(1.0f), 4)), 0.875f, 1e-5f);
}

// Every pass against the mirror: the mask from the read-back G-buffer, then the drawn image from the image without
// lines, in both styles, at widths that use radii 0 .. 4, with colour edges on.
// Through an orthographic camera (the cube's view as wide at its target) the detect pass matches the orthographic
// mirror: the cube's silhouette and creases are found, the floor (a plane seen at a slant) is not an edge.
TEST(Edges, TheDetectPassMatchesTheOrthographicMirror) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(cubeOnAFloor());
  const Camera camera = cubeCamera(4.0f).asOrthographic();
  RenderSettings settings = plainFrame();
  const EdgesSettings edges = linesOf(1.5f);
  settings.of<EdgesSettings>() = edges;
  test::render(renderer, camera, settings, View::Final, test::retaining({"gbuffer", "edges-mask"}));
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  const std::vector<std::uint8_t> mask = renderer.retained("edges-mask").readRgba();
  const FrameCamera frame = FrameCamera::from(camera, kWidth, kHeight);
  const std::vector<EdgeFlags> expected =
      EdgeDetector::of(edges, frame.near, frame.far, 2.0f * frame.halfExtent.y).detect(gbuffer, kWidth, kHeight);
  int mismatches = 0, profiles = 0, creases = 0;
  for (size_t i = 0; i < expected.size(); ++i) {
    profiles += expected[i].profile;
    creases += expected[i].crease;
    mismatches += (mask[i * 4] > 127) != expected[i].profile || (mask[i * 4 + 1] > 127) != expected[i].crease;
  }
  std::printf("edges mask, orthographic: %d profile, %d crease pixels; %d differ from the mirror\n", profiles, creases,
              mismatches);
  EXPECT_LE(mismatches, 2);
  EXPECT_GT(profiles, 100);
  EXPECT_GT(creases, 100);
}

TEST(Edges, ThePassesMatchTheMirror) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(cubeOnAFloor());
  const Camera camera = cubeCamera(4.0f);
  const RenderSettings plain = plainFrame();
  const test::RenderedImage off =
      test::render(renderer, camera, plain, View::Final, test::retaining({"gbuffer", "display-color"}));
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  const std::vector<std::uint8_t> display = renderer.retained("display-color").readRgba();
  std::vector<float> luma(static_cast<size_t>(kWidth) * kHeight);  // display-color's alpha, as the pass reads it
  for (size_t i = 0; i < luma.size(); ++i) luma[i] = static_cast<float>(display[i * 4 + 3]) / 255.0f;

  for (bool colorEdges : {false, true}) {
    RenderSettings settings = plain;
    EdgesSettings edges = linesOf(1.5f);
    if (colorEdges) edges.colorThreshold = 0.05f;
    settings.of<EdgesSettings>() = edges;
    test::render(renderer, camera, settings, View::Final, test::retaining({"edges-mask"}));
    const std::vector<std::uint8_t> mask = renderer.retained("edges-mask").readRgba();
    const FrameCamera frame = FrameCamera::from(camera, kWidth, kHeight);
    const std::vector<EdgeFlags> expected =
        EdgeDetector::of(edges, frame.near, frame.far).detect(gbuffer, kWidth, kHeight, luma);
    int mismatches = 0, profiles = 0, creases = 0, colors = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
      const EdgeFlags& e = expected[i];
      profiles += e.profile;
      creases += e.crease;
      colors += e.color;
      mismatches += (mask[i * 4] > 127) != e.profile || (mask[i * 4 + 1] > 127) != e.crease ||
                    (mask[i * 4 + 2] > 127) != e.color;
    }
    std::printf("edges mask%s: %d profile, %d crease, %d colour pixels; %d differ from the mirror\n",
                colorEdges ? " with colour edges" : "", profiles, creases, colors, mismatches);
    EXPECT_LE(mismatches, 2);
    EXPECT_GT(profiles, 100);
    EXPECT_GT(creases, 100);
    if (colorEdges) {
      EXPECT_GT(colors, 10);
    }
  }

  const std::vector<EdgeFlags> mask =
      EdgeDetector::of(linesOf(1.0f), 0.1f, 100.0f).detect(gbuffer, kWidth, kHeight);
  for (EdgeStyle style : {EdgeStyle::Lines, EdgeStyle::Toon})
    for (float width : {1.0f, 2.5f, 4.0f, 6.0f, 8.0f}) {
      RenderSettings settings = plain;
      EdgesSettings edges = linesOf(width);
      edges.style = style;
      edges.strength = 0.8f;
      settings.of<EdgesSettings>() = edges;
      const test::RenderedImage on = test::render(renderer, camera, settings, View::Final);
      const std::vector<float> distance = edgeDistances(mask, kWidth, kHeight, lineRadius(width));
      float worst = 0.0f;
      for (size_t i = 0; i < distance.size(); ++i) {
        glm::vec3 base = glm::vec3(off.rgba[i * 4], off.rgba[i * 4 + 1], off.rgba[i * 4 + 2]) / 255.0f;
        if (style == EdgeStyle::Toon) base = toonShade(base, edges.bands);
        const float a = lineCoverage(distance[i], width, edges.strength);
        const glm::vec3 expected = glm::mix(base, linearToSrgb(edges.color), a);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(on.rgba[i * 4 + c] / 255.0f - expected[c]));
      }
      std::printf("edges %s, width %.1f: worst %.2f / 255 from the mirror\n", edgeStyleName(style), width,
                  worst * 255.0f);
      EXPECT_LE(worst * 255.0f, 1.5f) << edgeStyleName(style) << " width " << width;
    }
}

TEST(Edges, CubeLinesLieOnItsSilhouetteAndCreasesAtTwoDistances) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(cubeOnAFloor());
  for (float distance : {3.0f, 6.0f}) {
    const Camera camera = cubeCamera(distance);
    const std::vector<Segment> lines = cubeLines(camera);
    ASSERT_EQ(lines.size(), 9u) << "the top's four edges, three upright ones, two on the floor";
    const test::RenderedImage off = test::render(renderer, camera, plainFrame(), View::Final);
    std::vector<double> widths;
    for (float width : {1.0f, 2.0f, 4.0f}) {
      RenderSettings settings = plainFrame();
      settings.of<EdgesSettings>() = linesOf(width);
      const test::RenderedImage on = test::render(renderer, camera, settings, View::Final);
      const LineScore s = score(off, on, lines, width);
      std::printf("edges at %.0f m, width %.0f: %d line pixels, precision %.4f, recall %.4f, %d stray; mean width "
                  "%.2f px; error against the reference %.2f (without lines %.2f)\n",
                  distance, width, s.linePixels, s.precision, s.recall, s.stray, s.meanWidth, s.errorOn, s.errorOff);
      EXPECT_GE(s.precision, 0.99) << distance << " m, width " << width;
      EXPECT_GE(s.recall, 0.98) << distance << " m, width " << width;
      EXPECT_EQ(s.stray, 0) << "no ink on the flat faces or the floor";
      // A line one pixel wide sits on whole pixels, the reference's straddles two at half coverage: the margin is
      // smaller there.
      EXPECT_LT(s.errorOn, (width >= 2.0f ? 0.5 : 0.9) * s.errorOff)
          << "the lines move the image towards the reference";
      widths.push_back(s.meanWidth);
    }
    EXPECT_GT(widths[2], widths[1]);
    EXPECT_GT(widths[1], widths[0]);
  }
}

TEST(Edges, LinesKeepTheirPixelWidthAsTheCameraMovesAway) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(cubeOnAFloor());
  for (float width : {1.5f, 3.0f, 5.0f}) {
    std::vector<double> measured;
    for (float distance : {2.5f, 4.0f, 7.0f}) {
      const Camera camera = cubeCamera(distance);
      const test::RenderedImage off = test::render(renderer, camera, plainFrame(), View::Final);
      RenderSettings settings = plainFrame();
      settings.of<EdgesSettings>() = linesOf(width);
      const test::RenderedImage on = test::render(renderer, camera, settings, View::Final);
      measured.push_back(score(off, on, cubeLines(camera), width).meanWidth);
    }
    std::printf("edges width %.1f px: mean width %.2f, %.2f, %.2f px at 2.5, 4 and 7 m\n", width, measured[0],
                measured[1], measured[2]);
    for (double m : measured) {
      EXPECT_GT(m, 0.75 * width) << width;
      EXPECT_LT(m, 1.35 * width) << width;
    }
    EXPECT_LT(std::abs(measured[2] - measured[0]), 0.15 * width) << "the same width in pixels near and far";
  }
}

// A plane filling the view at steep angles (the view's top edge up to 89 degrees from its normal): its first-order
// relative depth difference passes the depth threshold at the steepest (a first-order test would draw it there),
// eq. 1 stays far under it at every angle, and no line is drawn.
TEST(Edges, ASlantedPlaneIsNotAnEdge) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(test::sceneOf({test::makeRectangle(glm::vec3(-500.0f, 0.0f, 500.0f),
                                                       glm::vec3(1000.0f, 0.0f, 0.0f),
                                                       glm::vec3(0.0f, 0.0f, -1000.0f))}));
  const float fovy = 12.0f;
  float steepestFirstOrder = 0.0f;
  EdgesSettings edges = linesOf(2.0f);
  edges.depthThreshold = 0.02f;
  for (float degrees : {30.0f, 60.0f, 75.0f, 83.0f}) {
    // The camera 3 m from the origin, tilted so that the view's centre meets the plane y = 0 at `degrees` from its
    // normal and the view's top edge at degrees + fovy / 2.
    const float tilt = glm::radians(degrees);
    const glm::vec3 eye(0.0f, 3.0f * std::cos(tilt), 3.0f * std::sin(tilt));
    const Camera camera = test::makeCamera(eye, glm::vec3(0.0f), kWidth, kHeight, 0.1f, 100.0f, fovy);
    RenderSettings settings = plainFrame();
    settings.of<EdgesSettings>() = edges;
    const test::RenderedImage off =
        test::render(renderer, camera, plainFrame(), View::Final, test::retaining({"gbuffer"}));
    const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
    const test::RenderedImage on =
        test::render(renderer, camera, settings, View::Final, test::retaining({"edges-mask"}));
    const std::vector<std::uint8_t> mask = renderer.retained("edges-mask").readRgba();
    const EdgeDetector detector = EdgeDetector::of(edges, 0.1f, 100.0f);
    float firstOrder = 0.0f, secondOrder = 0.0f;
    int background = 0;
    for (int y = 1; y + 1 < kHeight; ++y)
      for (int x = 1; x + 1 < kWidth; ++x) {
        const size_t i = static_cast<size_t>(y) * kWidth + x;
        const float z = detector.viewDepth(&gbuffer[i * 4]);
        background += z == 0.0f;
        const float za = detector.viewDepth(&gbuffer[(i - kWidth) * 4]);
        const float zb = detector.viewDepth(&gbuffer[(i + kWidth) * 4]);
        firstOrder = std::max(firstOrder, std::abs(zb - za) / (2.0f * z));
        secondOrder = std::max(secondOrder, std::abs(detector.relativeSecondDifference(z, za, zb)));
      }
    // No pixel marked, and the image as without the lines (to one step: the two frames' AO may round apart).
    int marked = 0;
    for (size_t i = 0; i < mask.size(); i += 4) marked += mask[i] > 127 || mask[i + 1] > 127 || mask[i + 2] > 127;
    const int changed = static_cast<int>(test::bytesDifferingBeyond(on.rgba, off.rgba, 1));
    std::printf("edges, plane at %.0f degrees: first-order relative difference up to %.4f, second-order %.5f "
                "(threshold %.3f); %d pixels marked, %d bytes changed\n",
                degrees, firstOrder, secondOrder, detector.depthThreshold, marked, changed);
    ASSERT_EQ(background, 0) << "the plane must fill the view";
    EXPECT_LT(secondOrder, 0.25f * detector.depthThreshold) << degrees;
    EXPECT_EQ(marked, 0) << degrees;
    EXPECT_EQ(changed, 0) << degrees;
    steepestFirstOrder = firstOrder;
  }
  EXPECT_GT(steepestFirstOrder, edges.depthThreshold) << "a first-order test would mark the steepest plane";
}

// The edges read display-color, not scene-color: the lighting still applies the tone curve itself. With every
// effect on, the toon style and colour edges, the split view comparing the edges, and the mask's view, every pass
// leaves the baseline GL state (the test renderer checks for GL errors after each pass).
TEST(Edges, KeepTheToneMappingAbsorbedAndLeaveTheBaselineState) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(cubeOnAFloor());
  const Camera camera = cubeCamera(4.0f);
  RenderSettings settings;
  settings.set("edges", "on");
  test::render(renderer, camera, settings, View::Final);
  std::vector<std::string> names;
  for (const PlannedPass& pass : renderer.lastPlan().passes()) {
    if (!pass.live) continue;
    names.push_back(pass.decl.name);
    for (const std::string& absorbed : pass.absorbed) names.push_back(absorbed + " (done by " + pass.decl.name + ")");
  }
  for (const char* expected : {"edges-detect", "edges-h", "edges", "tonemap (done by lighting)"})
    EXPECT_EQ(std::count(names.begin(), names.end(), expected), 1) << expected;

  settings = RenderSettings::everyEffectOn();
  settings.set("edges.style", "toon");
  settings.set("edges.color-threshold", "0.1");
  View split = View::Split;
  split.compare = "edges";
  for (const View& view : {View::Final, split, View{"edges-mask"}}) {
    EXPECT_NO_THROW(test::render(renderer, camera, settings, view)) << view.name;
    EXPECT_EQ(gl::baselineStateDifferences(), "") << view.name;
  }
}

// Hatching's tone (Hatching.h, the CPU mirror): on a lit plane, the share of the paper the strokes cover grows band by
// band as the luma falls, from none in the lightest band; and the period follows the pixel's size, so strokes keep
// their spacing in pixels at any distance.
TEST(Edges, HatchingDensityFollowsTheLumaInBands) {
  const int bands = 4;
  const float spacing = 6.0f, pixel = 0.01f;  // a pixel 1 cm wide: strokes about 6 cm apart
  double previous = -1.0;
  for (int band = bands - 1; band >= 0; --band) {
    const float luma = (static_cast<float>(band) + 0.5f) / static_cast<float>(bands);
    double covered = 0.0;
    int samples = 0;
    for (int y = 0; y < 200; ++y)
      for (int x = 0; x < 200; ++x) {
        // A wall facing +z, sampled a pixel apart.
        const glm::vec3 p(static_cast<float>(x) * pixel, static_cast<float>(y) * pixel, 0.0f);
        const glm::vec3 c = hatchedColor(glm::vec3(luma), p, glm::vec3(0.0f, 0.0f, 1.0f), pixel, spacing, bands,
                                         glm::vec3(0.0f));
        covered += 1.0 - c.r;
        ++samples;
      }
    const double share = covered / samples;
    std::printf("band %d (luma %.3f): strokes cover %.1f %% of the paper\n", band, luma, 100.0 * share);
    if (band == bands - 1) {
      EXPECT_EQ(share, 0.0) << "the lightest band is bare paper";
    } else {
      EXPECT_GT(share, previous + 0.05) << "band " << band;
    }
    previous = share;
  }
  // One layer of strokes one pixel wide, about `spacing` pixels apart: about 1 / spacing of the paper, whatever the
  // pixel's size (the octave cross-fade keeps the spacing between spacing / 2 and spacing... in pixels).
  for (float size : {0.001f, 0.0037f, 0.02f, 0.3f}) {
    double covered = 0.0;
    for (int i = 0; i < 4000; ++i) {
      const glm::vec3 p(static_cast<float>(i % 200) * size, static_cast<float>(i / 200) * size, 0.0f);
      covered += hatchLayerCoverage(p, glm::vec3(0.0f, 0.0f, 1.0f), 0, size, spacing);
    }
    const double share = covered / 4000.0;
    std::printf("a pixel of %.4f: one layer covers %.3f (1 / spacing = %.3f)\n", size, share, 1.0 / spacing);
    EXPECT_GT(share, 0.6 / spacing);
    EXPECT_LT(share, 2.4 / spacing);
  }
}

// The GPU's hatching against the mirror on the cube and its floor (lines off: strength 0), from the G-buffer and the
// display colour of the same frame without edges.
TEST(Edges, HatchingMatchesTheMirror) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(cubeOnAFloor());
  const Camera camera = cubeCamera(4.0f);
  RenderSettings plain = plainFrame();
  plain.set("lighting.sun-intensity", "0.5");  // the cube's faces and the floor in the darker bands
  const test::RenderedImage off = test::render(renderer, camera, plain, View::Final, test::retaining({"gbuffer"}));
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  RenderSettings settings = plain;
  EdgesSettings edges = linesOf(1.5f);
  edges.style = EdgeStyle::Hatching;
  edges.strength = 0.0f;
  edges.color = glm::vec3(0.0f, 0.0f, 0.5f);
  settings.of<EdgesSettings>() = edges;
  const test::RenderedImage on = test::render(renderer, camera, settings, View::Final);
  const FrameCamera frame = FrameCamera::from(camera, kWidth, kHeight);
  const glm::mat4 cameraToWorld = glm::inverse(frame.view);
  const glm::vec2 pixelWorld = pixelWorldSize(frame.unjitteredProjection, kHeight);
  const EdgeDetector depth = EdgeDetector::of(edges, frame.near, frame.far);
  int close = 0, geometry = 0, stroked = 0;
  for (int row = 0; row < kHeight; ++row)
    for (int x = 0; x < kWidth; ++x) {
      const size_t i = static_cast<size_t>(row) * kWidth + static_cast<size_t>(x);
      const float z = depth.viewDepth(&gbuffer[i * 4]);
      if (z <= 0.0f) continue;  // background
      ++geometry;
      const glm::vec2 uv((static_cast<float>(x) + 0.5f) / kWidth, 1.0f - (static_cast<float>(row) + 0.5f) / kHeight);
      const float code = static_cast<float>(gbuffer[i * 4 + 2] * 256 + gbuffer[i * 4 + 3]);
      const glm::vec3 view = frame.reconstruction.viewPosition(uv, code / 65535.0f);
      const glm::vec3 world = glm::vec3(cameraToWorld * glm::vec4(view, 1.0f));
      const glm::vec3 normal = glm::mat3(cameraToWorld) * decodeNormal(gbuffer[i * 4], gbuffer[i * 4 + 1]);
      const glm::vec3 display = glm::vec3(off.rgba[i * 4], off.rgba[i * 4 + 1], off.rgba[i * 4 + 2]) / 255.0f;
      const glm::vec3 expected = hatchedColor(display, world, normal, pixelWorld.x * view.z + pixelWorld.y,
                                              edges.hatchSpacing, edges.bands, linearToSrgb(edges.color));
      const glm::vec3 got = glm::vec3(on.rgba[i * 4], on.rgba[i * 4 + 1], on.rgba[i * 4 + 2]) / 255.0f;
      if (glm::all(glm::lessThanEqual(glm::abs(got - expected), glm::vec3(3.0f / 255.0f)))) ++close;
      if (got.r < 0.9f) ++stroked;  // some stroke covers it
    }
  std::printf("hatching: %d of %d geometry pixels within 3/255 of the mirror, %d stroked\n", close, geometry, stroked);
  EXPECT_GT(stroked, geometry / 20);
  EXPECT_GE(close, geometry * 97 / 100);
}

// The strokes stay on the surface: the camera moves sideways in front of a wall, the wall moves 12 pixels across the
// image, and so does the hatching on it (strokes fixed to the image would not move).
TEST(Edges, HatchingStrokesStayOnTheSurfaceAsTheCameraMoves) {
  Renderer renderer = test::makeRenderer();
  Scene wall = test::sceneOf({test::makeRectangle(glm::vec3(-20.0f, -20.0f, 0.0f), glm::vec3(40.0f, 0.0f, 0.0f),
                                                  glm::vec3(0.0f, 40.0f, 0.0f))});
  renderer.setScene(wall);
  RenderSettings settings = plainFrame();
  settings.set("ao", "off");
  settings.set("lighting.sun-intensity", "0");  // the wall in a middle band: several layers of strokes
  EdgesSettings edges = linesOf(1.0f);
  edges.style = EdgeStyle::Hatching;
  edges.strength = 0.0f;
  edges.color = glm::vec3(0.0f);
  edges.bands = 8;
  settings.of<EdgesSettings>() = edges;
  const float distance = 5.0f;
  const Camera first = test::makeCamera({0.0f, 0.0f, distance}, {0.0f, 0.0f, 0.0f}, kWidth, kHeight, 0.1f, 100.0f,
                                        kFovy);
  // 12 pixels of the image at the wall's distance.
  const float shift = 12.0f * 2.0f * distance * std::tan(glm::radians(kFovy) * 0.5f) / kHeight;
  const Camera second = test::makeCamera({shift, 0.0f, distance}, {shift, 0.0f, 0.0f}, kWidth, kHeight, 0.1f, 100.0f,
                                         kFovy);
  const test::RenderedImage a = test::render(renderer, first, settings, View::Final);
  const test::RenderedImage b = test::render(renderer, second, settings, View::Final);
  auto difference = [&](int dx) {
    double sum = 0.0;
    int count = 0;
    for (int y = 20; y < kHeight - 20; ++y)
      for (int x = 20; x < kWidth - 20; ++x) {
        sum += std::abs(a.rgba[(static_cast<size_t>(y) * kWidth + x) * 4] -
                        b.rgba[(static_cast<size_t>(y) * kWidth + x - dx) * 4]);
        ++count;
      }
    return sum / count;
  };
  int strokes = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) strokes += a.rgba[i] < 128;
  std::printf("the wall: %d stroke pixels; mean difference %.2f / 255 where the wall moved, %.2f where the image "
              "stayed\n",
              strokes, difference(12), difference(0));
  EXPECT_GT(strokes, kWidth * kHeight / 10);
  EXPECT_LT(difference(12), 2.0);
  EXPECT_GT(difference(0), 20.0);
}
