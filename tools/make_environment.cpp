// obscura-make-environment: writes assets/environments/studio.hdr, an equirectangular Radiance .hdr of a photo
// studio (a dim grey room, a warm key softbox, a cool fill, a strip light behind and a floor), for the image-based
// ambient light's figures and tests (docs/lighting.md). No .hdr ships with Debian or this repository's sources, and a
// made one keeps its radiance known: the softboxes are rectangles of constant radiance in angle.
//
// Deterministic: the same bytes on every run. Usage: obscura-make-environment OUT.hdr
#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include <glm/geometric.hpp>
#include <stb_image_write.h>

#include "environment/Environment.h"

using namespace obscura;

namespace {

struct Softbox {
  float azimuthDegrees, elevationDegrees;  // its centre: azimuth from -z towards +x, elevation above the horizon
  float halfWidthDegrees, halfHeightDegrees;
  glm::vec3 radiance;
};

glm::vec3 studio(const glm::vec3& d) {
  const float elevation = std::asin(std::clamp(d.y, -1.0f, 1.0f)) * 57.2957795f;
  const float azimuth = std::atan2(d.x, -d.z) * 57.2957795f;
  glm::vec3 c = d.y < 0.0f ? glm::vec3(0.16f, 0.15f, 0.14f)                    // the floor
                           : glm::mix(glm::vec3(0.06f), glm::vec3(0.03f), d.y);  // walls, darker to the ceiling
  const Softbox boxes[] = {{-50, 35, 18, 14, {9.0f, 7.6f, 6.0f}},    // key, warm, front left
                           {70, 20, 22, 16, {1.6f, 2.0f, 2.6f}},     // fill, cool, right
                           {175, 55, 40, 5, {4.0f, 4.0f, 4.0f}}};    // strip behind, high
  for (const Softbox& b : boxes) {
    float da = std::abs(azimuth - b.azimuthDegrees);
    da = std::min(da, 360.0f - da);
    if (da <= b.halfWidthDegrees && std::abs(elevation - b.elevationDegrees) <= b.halfHeightDegrees) c = b.radiance;
  }
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: obscura-make-environment OUT.hdr\n";
    return 2;
  }
  const int width = 512, height = 256, n = 4;
  std::vector<float> rgb(static_cast<size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      glm::vec3 sum(0.0f);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          sum += studio(equirectDirection({(static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / n) / width,
                                           (static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / n) / height}));
      for (int c = 0; c < 3; ++c) rgb[(static_cast<size_t>(y) * width + x) * 3 + c] = sum[c] / (n * n);
    }
  if (!stbi_write_hdr(argv[1], width, height, 3, rgb.data())) {
    std::cerr << argv[1] << ": cannot write\n";
    return 1;
  }
  return 0;
}
