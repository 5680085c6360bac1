#pragma once
// Deterministic low-discrepancy sampling of the cosine-weighted hemisphere, for the ray-traced AO reference.
//
// Point set: the 2D Hammersley set of N = 2^m points, (i / N, radicalInverse2(i)), a (0, m, 2)-net in base 2 (Pharr,
// Jakob, Humphreys, *Physically Based Rendering* 3rd ed., sec. 7.4.1). Each pixel applies its own random digital shift
// (XOR of both coordinates' bits with a hash of the pixel): a digitally shifted (0, m, 2)-net is still a
// (0, m, 2)-net, so every pixel keeps the stratification, while neighbouring pixels get decorrelated patterns
// (PBRT 3rd ed. sec. 7.4.3 on scrambling). Everything is integer arithmetic on the pixel coordinates, so the result
// does not depend on thread count or order.
//
// Cosine-weighted directions: Malley's method, a uniform point on the unit disk lifted to the hemisphere
// (z = sqrt(1 - x^2 - y^2)) has density cos(theta) / pi (PBRT 3rd ed. sec. 13.6.3); the disk point comes from the
// Shirley-Chiu concentric mapping, which keeps the net's strata compact.
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace obscura::HemisphereSampling {

// A well-mixing 32-bit integer hash (the "lowbias32" finaliser of Chris Wellons' hash prospector).
std::uint32_t hash32(std::uint32_t x);

// Bits of i reversed: radicalInverse2(i) * 2^32.
std::uint32_t reverseBits(std::uint32_t i);

// Point i of the N = 2^log2Count Hammersley set after a digital shift by (shiftX, shiftY), in [0, 1)^2.
glm::vec2 shiftedHammersley(std::uint32_t i, int log2Count, std::uint32_t shiftX, std::uint32_t shiftY);

// Shirley-Chiu concentric map from [0, 1)^2 to the unit disk.
glm::vec2 concentricDisk(const glm::vec2& u);

// Cosine-weighted direction in the local frame whose z axis is the surface normal (density cos(theta) / pi).
glm::vec3 cosineHemisphere(const glm::vec2& u);

// An orthonormal basis (t, b, n) around the unit vector n (Duff et al., "Building an Orthonormal Basis, Revisited",
// JCGT 2017, listing 3): continuous except at n.z = 0 sign changes, no normalisation needed.
void orthonormalBasis(const glm::vec3& n, glm::vec3* t, glm::vec3* b);

}  // namespace obscura::HemisphereSampling
