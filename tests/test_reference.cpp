// The ray-traced reference (reference/AoReferenceTracer.h) against closed-form obscurance, and its sampling.
//
// Closed forms. With cosine-weighted directions, the measure (1/pi) integral over a set S of cos(theta) dw equals the
// area of S's projection onto the tangent-plane unit disk, divided by pi (Malley's method, run backwards). Hence:
// - Floor point at distance d from an infinite wall (the wall on the -x side): a direction w reaches the wall within
//   R iff w_x < -d/R, so A = 1 - segment(d/R) / pi, with segment(a) = acos(a) - a sqrt(1 - a^2) the area of the disk
//   beyond the chord at a. At the foot of the wall (d = 0) A = 1/2: the wall hides half the cosine-weighted sky.
// - Floor point under an infinite ceiling at height h: w is blocked iff h / w_z < R, i.e. w_z > h/R, a disk of radius
//   sqrt(1 - (h/R)^2) in projection, so A = (h/R)^2 (for h < R), and A = 1 for h >= R.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/trigonometric.hpp>

#include "TestSupport.h"
#include "base/Error.h"
#include "encoding/LinearDepthPacking.h"
#include "reference/AoReferenceTracer.h"
#include "reference/HemisphereSampling.h"

using namespace obscura;
namespace hs = obscura::HemisphereSampling;

namespace {

constexpr float kPi = 3.14159265358979f;

// A square of side 2 * half centred at `centre` in the plane spanned by u and v (normal u x v).
Mesh square(const glm::vec3& centre, const glm::vec3& u, const glm::vec3& v, float half) {
  return test::makeRectangle(centre - half * u - half * v, 2 * half * u, 2 * half * v);
}

const glm::vec3 kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);

Mesh floorMesh() { return square({0, 0, 0}, kX, -kZ, 200.0f); }  // y = 0, facing +y

float wallVisibility(float distance, float radius) {
  const float a = std::min(distance / radius, 1.0f);
  return 1.0f - (std::acos(a) - a * std::sqrt(1.0f - a * a)) / kPi;
}

}  // namespace

TEST(HemisphereSampling, ShiftedHammersleyKeepsEveryElementaryInterval) {
  // A (0, m, 2)-net: for every split of the m bits, each 2^-k x 2^-(m-k) box holds exactly one of the 2^m points.
  const int m = 8;
  for (std::uint32_t pixel : {0u, 1u, 12345u}) {
    const std::uint32_t sx = hs::hash32(pixel), sy = hs::hash32(pixel + 77u);
    for (int k = 0; k <= m; ++k) {
      std::vector<int> count(1u << m, 0);
      for (std::uint32_t i = 0; i < (1u << m); ++i) {
        const glm::vec2 p = hs::shiftedHammersley(i, m, sx, sy);
        ASSERT_TRUE(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f);
        const int bx = static_cast<int>(p.x * float(1 << k)), by = static_cast<int>(p.y * float(1 << (m - k)));
        ++count[static_cast<size_t>(bx * (1 << (m - k)) + by)];
      }
      for (int c : count) ASSERT_EQ(c, 1) << "k = " << k << ", pixel " << pixel;
    }
  }
}

TEST(HemisphereSampling, CosineDirectionsHaveTheRightMoments) {
  // For density cos(theta) / pi: E[cos theta] = 2/3, E[cos^2 theta] = 1/2, E[x] = E[y] = 0.
  const int m = 12;
  double meanZ = 0, meanZ2 = 0, meanX = 0, meanY = 0;
  for (std::uint32_t i = 0; i < (1u << m); ++i) {
    const glm::vec3 w = hs::cosineHemisphere(hs::shiftedHammersley(i, m, 0x1234567u, 0x89abcdefu));
    ASSERT_NEAR(glm::length(w), 1.0f, 1e-5f);
    ASSERT_GE(w.z, 0.0f);
    meanZ += w.z;
    meanZ2 += w.z * w.z;
    meanX += w.x;
    meanY += w.y;
  }
  const double n = double(1u << m);
  EXPECT_NEAR(meanZ / n, 2.0 / 3.0, 2e-3);
  EXPECT_NEAR(meanZ2 / n, 0.5, 2e-3);
  EXPECT_NEAR(meanX / n, 0.0, 2e-3);
  EXPECT_NEAR(meanY / n, 0.0, 2e-3);
}

TEST(HemisphereSampling, BasisIsOrthonormal) {
  for (const glm::vec3& n : {kX, kY, kZ, -kZ, glm::normalize(glm::vec3(0.3f, -0.8f, 0.1f)),
                             glm::normalize(glm::vec3(1e-6f, 0.0f, -1.0f))}) {
    glm::vec3 t, b;
    hs::orthonormalBasis(n, &t, &b);
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(b), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(b, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, b), 0.0f, 1e-5f);
  }
}

TEST(Reference, OpenPlaneIsUnoccluded) {
  const AoReferenceTracer tracer(test::sceneOf({floorMesh()}));
  const Camera camera = test::makeCamera({0.0f, 2.0f, 4.0f}, {0.0f, 0.0f, -2.0f}, 64, 48, 0.1f, 100.0f);
  const ReferenceFrame frame = tracer.trace(camera, {4.0f, 64, 2});
  size_t geometry = 0;
  for (size_t i = 0; i < frame.mask.size(); ++i) {
    geometry += frame.mask[i];
    EXPECT_EQ(frame.visibility[i], 1.0f) << "pixel " << i;
  }
  EXPECT_GT(geometry, frame.mask.size() / 2);
}

TEST(Reference, FloorBesideAWallMatchesTheClosedForm) {
  // Wall x = 0 facing +x, 100 m tall: infinite for every radius used here.
  const AoReferenceTracer tracer(test::sceneOf({floorMesh(), square({0, 50, 0}, kZ, kY, 100.0f)}));
  for (float radius : {0.5f, 2.0f}) {
    // 0.002: just off the foot of the wall (a point on the wall's plane sees it edge-on, at t = 0).
    for (float fraction : {0.002f, 0.1f, 0.3f, 0.6f, 0.9f, 1.2f}) {
      const float d = fraction * radius;
      const float expected = wallVisibility(d, radius);
      // Averaged over a few pixels' sample patterns; each is a 1024-point net, accurate to well under 1%.
      float sum = 0.0f;
      for (std::uint32_t px = 0; px < 4; ++px)
        sum += tracer.visibilityAt({d, 0.0f, 0.0f}, kY, {radius, 1024, 1}, px, 7);
      EXPECT_NEAR(sum / 4.0f, expected, 0.01f) << "d = " << d << ", R = " << radius;
    }
  }
  EXPECT_NEAR(wallVisibility(0.0f, 1.0f), 0.5f, 1e-6f);
}

TEST(Reference, FloorUnderACeilingMatchesTheClosedFormFromEitherSideOfTheCeiling) {
  // The ceiling faces up, away from the floor, with a single-sided material: its back face still blocks light.
  for (const glm::vec3& up : {kY, -kY}) {
    const glm::vec3 u = kX, v = up.y > 0 ? -kZ : kZ;  // u x v = up
    const AoReferenceTracer tracer(test::sceneOf({floorMesh(), square({0, 0.5f, 0}, u, v, 200.0f)}));
    for (float radius : {0.25f, 0.8f, 1.0f, 3.0f}) {
      const float h = 0.5f;
      const float expected = h >= radius ? 1.0f : (h / radius) * (h / radius);
      const float traced = tracer.visibilityAt({0.3f, 0.0f, -0.2f}, kY, {radius, 1024, 1}, 3, 5);
      EXPECT_NEAR(traced, expected, 0.01f) << "R = " << radius << ", ceiling facing " << up.y;
    }
  }
}

TEST(Reference, PrimaryRaysFollowTheRasterisersProjectionAndCulling) {
  // A single-sided square 5 m in front of the camera, facing it, and one behind it facing away (culled: invisible).
  const Camera camera = test::makeCamera({0, 0, 0}, {0, 0, -1}, 40, 30, 0.5f, 20.0f, 60.0f);
  Scene scene = test::sceneOf({square({0, 0, -5}, kX, kY, 1.0f), square({0, 0, -10}, kY, kX, 100.0f)});
  const AoReferenceTracer tracer(scene);
  const ReferenceFrame frame = tracer.trace(camera, {1.0f, 16, 1});
  // The square spans +-1 m at 5 m, a tangent of 0.2; half the image height (15 pixels) is tan(30 deg). Pixels are
  // square, so the square covers 0.2 * 15 / tan(30 deg) = 5.2 pixels each way from the image centre.
  const float halfExtent = 0.2f * 15.0f / std::tan(glm::radians(30.0f));
  const float expectedDepth = (5.0f - camera.near) / (camera.far - camera.near);
  const Image depth = frame.depthImage(), mask = frame.maskImage();
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      const float cx = static_cast<float>(x) + 0.5f - 20.0f, cy = static_cast<float>(y) + 0.5f - 15.0f;
      const bool inside = std::abs(cx) < halfExtent - 0.01f && std::abs(cy) < halfExtent - 0.01f;
      const bool outside = std::abs(cx) > halfExtent + 0.01f || std::abs(cy) > halfExtent + 0.01f;
      const size_t i = static_cast<size_t>(y) * 40 + static_cast<size_t>(x);
      if (inside) {
        ASSERT_EQ(frame.mask[i], 1) << x << "," << y;
        EXPECT_NEAR(frame.linearDepth[i], expectedDepth, 1e-5f);
        EXPECT_EQ(depth.rgba[4 * i], static_cast<std::uint8_t>(std::lround(
                                         LinearDepthPacking::depthFromCode(LinearDepthPacking::codeFromDepth(
                                             expectedDepth)) * 255.0f)));
        EXPECT_EQ(mask.rgba[4 * i], 255);
      } else if (outside) {
        ASSERT_EQ(frame.mask[i], 0) << x << "," << y << ": the back face should have been culled";
        EXPECT_EQ(depth.rgba[4 * i], 255);
        EXPECT_EQ(mask.rgba[4 * i], 0);
        EXPECT_EQ(frame.aoImage().rgba[4 * i], 255);
      }
    }
  }
  // Marked double-sided, the far square shows: every pixel holds geometry.
  Material twoSided;
  twoSided.doubleSided = true;
  scene.materials.push_back(twoSided);
  scene.meshes[1].material = 0;
  const ReferenceFrame both = AoReferenceTracer(scene).trace(camera, {1.0f, 16, 1});
  for (std::uint8_t m : both.mask) ASSERT_EQ(m, 1);
}

// alphaMode MASK, as the raster passes apply it: primary rays pass through the cut-out half of the quad, hemisphere
// rays too, and the mask matches obscura-render's G-buffer pixel for pixel.
TEST(Reference, AlphaMaskCutOutsAreNotSurfaces) {
  const Camera camera = test::makeCamera({0.0f, 1.2f, 4.0f}, {0.0f, 0.6f, 0.0f}, 100, 75);
  const Scene masked = test::cutOutQuadOnAFloor(AlphaMode::Mask);
  const AoReferenceTracer tracer(masked);
  const ReferenceFrame frame = tracer.trace(camera, {1.0f, 64, 2});

  // The mask: the same pixels as the rasteriser's (both sample the 2-texel texture with GL_NEAREST).
  Renderer renderer = test::makeRenderer();
  renderer.setScene(masked);
  const test::RenderedImage rasterMask = test::render(renderer, camera, AoSettings{}, View::Mask);
  size_t differing = 0, hole = 0;
  for (size_t i = 0; i < frame.mask.size(); ++i) differing += (frame.mask[i] != 0) != (rasterMask.rgba[4 * i] != 0);
  // Pixels whose centre falls within float rounding of an edge may go either way.
  EXPECT_LE(differing, frame.mask.size() / 500) << "pixels where the reference and the G-buffer disagree";
  const AoReferenceTracer opaqueTracer(test::cutOutQuadOnAFloor(AlphaMode::Opaque));
  const ReferenceFrame opaque = opaqueTracer.trace(camera, {1.0f, 64, 2});
  for (size_t i = 0; i < frame.mask.size(); ++i) hole += opaque.mask[i] && !frame.mask[i];
  EXPECT_GT(hole, frame.mask.size() / 20) << "the cut-out half should let the background through";

  // Hemisphere rays: the floor at the foot of the cut-out half is open (the kept half is 1.5 m away, beyond the 1 m
  // radius); at the foot of the kept half it is not.
  const ReferenceSettings settings{1.0f, 1024, 1};
  EXPECT_EQ(tracer.visibilityAt({-1.5f, 0.0f, 0.05f}, kY, settings), 1.0f);
  EXPECT_LT(tracer.visibilityAt({1.5f, 0.0f, 0.05f}, kY, settings), 0.8f);
  EXPECT_LT(opaqueTracer.visibilityAt({-1.5f, 0.0f, 0.05f}, kY, settings), 0.8f);
}

TEST(Reference, ImageDoesNotDependOnTheThreadCount) {
  const AoReferenceTracer tracer(test::sceneOf({floorMesh(), square({0, 50, 0}, kZ, kY, 100.0f)}));
  const Camera camera = test::makeCamera({3.0f, 1.5f, 2.0f}, {0.0f, 0.0f, 0.0f}, 48, 32);
  const ReferenceFrame one = tracer.trace(camera, {1.0f, 32, 1});
  const ReferenceFrame three = tracer.trace(camera, {1.0f, 32, 3});
  EXPECT_EQ(one.visibility, three.visibility);
  EXPECT_EQ(one.linearDepth, three.linearDepth);
  // And the crease is there: some pixels see the wall within the radius.
  EXPECT_LT(*std::min_element(one.visibility.begin(), one.visibility.end()), 0.7f);
}

TEST(Reference, RefusesBadSettings) {
  const AoReferenceTracer tracer(test::sceneOf({floorMesh()}));
  const Camera camera = test::makeCamera({0, 1, 3}, {0, 0, 0}, 8, 8);
  EXPECT_THROW(tracer.trace(camera, {1.0f, 100, 1}), InputError);  // not a power of two
  EXPECT_THROW(tracer.trace(camera, {0.0f, 64, 1}), InputError);
  EXPECT_THROW(tracer.trace(camera, {1.0f, 64, 0}), InputError);
}
