// obscura-environment-study: which RGBA8 encoding the prefiltered environment's levels can take so that the
// hardware's bilinear filter may read them (one fetch) instead of the shader filtering RGB9E5 texels by hand (four
// fetches and four decodes per level). docs/lighting.md ("Storage") shows its output and the choice made from it.
//
// For each environment (the built-in sky, assets/environments/studio.hdr, and the sky with its sun 100 times as
// bright, as a photographed sun can be), each prefiltered level (roughness 0, 0.2, .., 1) and each candidate, it
// encodes the level's linear texels, filters the encoded bytes as the hardware does (bilinear between texel centres
// on the normalised channels, wrapping in u and clamping in v, then decoded) at 20,000 random points, and compares the
// result with the same bilinear filter over the linear texels (what the level means). Errors are given per point
// relative to the reference's brightest channel (floored at 1 % of the level's mean, so near-black points do not
// dominate), as the mean, the 99th percentile and the worst, and in units of the level's brightest channel.
//
//   build/obscura-environment-study [--samples N] [--environment FILE.hdr]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "encoding/EnvironmentEncoding.h"
#include "encoding/HdrEncoding.h"
#include "environment/Environment.h"

using namespace obscura;

namespace {

struct Errors {
  double mean = 0.0, p99 = 0.0, worst = 0.0, worstOfBrightest = 0.0;
};

// Bilinear between texel centres of a w x h grid of any value type (wrap in u, clamp in v).
template <typename T, typename Fetch>
T bilinear(int w, int h, float u, float v, const Fetch& fetch) {
  const float px = u * static_cast<float>(w) - 0.5f, py = v * static_cast<float>(h) - 0.5f;
  const float fx0 = std::floor(px), fy0 = std::floor(py);
  const float fx = px - fx0, fy = py - fy0;
  auto wrap = [w](int x) { return ((x % w) + w) % w; };
  const int x0 = wrap(static_cast<int>(fx0)), x1 = wrap(static_cast<int>(fx0) + 1);
  const int y0 = std::clamp(static_cast<int>(fy0), 0, h - 1), y1 = std::clamp(static_cast<int>(fy0) + 1, 0, h - 1);
  const T top = fetch(x0, y0) * (1.0f - fx) + fetch(x1, y0) * fx;
  const T bottom = fetch(x0, y1) * (1.0f - fx) + fetch(x1, y1) * fx;
  return top * (1.0f - fy) + bottom * fy;
}

float brightest(const glm::vec3& c) { return std::max(c.r, std::max(c.g, c.b)); }

// One candidate: how a level's texels become bytes, and how the shader reads them.
struct Candidate {
  std::string name;
  bool hardwareFiltered;  // false: fetched NEAREST, each texel decoded, then filtered (RGB9E5 today)
  // Channels in [0, 1]; `scale` in: the scale to use (0: the level's own), out: the one used.
  std::function<std::vector<glm::vec4>(const EnvironmentImage&, float&)> encode;
  std::function<glm::vec3(const glm::vec4&, float)> decode;                       // channels, scale
};

Errors measure(const EnvironmentImage& level, const Candidate& candidate, int samples, unsigned seed,
               float sharedScale, bool eightBitFilter) {
  float scale = sharedScale;
  const std::vector<glm::vec4> channels = candidate.encode(level, scale);
  double levelMean = 0.0;
  float levelBrightest = 0.0f;
  for (const glm::vec3& c : level.texels) {
    levelMean += brightest(c);
    levelBrightest = std::max(levelBrightest, brightest(c));
  }
  levelMean /= static_cast<double>(level.texels.size());
  const float floorValue = static_cast<float>(0.01 * levelMean);
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<double> errors;
  errors.reserve(static_cast<size_t>(samples));
  Errors out;
  for (int i = 0; i < samples; ++i) {
    const float u = unit(random), v = unit(random);
    const glm::vec3 reference = bilinear<glm::vec3>(level.width, level.height, u, v,
                                                    [&](int x, int y) { return level.at(x, y); });
    auto texel = [&](int x, int y) { return channels[static_cast<size_t>(y) * level.width + x]; };
    // llvmpipe's filter returns 8-bit channels (its bilinear blend of UNORM8 texels is fixed-point); GPUs and
    // SwiftShader keep more bits.
    auto filtered = [&] {
      const glm::vec4 f = bilinear<glm::vec4>(level.width, level.height, u, v, texel);
      return eightBitFilter ? glm::floor(f * 255.0f + 0.5f) / 255.0f : f;
    };
    const glm::vec3 got =
        candidate.hardwareFiltered
            ? candidate.decode(filtered(), scale)
            : bilinear<glm::vec3>(level.width, level.height, u, v,
                                  [&](int x, int y) { return candidate.decode(texel(x, y), scale); });
    float difference = 0.0f;
    for (int c = 0; c < 3; ++c) difference = std::max(difference, std::abs(got[c] - reference[c]));
    const double relative = difference / std::max(brightest(reference), floorValue);
    errors.push_back(relative);
    out.mean += relative;
    out.worst = std::max(out.worst, relative);
    out.worstOfBrightest = std::max(out.worstOfBrightest, static_cast<double>(difference / levelBrightest));
  }
  out.mean /= samples;
  std::sort(errors.begin(), errors.end());
  out.p99 = errors[static_cast<size_t>(0.99 * static_cast<double>(errors.size() - 1))];
  return out;
}

std::vector<Candidate> candidates() {
  std::vector<Candidate> out;
  out.push_back({"rgb9e5, by hand", false,
                 [](const EnvironmentImage& level, float&) {
                   std::vector<glm::vec4> c;
                   for (const glm::vec3& t : level.texels) {
                     const HdrTexel b = encodeHdr(t);
                     c.emplace_back(b[0] / 255.0f, b[1] / 255.0f, b[2] / 255.0f, b[3] / 255.0f);
                   }
                   return c;
                 },
                 [](const glm::vec4& c, float) {
                   auto byte = [](float x) { return static_cast<std::uint8_t>(std::lround(x * 255.0f)); };
                   return decodeHdr(HdrTexel{byte(c.r), byte(c.g), byte(c.b), byte(c.a)});
                 }});
  for (EnvironmentEncodingKind kind : allEnvironmentEncodings()) {
    out.push_back({environmentEncodingName(kind), true,
                   [kind](const EnvironmentImage& level, float& scale) {
                     if (scale <= 0.0f) scale = environmentLevelScale(kind, level.texels);
                     const std::vector<EnvironmentTexel> bytes = encodeEnvironmentLevel(kind, level.texels, scale);
                     std::vector<glm::vec4> c;
                     for (const EnvironmentTexel& b : bytes)
                       c.emplace_back(b[0] / 255.0f, b[1] / 255.0f, b[2] / 255.0f, b[3] / 255.0f);
                     return c;
                   },
                   [kind](const glm::vec4& c, float scale) { return decodeEnvironmentChannels(kind, c, scale); }});
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int samples = 20000;
  std::string file = "assets/environments/studio.hdr";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--samples" && i + 1 < argc) samples = std::atoi(argv[++i]);
    else if (arg == "--environment" && i + 1 < argc) file = argv[++i];
    else {
      std::fprintf(stderr, "usage: obscura-environment-study [--samples N] [--environment FILE.hdr]\n");
      return 2;
    }
  }
  struct Named {
    std::string name;
    EnvironmentImage image;
  };
  std::vector<Named> environments;
  environments.push_back({"sky", ProceduralSky{}.image(kEnvironmentWidth, kEnvironmentHeight)});
  environments.push_back({file, loadEnvironmentImage(file)});
  ProceduralSky brightSun;
  brightSun.sun *= 100.0f;
  environments.push_back({"sky, sun x 100", brightSun.image(kEnvironmentWidth, kEnvironmentHeight)});

  const std::vector<Candidate> all = candidates();
  std::printf("Filtering the prefiltered environment's levels: error of each encoding read through bilinear filtering\n"
              "against the same filter over the linear texels, %d random points per level, as mean / 99th\n"
              "percentile / worst in %% of the reference's brightest channel at the point (floored at 1 %% of the\n"
              "level's mean). scales: each level its own, or as stored (level 0, level 1, levels 2 .. 5 sharing\n"
              "one: GpuEnvironment). filter: exact, or its output rounded to 8 bits as llvmpipe's is.\n",
              samples);
  for (const Named& environment : environments) {
    const PrefilteredEnvironment prefiltered = PrefilteredEnvironment::of(environment.image);
    std::printf("\n%s; brightest channel / mean per level:", environment.name.c_str());
    std::vector<float> top(kEnvironmentLevels, 0.0f);
    for (int level = 0; level < kEnvironmentLevels; ++level) {
      double mean = 0.0;
      for (const glm::vec3& c : prefiltered.levels[level].texels) {
        mean += brightest(c);
        top[static_cast<size_t>(level)] = std::max(top[static_cast<size_t>(level)], brightest(c));
      }
      mean /= static_cast<double>(prefiltered.levels[level].texels.size());
      std::printf(" %.3g / %.3g", top[static_cast<size_t>(level)], mean);
    }
    // Levels 2 .. 5 share level 2's scale (the brightest of them) where stored.
    const float shared = *std::max_element(top.begin() + 2, top.end());
    std::printf("\n| encoding | scales | filter |");
    for (int level = 0; level < kEnvironmentLevels; ++level)
      std::printf(" %d: %dx%d |", level, prefiltered.levels[level].width, prefiltered.levels[level].height);
    std::printf("\n|---|---|---|---|---|---|---|---|---|\n");
    for (const Candidate& candidate : all)
      for (bool stored : {false, true})
        for (bool eightBit : {false, true}) {
          if (!candidate.hardwareFiltered && (stored || eightBit)) continue;
          std::printf("| %s | %s | %s |", candidate.name.c_str(),
                      candidate.hardwareFiltered ? (stored ? "as stored" : "own") : "",
                      candidate.hardwareFiltered ? (eightBit ? "8-bit" : "exact") : "");
          for (int level = 0; level < kEnvironmentLevels; ++level) {
            const Errors e = measure(prefiltered.levels[level], candidate, samples,
                                     1234u + static_cast<unsigned>(level), stored && level >= 2 ? shared : 0.0f,
                                     eightBit);
            std::printf(" %.2f / %.2f / %.1f |", 100.0 * e.mean, 100.0 * e.p99, 100.0 * e.worst);
          }
          std::printf("\n");
        }
  }
  return 0;
}
