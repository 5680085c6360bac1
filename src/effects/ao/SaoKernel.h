#pragma once
// The SAO estimator in plain C++: the CPU mirror of shaders_es2/ao/sao.frag. Tests run it over a G-buffer read back
// from the GPU and compare with the shader's output.
//
// Taps (McGuire, Mara, Luebke 2012, sec. 3.2): tap i of s lies on a spiral,
//   alpha_i = (i + 0.5) / s,   theta_i = 2 pi tau alpha_i + phi,   offset_i = alpha_i h (cos theta_i, sin theta_i),
// where tau (spiral turns) is coprime with s so no two taps share an angle, phi is a per-pixel rotation and
// h = min(projScale r / -z_C, maxScreenRadius * height) is the world-space radius r projected to pixels
// (projScale = height / (2 tan(fovy / 2)): pixels per metre at 1 m). An orthographic camera projects r to
// r height / (2 ymag) pixels at every depth: projScale is the pair (x, y) of FrameCamera::projScale, and
// h = min(r (projScale.x / -z_C + projScale.y), maxScreenRadius * height) covers both.
//
// Per-pixel rotation: interleaved gradient noise (Jimenez 2014), phi = 2 pi fract(52.9829189 fract(0.06711056 x +
// 0.00583715 y)) at integer pixel (x, y). Arithmetic only, since GLSL ES 1.00 has no bitwise operators (the SAO
// reference uses (3x ^ y + xy) * 10); its low-discrepancy 3x3 neighbourhoods suit the bilateral blur.
//
// Estimator, dimensionless: distances are measured in units of the radius, u = (Q - C) / r from the centre C to the
// tap's point Q, with n the centre normal, beta the bias as a fraction of r and eps = 0.01:
//   Alchemy 2011 (McGuire et al. HPG 2011, eq. 7, with SAO's bias):
//       A = max(0, 1 - (2 sigma / s) sum_i [u.u < 1] max(0, u.n - beta) / (u.u + eps))^k
//   SAO 2012 (reference code's recommended falloff):
//       A = max(0, 1 - (5 sigma / s) sum_i (max(0, 1 - u.u)^3) max(0, u.n - beta) / (u.u + eps))^k
// The papers write the tap term in metres, (v.n - beta) / (v.v + eps) with v = Q - C, eps = 0.01 m^2 and beta in
// metres; at r = 1 m the two forms are the same numbers. In metres the term changes with the scene's units (a model
// in centimetres, with the radius in centimetres, would get other AO: eps and beta would not scale with it). In
// units of r, scaling the scene and the radius together gives the same AO, and eps = 0.01 r^2 keeps the paper's
// intent ("large epsilon to avoid overdarkening within cracks") at every scale. The 1/r this removes from the sum
// is what sigma absorbed before.
#include <glm/vec2.hpp>
#include <glm/ext/vector_int2.hpp>
#include <glm/vec3.hpp>

#include "effects/ao/AoSettings.h"

namespace obscura::SaoKernel {

constexpr float kEpsilon = 0.01f;

// The coprime tau in [1, s) that spreads the s taps best: as points (alpha_i, frac(tau alpha_i)) in (radius, angle)
// fractions they form a rank-1 lattice, and the best tau maximises its smallest distance (angle wrapping around;
// ties to the smaller tau).
int bestSpiralTurns(int samples);
int greatestCommonDivisor(int a, int b);

// Depth hierarchy (SAO paper sec. 3.3): how many levels above the G-buffer, and the paper's level choice for a tap
// `tapDistance` pixels from the centre: m = clamp(floor(log2 h) - LOG_MAX_OFFSET, 0, MAX_MIP_LEVEL).
constexpr int kMaxMipLevel = 5;
constexpr int kLogMaxOffset = 3;
int hierarchyLevel(float tapDistance);
// Size of hierarchy level m for a level-0 size: floor(size / 2^m), at least 1.
glm::ivec2 hierarchyLevelSize(glm::ivec2 levelZeroSize, int level);
// The level-0 (G-buffer) pixel whose depth hierarchy level m keeps at texel p: the rotated-grid pick
// p_(k-1) = min(2 p_k + (p_k.y mod 2, p_k.x mod 2), size_(k-1) - 1), followed from level m down to 0.
glm::ivec2 hierarchySourcePixel(glm::ivec2 p, int level, glm::ivec2 levelZeroSize);
// The G-buffer pixel an AO pixel stands for at AO scale 1 (itself) or 2 (half resolution: 2p, the same corner of
// every block; see shaders_es2/ao/ao_resolution.glsl for why not the rotated grid).
glm::ivec2 aoCentrePixel(glm::ivec2 aoPixel, int aoScale, glm::ivec2 levelZeroSize);

// Per-pixel spiral rotation phi (radians) at integer pixel coordinates.
float rotationAngle(float pixelX, float pixelY);

// Unit direction of tap i and its radius as a fraction of the disk radius (alpha_i).
glm::vec2 tapDirection(int tapIndex, int samples, int spiralTurns, float rotation, float* radiusFraction);

// Projected disk radius in pixels for a centre at view-space depth viewZ (< 0); projScale: FrameCamera::projScale.
float diskRadiusPixels(float radius, float viewZ, glm::vec2 projScale, float maxRadiusPixels);

// One tap's contribution to the obscurance sum, for v = Q - C in scene units and bias as a fraction of radius.
float tapObscurance(Falloff falloff, const glm::vec3& v, const glm::vec3& n, float radius, float bias);

// The factor the tap sum is multiplied by: 5 sigma / s (SAO 2012) or 2 sigma / s (Alchemy 2011).
float intensityScale(Falloff falloff, float intensity, int samples);

// Final ambient visibility from the summed taps: max(0, 1 - sum * intensityScale)^k.
float ambientVisibility(Falloff falloff, float sum, int samples, float intensity, float contrast);

}  // namespace obscura::SaoKernel
