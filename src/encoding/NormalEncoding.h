#pragma once
// View-space unit normals in two 8-bit channels. CPU mirror of encodeNormal / decodeNormal in
// shaders_es2/lib/packing.glsl; the candidates below were compared by tools/normal_encoding_study.cpp.
//
// Perspective makes view-space normals that face away from the viewer (n.z < 0) at the screen edges (Gravås 2013,
// sec. 3.1.5.1), so the encoding must cover the whole sphere.
//
// Measured by `build/obscura-normal-study` over 250,006 directions (200k Fibonacci sphere, the six axes, 50k in the
// back-facing band n.z in [-0.3, 0]), 8 bits per channel:
//   octahedral, 254 steps (chosen)   max 0.935 deg, mean 0.331 deg, p99 0.745 deg  (axes and poles exact)
//   octahedral, 255 steps            max 0.942 deg, mean 0.330 deg, p99 0.741 deg
//   spheremap / Lambert azimuthal    max 179.4 deg (singular at n = (0,0,-1)), mean 0.473 deg, p99 2.33 deg
// The README records the same table; tests/test_packing.cpp asserts the bound.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace obscura {

enum class NormalEncodingKind {
  Octahedral254,     // Cigolle et al. 2014; octahedron coordinate p in [-1,1] stored as round(127 p + 127)
  Octahedral255,     // same, stored as round(127.5 p + 127.5)
  LambertAzimuthal,  // spheremap transform (Mittring 2009, Pranckevicius 2010), as in Gravås 2013 eq. 3.1.5
};

constexpr NormalEncodingKind kGBufferNormalEncoding = NormalEncodingKind::Octahedral254;

std::array<std::uint8_t, 2> encodeNormal(const glm::vec3& unitNormal,
                                         NormalEncodingKind kind = kGBufferNormalEncoding);
glm::vec3 decodeNormal(std::uint8_t x, std::uint8_t y, NormalEncodingKind kind = kGBufferNormalEncoding);

// The direction set the encodings are measured on: a Fibonacci sphere of `count` points, the six axes and both
// poles, and a dense band of directions just behind the view plane (n.z in [-0.3, 0]), where perspective puts them.
std::vector<glm::vec3> encodingTestDirections(int count);

// Angle between two unit vectors in degrees, robust near 0 and 180.
double angleBetweenDegrees(const glm::vec3& a, const glm::vec3& b);

}  // namespace obscura
