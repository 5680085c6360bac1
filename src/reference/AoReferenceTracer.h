#pragma once
// Ray-traced ambient obscurance with Embree 3: the ground truth SAO is measured against (docs/accuracy.md).
//
// Per pixel, one primary ray through the pixel centre with obscura-render's projection (right-handed, OpenGL
// conventions, row 0 at the top of the image, near and far planes clipping as the rasteriser does). At the first hit
// P, with n the geometric normal turned to face the viewer, the ambient visibility is
//
//     A(P) = (1/pi) * integral over the hemisphere around n of V_R(P, w) cos(theta) dw,
//
// V_R(P, w) = 1 if the ray from P along w meets no surface within distance R (the AO radius), else 0. The ambient
// *obscurance* is 1 - A; the images hold A (1 = unoccluded, white), like obscura-render's `ao` view. Sampling w with
// density cos(theta) / pi makes the estimator the plain fraction of unblocked rays, A ~= (1/N) sum_i V_R(P, w_i)
// (the cosine and the 1/pi cancel against the density), with the N directions from HemisphereSampling.h.
//
// Choices, and why:
// - Geometric, not shading, normal: the hemisphere of the true surface. Shading normals of a tessellated curve tilt
//   below the facet, so some rays would start inside the surface and count it as an occluder.
// - The normal faces the viewer: a surface seen from behind (double-sided materials) gets the hemisphere on the
//   side the camera sees, as the G-buffer's normal does.
// - Primary rays skip back faces of single-sided materials, because the rasteriser culls them (GpuScene); hemisphere
//   rays are blocked by every face, from either side: geometry hides the sky whichever way it faces.
// - Rays start at P offset along n by a small distance relative to the magnitude of P (float precision), with
//   tnear = 0 and tfar = R.
// - alphaMode MASK cut-outs are not surfaces, for primary and hemisphere rays alike, as the G-buffer and lighting
//   passes discard them (the texture's alpha sampled with its sampler's filter and wrap on the original image;
//   mipmaps not modelled).
#include <cstdint>
#include <memory>
#include <vector>

#include "scene/Camera.h"
#include "scene/Scene.h"

namespace obscura {

struct ReferenceSettings {
  float radius = 1.0f;  // R, metres (the same meaning as AoSettings::radius)
  int rays = 256;       // hemisphere rays per pixel; a power of two (the Hammersley set is a (0, m, 2)-net)
  int threads = 2;      // worker threads; the result does not depend on it
};

// Per-pixel results, rows top to bottom.
struct ReferenceFrame {
  int width = 0, height = 0;
  std::vector<float> visibility;   // A in [0, 1]; 1 on background
  std::vector<float> linearDepth;  // (-z_view - near) / (far - near); 1 on background
  std::vector<std::uint8_t> mask;  // 1 geometry, 0 background

  // The views, in obscura-render's encodings (grey RGBA8): ao (background white), depth (the G-buffer's 16-bit code
  // shown as grey, background white), mask (geometry 255, background 0).
  Image aoImage() const;
  Image depthImage() const;
  Image maskImage() const;
};

class AoReferenceTracer {
 public:
  // Builds the Embree scene (every instance flattened to world space). Throws std::runtime_error if Embree fails.
  explicit AoReferenceTracer(const Scene& scene, int buildThreads = 2);
  ~AoReferenceTracer();
  AoReferenceTracer(const AoReferenceTracer&) = delete;
  AoReferenceTracer& operator=(const AoReferenceTracer&) = delete;

  // Throws InputError if the settings are out of range (radius as AoSettings; rays a power of two in 1 .. 65536;
  // threads in 1 .. 256).
  ReferenceFrame trace(const Camera& camera, const ReferenceSettings& settings) const;

  // Ambient visibility at one world-space point with the given (unit) normal: the integral above, without a primary
  // ray (for tests). `pixelX`/`pixelY` select the per-pixel digital shift.
  float visibilityAt(const glm::vec3& point, const glm::vec3& normal, const ReferenceSettings& settings,
                     std::uint32_t pixelX = 0, std::uint32_t pixelY = 0) const;

  std::size_t triangleCount() const { return triangles_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::size_t triangles_ = 0;
};

// Throws InputError naming the problem if `settings` is out of range.
void validateReferenceSettings(const ReferenceSettings& settings);

}  // namespace obscura
