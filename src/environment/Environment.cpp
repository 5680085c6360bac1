#include "environment/Environment.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/trigonometric.hpp>
#include <stb_image.h>

#include "base/Error.h"
#include "base/TimeSpent.h"
#include "environment/PrefilterCache.h"

namespace obscura {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Van der Corput's radical inverse in base 2 (the Hammersley point's second coordinate), by integer arithmetic.
double radicalInverse(unsigned i) {
  double result = 0.0, scale = 0.5;
  for (; i != 0; i >>= 1, scale *= 0.5)
    if (i & 1u) result += scale;
  return result;
}

// A half vector drawn from GGX's D(h) (n.h) around +z (Karis 2013, ImportanceSampleGGX).
glm::dvec3 sampleGgx(double u1, double u2, double alpha) {
  const double phi = 2.0 * kPi * u1;
  const double cosTheta = std::sqrt((1.0 - u2) / (1.0 + (alpha * alpha - 1.0) * u2));
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

// A value's half float (IEEE 754 binary16) bits, rounded to the nearest, at most the largest finite half: what the
// half-float atlas holds.
std::uint16_t halfFloatBits(float value) { return glm::packHalf1x16(std::min(value, 65504.0f)); }

// An orthonormal frame around n (tangent, bitangent).
void frameAround(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
  const glm::dvec3 up = std::abs(n.y) < 0.999 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  t = glm::normalize(glm::cross(up, n));
  b = glm::cross(n, t);
}

// Bilinear between texel centres of a w x h equirectangular grid (wrap in u, clamp in v): the addressing of
// environmentLevel() in lib/environment.glsl, and what the hardware's filter does inside the filtered texture's
// borders.
// `read` maps a stored texel to what the texture holds (the half-float atlas's rounding).
struct AsStored {
  template <typename T>
  const T& operator()(const T& texel) const { return texel; }
};
template <typename T, typename Read = AsStored>
T bilinear(const std::vector<T>& texels, int w, int h, const glm::vec2& uv, Read read = {}) {
  const float px = uv.x * static_cast<float>(w) - 0.5f, py = uv.y * static_cast<float>(h) - 0.5f;
  const float fx0 = std::floor(px), fy0 = std::floor(py);
  const float fx = px - fx0, fy = py - fy0;
  auto wrap = [w](int x) { return ((x % w) + w) % w; };
  const int x0 = wrap(static_cast<int>(fx0)), x1 = wrap(static_cast<int>(fx0) + 1);
  const int y0 = std::clamp(static_cast<int>(fy0), 0, h - 1), y1 = std::clamp(static_cast<int>(fy0) + 1, 0, h - 1);
  auto at = [&](int x, int y) -> T { return read(texels[static_cast<size_t>(y) * w + x]); };
  const T top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * fx;
  const T bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * fx;
  return top + (bottom - top) * fy;
}

float brightestChannel(const glm::vec3& c) { return std::max(c.r, std::max(c.g, c.b)); }

std::vector<glm::vec4> normalisedChannels(const std::vector<EnvironmentTexel>& bytes) {
  std::vector<glm::vec4> out;
  out.reserve(bytes.size());
  for (const EnvironmentTexel& b : bytes) out.push_back(glm::vec4(b[0], b[1], b[2], b[3]) * (1.0f / 255.0f));
  return out;
}

// The image as level 0's kEnvironmentWidth x kEnvironmentHeight: each texel the mean of n x n bilinear lookups over
// its footprint, n enough to cover the source's texels (a 2048-wide image: 4 x 4).
EnvironmentImage resampled(const EnvironmentImage& image, int width, int height) {
  EnvironmentImage out(width, height);
  const int n = std::max(1, (image.width + width - 1) / width);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      glm::vec3 sum(0.0f);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const glm::vec2 uv((static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / static_cast<float>(n)) /
                                 static_cast<float>(width),
                             (static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / static_cast<float>(n)) /
                                 static_cast<float>(height));
          sum += bilinear(image.texels, image.width, image.height, uv);
        }
      out.at(x, y) = sum / static_cast<float>(n * n);
    }
  return out;
}

}  // namespace

glm::vec2 equirectUv(const glm::vec3& d) {
  const float horizontal = std::abs(d.x) + std::abs(d.z);
  const float u = horizontal > 0.0f ? std::atan2(d.x, -d.z) * static_cast<float>(0.5 / kPi) + 0.5f : 0.5f;
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) * static_cast<float>(1.0 / kPi);
  return {u, v};
}

glm::vec3 equirectDirection(const glm::vec2& uv) {
  const double phi = (uv.x - 0.5) * 2.0 * kPi, theta = uv.y * kPi;
  return glm::vec3(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
}

glm::vec3 EnvironmentImage::texelDirection(int x, int y) const {
  return equirectDirection({(static_cast<float>(x) + 0.5f) / static_cast<float>(width),
                            (static_cast<float>(y) + 0.5f) / static_cast<float>(height)});
}

double EnvironmentImage::texelSolidAngle(int y) const {
  const double theta0 = y * kPi / height, theta1 = (y + 1) * kPi / height;
  return 2.0 * kPi / width * (std::cos(theta0) - std::cos(theta1));
}

glm::vec3 EnvironmentImage::radiance(const glm::vec3& direction) const {
  return bilinear(texels, width, height, equirectUv(direction));
}

EnvironmentImage EnvironmentImage::halved() const {
  EnvironmentImage out(std::max(width / 2, 1), std::max(height / 2, 1));
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const int x1 = std::min(2 * x + 1, width - 1), y1 = std::min(2 * y + 1, height - 1);
      out.at(x, y) = 0.25f * (at(2 * x, 2 * y) + at(x1, 2 * y) + at(2 * x, y1) + at(x1, y1));
    }
  return out;
}

glm::vec3 ProceduralSky::radiance(const glm::vec3& direction) const {
  const glm::vec3 d = glm::normalize(direction);
  const glm::vec3 s = glm::normalize(sunDirection);
  // Above the horizon: horizon to zenith by the square root of the elevation's sine (a bright band at the horizon,
  // as Rayleigh scattering's longer path there gives); a tenth of a radian of blend into the ground below it.
  const float up = d.y;
  const glm::vec3 sky = glm::mix(horizon, zenith, std::sqrt(std::max(up, 0.0f)));
  glm::vec3 c = glm::mix(ground, sky, std::clamp(up / 0.1f + 1.0f, 0.0f, 1.0f));
  const float cosGamma = glm::dot(d, s);
  if (up > -0.1f) c += glow * std::pow(std::max(cosGamma, 0.0f), 64.0f) * std::clamp(up / 0.1f + 1.0f, 0.0f, 1.0f);
  if (cosGamma >= sunCosRadius) c += sun;
  return c;
}

EnvironmentImage ProceduralSky::image(int width, int height) const {
  const TimedScope timed("sky");
  EnvironmentImage out(width, height);
  constexpr int n = 4;
  // Supersampled only where the radiance is not smooth within a texel: the disc's edge (texels whose centre lies
  // within the disc's radius and two texel diagonals of its centre) and the rows near the horizon's kinks (the sky's
  // sqrt(up) at up = 0, the ground's blend at up = 0 and -0.1). Elsewhere the centre's radiance is the texel's mean
  // within 0.1 % (tests/test_environment.cpp measures it against supersampling every texel): the gradient and the
  // glow, (cos gamma)^64, change little over a texel of 180 / height degrees.
  const glm::vec3 toSun = glm::normalize(sunDirection);
  const double texel = kPi / height;
  const float nearSun = static_cast<float>(std::cos(std::acos(static_cast<double>(sunCosRadius)) + 3.0 * texel));
  for (int y = 0; y < height; ++y) {
    const double up0 = std::cos(y * texel), up1 = std::cos((y + 1) * texel);  // the row's up, from top to bottom
    const double margin = 4.0 * texel;
    const bool kinked = (up1 < margin && up0 > -margin) || (up1 < -0.1 + margin && up0 > -0.1 - margin);
    for (int x = 0; x < width; ++x) {
      const glm::vec3 centre = out.texelDirection(x, y);
      if (!kinked && glm::dot(centre, toSun) < nearSun) {
        out.at(x, y) = radiance(centre);
        continue;
      }
      glm::vec3 sum(0.0f);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          sum += radiance(equirectDirection(
              {(static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / n) / static_cast<float>(width),
               (static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / n) / static_cast<float>(height)}));
      out.at(x, y) = sum / static_cast<float>(n * n);
    }
  }
  return out;
}

EnvironmentImage uniformEnvironment(const glm::vec3& radiance, int width, int height) {
  EnvironmentImage out(width, height);
  std::fill(out.texels.begin(), out.texels.end(), radiance);
  return out;
}

EnvironmentImage loadEnvironmentImage(const std::string& path, int maxWidth) {
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const bool png = lower.size() >= 4 && lower.compare(lower.size() - 4, 4, ".png") == 0;
  int width = 0, height = 0, channels = 0;
  EnvironmentImage image;
  if (png) {
    stbi_uc* bytes = stbi_load(path.c_str(), &width, &height, &channels, 4);
    if (!bytes) throw InputError(path + ": cannot read the environment (" + stbi_failure_reason() + ")");
    image = EnvironmentImage(width, height);
    const HdrEncoding rgbe{HdrEncodingKind::Rgbe, 0.0f};
    for (size_t i = 0; i < image.texels.size(); ++i)
      image.texels[i] = decodeHdr(HdrTexel{bytes[4 * i], bytes[4 * i + 1], bytes[4 * i + 2], bytes[4 * i + 3]}, rgbe);
    stbi_image_free(bytes);
  } else {
    float* values = stbi_loadf(path.c_str(), &width, &height, &channels, 3);
    if (!values) throw InputError(path + ": cannot read the environment (" + stbi_failure_reason() + ")");
    image = EnvironmentImage(width, height);
    for (size_t i = 0; i < image.texels.size(); ++i)
      image.texels[i] = glm::max(glm::vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]), glm::vec3(0.0f));
    stbi_image_free(values);
  }
  if (width < 4 || height < 2)
    throw InputError(path + ": an environment needs an equirectangular image of at least 4 x 2 texels");
  while (image.width > maxWidth && image.width % 2 == 0 && image.height % 2 == 0) image = image.halved();
  return image;
}

std::array<float, 9> ShIrradiance::basis(const glm::vec3& d) {
  // R&H eq. 3: the real spherical harmonics' constants, sqrt((2l + 1) / 4 pi (l - m)! / (l + m)!) folded.
  const float k0 = static_cast<float>(0.5 * std::sqrt(1.0 / kPi));          // 0.282095
  const float k1 = static_cast<float>(std::sqrt(3.0 / (4.0 * kPi)));        // 0.488603
  const float k2 = static_cast<float>(0.5 * std::sqrt(15.0 / kPi));         // 1.092548
  const float k20 = static_cast<float>(0.25 * std::sqrt(5.0 / kPi));        // 0.315392
  const float k22 = static_cast<float>(0.25 * std::sqrt(15.0 / kPi));       // 0.546274
  return {k0,           k1 * d.y,     k1 * d.z,     k1 * d.x,
          k2 * d.x * d.y, k2 * d.y * d.z, k20 * (3.0f * d.z * d.z - 1.0f), k2 * d.x * d.z,
          k22 * (d.x * d.x - d.y * d.y)};
}

ShIrradiance ShIrradiance::project(const EnvironmentImage& image) {
  const TimedScope timed("irradiance");
  std::array<glm::dvec3, 9> sum{};
  for (int y = 0; y < image.height; ++y) {
    const double solidAngle = image.texelSolidAngle(y);
    for (int x = 0; x < image.width; ++x) {
      const std::array<float, 9> basisValues = basis(image.texelDirection(x, y));
      const glm::dvec3 radiance(image.at(x, y));
      for (int i = 0; i < 9; ++i) sum[i] += radiance * (basisValues[i] * solidAngle);
    }
  }
  ShIrradiance sh;
  for (int i = 0; i < 9; ++i) sh.coefficients[i] = glm::vec3(sum[i]);
  return sh;
}

std::array<glm::vec3, 9> ShIrradiance::polynomial() const {
  // R&H eq. 13 divided by pi. Their c1 .. c5 are the clamped cosine's coefficients A_0 = pi, A_1 = 2 pi / 3,
  // A_2 = pi / 4 (eq. 9) times the basis constants: c1 = A_2 k22, 2 c1 = A_2 k2, c2 = A_1 k1 / 2, c3 = 3 A_2 k20,
  // c4 = A_0 k0, c5 = A_2 k20.
  const double a1 = 2.0 / 3.0, a2 = 0.25;  // A_l / pi
  const double k0 = 0.5 * std::sqrt(1.0 / kPi), k1 = std::sqrt(3.0 / (4.0 * kPi)), k2 = 0.5 * std::sqrt(15.0 / kPi);
  const double k20 = 0.25 * std::sqrt(5.0 / kPi), k22 = 0.25 * std::sqrt(15.0 / kPi);
  const auto& L = coefficients;
  auto f = [](double k) { return static_cast<float>(k); };
  return {L[0] * f(k0) - L[6] * f(a2 * k20),  // 1: c4 L00 - c5 L20
          L[3] * f(a1 * k1),                  // x: 2 c2 L11
          L[1] * f(a1 * k1),                  // y: 2 c2 L1-1
          L[2] * f(a1 * k1),                  // z: 2 c2 L10
          L[4] * f(a2 * k2),                  // xy: 2 c1 L2-2
          L[5] * f(a2 * k2),                  // yz: 2 c1 L2-1
          L[7] * f(a2 * k2),                  // xz: 2 c1 L21
          L[8] * f(a2 * k22),                 // x^2 - y^2: c1 L22
          L[6] * f(3.0 * a2 * k20)};          // z^2: c3 L20
}

glm::vec3 ShIrradiance::reflectedRadiance(const glm::vec3& n) const {
  const std::array<glm::vec3, 9> p = polynomial();
  return p[0] + p[1] * n.x + p[2] * n.y + p[3] * n.z + p[4] * (n.x * n.y) + p[5] * (n.y * n.z) +
         p[6] * (n.x * n.z) + p[7] * (n.x * n.x - n.y * n.y) + p[8] * (n.z * n.z);
}

double ggxDistribution(double nDotH, double alpha) {
  const double a2 = alpha * alpha;
  const double d = nDotH * nDotH * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d);
}

glm::vec3 PrefilteredEnvironment::prefilter(const std::vector<EnvironmentImage>& sourceLevels, const glm::vec3& r,
                                            double roughness, int samples) {
  const double alpha = roughness * roughness;
  const glm::dvec3 n = glm::normalize(glm::dvec3(r));
  glm::dvec3 t, b;
  frameAround(n, t, b);
  // Filtered importance sampling: a sample of density pdf stands for the solid angle 1 / (N pdf); it reads the source
  // level whose texels are about that large (without Colbert & Krivanek's +1 bias: with enough samples per texel the
  // blur it adds was the larger error against the brute-force integral).
  const double texelSolidAngle = 4.0 * kPi / (static_cast<double>(sourceLevels[0].width) * sourceLevels[0].height);
  const double maxLevel = static_cast<double>(sourceLevels.size() - 1);
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  for (int i = 0; i < samples; ++i) {
    const glm::dvec3 hLocal = sampleGgx((i + 0.5) / samples, radicalInverse(static_cast<unsigned>(i)), alpha);
    const glm::dvec3 h = t * hLocal.x + b * hLocal.y + n * hLocal.z;
    const glm::dvec3 l = 2.0 * glm::dot(n, h) * h - n;
    const double nDotL = glm::dot(n, l);
    if (nDotL <= 0.0) continue;
    // With n = v, the density of l is D(h) (n.h) / (4 v.h) = D(h) / 4.
    const double pdf = ggxDistribution(hLocal.z, alpha) * 0.25;
    const double sampleSolidAngle = 1.0 / (samples * pdf);
    const double level = std::clamp(0.5 * std::log2(sampleSolidAngle / texelSolidAngle), 0.0, maxLevel);
    const int l0 = static_cast<int>(std::floor(level));
    const int l1 = std::min(l0 + 1, static_cast<int>(maxLevel));
    const glm::vec3 dir(l);
    const glm::vec3 c0 = sourceLevels[l0].radiance(dir), c1 = sourceLevels[l1].radiance(dir);
    sum += glm::dvec3(c0 + (c1 - c0) * static_cast<float>(level - l0)) * nDotL;
    weight += nDotL;
  }
  return weight > 0.0 ? glm::vec3(sum / weight) : glm::vec3(0.0f);
}

glm::vec3 sunDirection(float elevationDegrees, float azimuthDegrees) {
  const float elevation = glm::radians(elevationDegrees), azimuth = glm::radians(azimuthDegrees);
  return {std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth)};
}

PrefilteredEnvironment PrefilteredEnvironment::fromLevels(std::array<EnvironmentImage, kEnvironmentLevels> levels,
                                                          EnvironmentFiltering filtering) {
  PrefilteredEnvironment out;
  out.levels = std::move(levels);
  out.encodeLevels(filtering);
  return out;
}

PrefilteredEnvironment PrefilteredEnvironment::of(const EnvironmentImage& image, int samples,
                                                  EnvironmentFiltering filtering) {
  const TimedScope timed("prefilter");
  PrefilteredEnvironment out;
  if (prefilter_cache::load(image, samples, &out.levels)) {  // test runs only (PrefilterCache.h)
    out.encodeLevels(filtering);
    return out;
  }
  std::vector<EnvironmentImage> source = {image.width == kEnvironmentWidth && image.height == kEnvironmentHeight
                                              ? image
                                              : resampled(image, kEnvironmentWidth, kEnvironmentHeight)};
  while (source.back().width > 4) source.push_back(source.back().halved());
  out.levels[0] = source[0];
  for (int level = 1; level < kEnvironmentLevels; ++level) {
    EnvironmentImage& target = out.levels[level];
    target = EnvironmentImage(kEnvironmentWidth >> level, kEnvironmentHeight >> level);
    const double roughness = environmentLevelRoughness(level);
    const int levelSamples = std::max(64, samples >> (2 * (kEnvironmentLevels - 1 - level)));
    for (int y = 0; y < target.height; ++y)
      for (int x = 0; x < target.width; ++x)
        target.at(x, y) = prefilter(source, target.texelDirection(x, y), roughness, levelSamples);
  }
  prefilter_cache::store(image, samples, out.levels);
  out.encodeLevels(filtering);
  return out;
}

EnvironmentFilterError environmentFilterError(const EnvironmentImage& level, EnvironmentEncodingKind kind, float scale,
                                              bool eightBitFilter, int samples, unsigned seed) {
  const std::vector<glm::vec4> channels = normalisedChannels(encodeEnvironmentLevel(kind, level.texels, scale));
  double levelMean = 0.0;
  for (const glm::vec3& c : level.texels) levelMean += brightestChannel(c);
  const float floorValue = static_cast<float>(0.01 * levelMean / static_cast<double>(level.texels.size()));
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<double> errors;
  errors.reserve(static_cast<size_t>(samples));
  EnvironmentFilterError out;
  for (int i = 0; i < samples; ++i) {
    const glm::vec2 uv(unit(random), unit(random));
    const glm::vec3 reference = bilinear(level.texels, level.width, level.height, uv);
    glm::vec4 filtered = bilinear(channels, level.width, level.height, uv);
    // llvmpipe's filter returns 8-bit channels (a fixed-point blend of UNORM8 texels); GPUs keep more bits.
    if (eightBitFilter) filtered = glm::floor(filtered * 255.0f + 0.5f) / 255.0f;
    const glm::vec3 got = decodeEnvironmentChannels(kind, filtered, scale);
    float difference = 0.0f;
    for (int c = 0; c < 3; ++c) difference = std::max(difference, std::abs(got[c] - reference[c]));
    const double relative = difference / std::max(brightestChannel(reference), floorValue);
    errors.push_back(relative);
    out.mean += relative;
    out.worst = std::max(out.worst, relative);
  }
  out.mean /= std::max(samples, 1);
  std::sort(errors.begin(), errors.end());
  if (!errors.empty()) out.p99 = errors[static_cast<size_t>(0.99 * static_cast<double>(errors.size() - 1))];
  return out;
}

std::vector<HdrTexel> PrefilteredEnvironment::encodedLevel(int level) const {
  std::vector<HdrTexel> out;
  out.reserve(levels[level].texels.size());
  for (const glm::vec3& c : levels[level].texels) out.push_back(encodeHdr(c));
  return out;
}

std::vector<EnvironmentTexel> PrefilteredEnvironment::filteredLevel(int level) const {
  return encodeEnvironmentLevel(kEnvironmentEncoding, levels[level].texels, filteredScale_);
}

void PrefilteredEnvironment::encodeLevels(EnvironmentFiltering filtering) {
  for (int level = 0; level < kEnvironmentLevels; ++level) {
    decoded_[level].clear();
    for (const HdrTexel& t : encodedLevel(level)) decoded_[level].push_back(decodeHdr(t));
  }
  // One scale for the filtered levels: the brightest channel among them (level 2's: prefiltering only blurs).
  std::vector<glm::vec3> filteredTexels;
  for (int level = kEnvironmentFilteredLevel; level < kEnvironmentLevels; ++level)
    filteredTexels.insert(filteredTexels.end(), levels[level].texels.begin(), levels[level].texels.end());
  filteredScale_ = environmentLevelScale(kEnvironmentEncoding, filteredTexels);
  filterError_ = {};
  for (int level = kEnvironmentFilteredLevel; level < kEnvironmentLevels; ++level) {
    const EnvironmentFilterError e = environmentFilterError(levels[level], kEnvironmentEncoding, filteredScale_, true,
                                                            kEnvironmentFilterSamples, 1234u + static_cast<unsigned>(level));
    filterError_.mean = std::max(filterError_.mean, e.mean);
    filterError_.p99 = std::max(filterError_.p99, e.p99);
    filterError_.worst = std::max(filterError_.worst, e.worst);
  }
  const bool withinBound =
      filterError_.p99 <= kEnvironmentFilterBound.p99 && filterError_.worst <= kEnvironmentFilterBound.worst;
  const bool filtered = filtering == EnvironmentFiltering::Hardware ||
                        (filtering == EnvironmentFiltering::Measured && withinBound);
  filteredFrom_ = filtered ? kEnvironmentFilteredLevel : kEnvironmentLevels;
  for (int level = 0; level < kEnvironmentLevels; ++level)
    filtered_[level] = level >= filteredFrom_ ? normalisedChannels(filteredLevel(level)) : std::vector<glm::vec4>();
}

float roundedToHalfFloat(float value) {
  return glm::unpackHalf1x16(halfFloatBits(value));
}

glm::vec3 PrefilteredEnvironment::sample(const glm::vec3& direction, float roughness, EnvironmentLayout layout) const {
  const glm::vec2 uv = equirectUv(glm::normalize(direction));
  const float lod = std::clamp(roughness, 0.0f, 1.0f) * static_cast<float>(kEnvironmentLevels - 1);
  const float base = std::floor(lod);
  const float f = lod - base;
  const int k = static_cast<int>(base);
  auto level = [&](int i) {
    if (layout == EnvironmentLayout::HalfFloatAtlas)
      return bilinear(levels[i].texels, levels[i].width, levels[i].height, uv, [](const glm::vec3& c) {
        return glm::vec3(roundedToHalfFloat(c.r), roundedToHalfFloat(c.g), roundedToHalfFloat(c.b));
      });
    if (i < filteredFrom_) return bilinear(decoded_[i], levels[i].width, levels[i].height, uv);
    return decodeEnvironmentChannels(kEnvironmentEncoding,
                                     bilinear(filtered_[i], levels[i].width, levels[i].height, uv), filteredScale_);
  };
  const glm::vec3 c = level(k);
  return f > 0.0f ? c + (level(k + 1) - c) * f : c;
}

glm::vec3 prefilterReference(const EnvironmentImage& image, const glm::vec3& r, double roughness) {
  const double alpha = roughness * roughness;
  const glm::dvec3 n = glm::normalize(glm::dvec3(r));
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  for (int y = 0; y < image.height; ++y) {
    const double solidAngle = image.texelSolidAngle(y);
    for (int x = 0; x < image.width; ++x) {
      const glm::dvec3 l(image.texelDirection(x, y));
      const double nDotL = glm::dot(n, l);
      if (nDotL <= 0.0) continue;
      const double w = ggxDistribution(glm::dot(n, glm::normalize(n + l)), alpha) * nDotL * solidAngle;
      sum += glm::dvec3(image.at(x, y)) * w;
      weight += w;
    }
  }
  return glm::vec3(sum / weight);
}

glm::vec2 envBrdfApprox(float roughness, float nDotV) {
  // Karis 2014: c0 = (-1, -0.0275, -0.572, 0.022), c1 = (1, 0.0425, 1.04, -0.04).
  const float rx = -roughness + 1.0f, ry = -0.0275f * roughness + 0.0425f;
  const float rz = -0.572f * roughness + 1.04f, rw = 0.022f * roughness - 0.04f;
  const float a004 = std::min(rx * rx, std::exp2(-9.28f * nDotV)) * rx + ry;
  return {-1.04f * a004 + rz, 1.04f * a004 + rw};
}

glm::vec2 envBrdfIntegrated(float roughness, float nDotV, int samples) {
  const double alpha = static_cast<double>(roughness) * roughness;
  const double nv = std::max(static_cast<double>(nDotV), 1e-4);
  const glm::dvec3 v(std::sqrt(1.0 - nv * nv), 0.0, nv);
  const double k = alpha / 2.0;  // Schlick-GGX's k for image-based light (Karis 2013)
  auto g1 = [k](double c) { return c / (c * (1.0 - k) + k); };
  double a = 0.0, b = 0.0;
  for (int i = 0; i < samples; ++i) {
    const glm::dvec3 h = sampleGgx((i + 0.5) / samples, radicalInverse(static_cast<unsigned>(i)), alpha);
    const glm::dvec3 l = 2.0 * glm::dot(v, h) * h - v;
    const double nl = l.z, nh = h.z, vh = std::max(glm::dot(v, h), 0.0);
    if (nl <= 0.0) continue;
    // BRDF (n.l) / pdf with pdf = D (n.h) / (4 v.h): G v.h / (n.h n.v); F = F0 (1 - Fc) + Fc.
    const double visibility = g1(nv) * g1(nl) * vh / (nh * nv);
    const double fc = std::pow(1.0 - vh, 5.0);
    a += (1.0 - fc) * visibility;
    b += fc * visibility;
  }
  return glm::vec2(static_cast<float>(a / samples), static_cast<float>(b / samples));
}

std::vector<std::uint8_t> computeEnvironmentBrdfTable() {
  const TimedScope timed("brdf table");
  std::vector<std::uint8_t> bytes;
  for (int j = 0; j < kEnvironmentBrdfSize; ++j)
    for (int i = 0; i < kEnvironmentBrdfSize; ++i) {
      const glm::vec2 ab = envBrdfIntegrated((static_cast<float>(j) + 0.5f) / kEnvironmentBrdfSize,
                                             (static_cast<float>(i) + 0.5f) / kEnvironmentBrdfSize, 1024);
      auto byte = [](float v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
      bytes.insert(bytes.end(), {byte(ab.x), byte(ab.y), 0, 255});
    }
  return bytes;
}

#if OBSCURA_BOOTSTRAP_ENVIRONMENT
// tools/bake_environment.cpp, which makes the baked table, is built with this file alone: it computes it.
const std::vector<std::uint8_t>& environmentBrdfTable() {
  static const std::vector<std::uint8_t> table = computeEnvironmentBrdfTable();
  return table;
}
#endif

glm::vec2 environmentBrdf(float roughness, float nDotV) {
  const std::vector<std::uint8_t>& table = environmentBrdfTable();
  const float n = static_cast<float>(kEnvironmentBrdfSize);
  const float px = std::clamp(nDotV, 0.0f, 1.0f) * n - 0.5f, py = std::clamp(roughness, 0.0f, 1.0f) * n - 0.5f;
  const float fx0 = std::floor(px), fy0 = std::floor(py);
  const float fx = px - fx0, fy = py - fy0;
  auto clampIndex = [](float v) { return std::clamp(static_cast<int>(v), 0, kEnvironmentBrdfSize - 1); };
  const int x0 = clampIndex(fx0), x1 = clampIndex(fx0 + 1.0f), y0 = clampIndex(fy0), y1 = clampIndex(fy0 + 1.0f);
  auto at = [&](int x, int y) {
    const size_t i = (static_cast<size_t>(y) * kEnvironmentBrdfSize + x) * 4;
    return glm::vec2(table[i], table[i + 1]) / 255.0f;
  };
  const glm::vec2 top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * fx;
  const glm::vec2 bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * fx;
  return top + (bottom - top) * fy;
}

glm::vec3 ambientLightMirror(const ShIrradiance& sh, const PrefilteredEnvironment& specular, const glm::vec3& n,
                             const glm::vec3& v, const glm::vec3& diffuseColor, const glm::vec3& f0,
                             float roughness) {
  const float nDotV = std::clamp(glm::dot(n, v), 0.0f, 1.0f);
  const glm::vec2 ab = environmentBrdf(roughness, nDotV);
  const glm::vec3 specularAlbedo = f0 * ab.x + ab.y;
  const glm::vec3 r = 2.0f * glm::dot(n, v) * n - v;
  return diffuseColor * (1.0f - specularAlbedo) * glm::max(sh.reflectedRadiance(n), glm::vec3(0.0f)) +
         specularAlbedo * specular.sample(r, roughness);
}

const char* environmentLayoutName(EnvironmentLayout layout) {
  switch (layout) {
    case EnvironmentLayout::MipChain: return "mipchain";
    case EnvironmentLayout::Atlas: return "atlas";
    case EnvironmentLayout::HalfFloatAtlas: return "halffloat";
  }
  return "atlas";
}

EnvironmentLayout GpuEnvironment::layoutFor(const gl::GlCaps& caps, std::optional<EnvironmentLayout> forced) {
  const EnvironmentLayout wanted = forced.value_or(EnvironmentLayout::HalfFloatAtlas);
  if (wanted == EnvironmentLayout::HalfFloatAtlas && caps.textureHalfFloatLinear) return wanted;
  if (wanted != EnvironmentLayout::Atlas && caps.shaderTextureLod) return EnvironmentLayout::MipChain;
  return EnvironmentLayout::Atlas;
}

std::vector<std::pair<std::string, std::string>> GpuEnvironment::shaderDefines(EnvironmentLayout layout,
                                                                              int filteredFrom) {
  const glm::ivec2 brdf = environmentFilteredOrigin(-1);
  return {{"ENVIRONMENT_LOD", layout == EnvironmentLayout::MipChain ? "1" : "0"},
          {"ENVIRONMENT_HALF_FLOAT", layout == EnvironmentLayout::HalfFloatAtlas ? "1" : "0"},
          {"ENVIRONMENT_SKY_CUBE", layout == EnvironmentLayout::HalfFloatAtlas ? "1" : "0"},
          {"ENVIRONMENT_HALF_FLOAT_SIZE", "vec2(" + std::to_string(kEnvironmentHalfFloatWidth) + ".0, " +
                                              std::to_string(kEnvironmentHalfFloatHeight) + ".0)"},
          {"ENVIRONMENT_LEVELS", std::to_string(kEnvironmentLevels)},
          {"ENVIRONMENT_FILTERED_FROM", std::to_string(filteredFrom)},
          {"ENVIRONMENT_FILTERED_LEVEL", std::to_string(kEnvironmentFilteredLevel)},
          {"ENVIRONMENT_ENCODING", std::to_string(static_cast<int>(kEnvironmentEncoding))},
          {"ENVIRONMENT_WIDTH", std::to_string(kEnvironmentWidth) + ".0"},
          {"ENVIRONMENT_HEIGHT", std::to_string(kEnvironmentHeight) + ".0"},
          {"ENVIRONMENT_FILTERED_SIZE", "vec2(" + std::to_string(kEnvironmentFilteredWidth) + ".0, " +
                                            std::to_string(kEnvironmentFilteredHeight) + ".0)"},
          {"ENVIRONMENT_BRDF_ORIGIN",
           "vec2(" + std::to_string(brdf.x) + ".0, " + std::to_string(brdf.y) + ".0)"},
          {"ENVIRONMENT_BRDF_SIZE", std::to_string(kEnvironmentBrdfSize) + ".0"}};
}

glm::vec3 cubeFaceDirection(int face, const glm::vec2& st) {
  const float sc = 2.0f * st.x - 1.0f, tc = 2.0f * st.y - 1.0f;
  switch (face) {
    case 0: return {1.0f, -tc, -sc};
    case 1: return {-1.0f, -tc, sc};
    case 2: return {sc, 1.0f, tc};
    case 3: return {sc, -1.0f, -tc};
    case 4: return {sc, -tc, 1.0f};
    default: return {-sc, -tc, -1.0f};
  }
}

std::array<std::vector<glm::vec3>, 6> skyCubeFaces(const PrefilteredEnvironment& specular) {
  const TimedScope timed("sky cube faces");
  constexpr int n = kEnvironmentSkyFace;
  // sample(d, 0, HalfFloatAtlas) per texel, with level 0 rounded to half floats once, not at each of the 221,184
  // lookups (natively 31 -> 18 ms; the page's start-up: docs/lighting.md).
  const EnvironmentImage& level = specular.levels[0];
  std::vector<glm::vec3> rounded;
  rounded.reserve(level.texels.size());
  for (const glm::vec3& c : level.texels)
    rounded.emplace_back(roundedToHalfFloat(c.r), roundedToHalfFloat(c.g), roundedToHalfFloat(c.b));
  std::array<std::vector<glm::vec3>, 6> faces;
  for (int face = 0; face < 6; ++face) {
    faces[static_cast<size_t>(face)].reserve(static_cast<size_t>(n) * n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const glm::vec3 d = cubeFaceDirection(face, (glm::vec2(x, y) + 0.5f) / static_cast<float>(n));
        const glm::vec3 c = bilinear(rounded, level.width, level.height, equirectUv(glm::normalize(d)));
        faces[static_cast<size_t>(face)].emplace_back(roundedToHalfFloat(c.r), roundedToHalfFloat(c.g),
                                                      roundedToHalfFloat(c.b));
      }
  }
  return faces;
}

glm::vec3 skyCubeSample(const std::array<std::vector<glm::vec3>, 6>& faces, const glm::vec3& d) {
  // GL's table (OpenGL ES 2.0, table 3.21): the major axis picks the face, (sc, tc) / |ma| the place on it.
  const glm::vec3 a = glm::abs(d);
  int face;
  float sc, tc, ma;
  if (a.x >= a.y && a.x >= a.z) {
    face = d.x >= 0.0f ? 0 : 1, sc = d.x >= 0.0f ? -d.z : d.z, tc = -d.y, ma = a.x;
  } else if (a.y >= a.z) {
    face = d.y >= 0.0f ? 2 : 3, sc = d.x, tc = d.y >= 0.0f ? d.z : -d.z, ma = a.y;
  } else {
    face = d.z >= 0.0f ? 4 : 5, sc = d.z >= 0.0f ? d.x : -d.x, tc = -d.y, ma = a.z;
  }
  constexpr int n = kEnvironmentSkyFace;
  const glm::vec2 p = (glm::vec2(sc, tc) / ma + 1.0f) * 0.5f * static_cast<float>(n) - 0.5f;
  const glm::vec2 p0 = glm::floor(p), f = p - p0;
  const std::vector<glm::vec3>& texels = faces[static_cast<size_t>(face)];
  auto at = [&](float x, float y) {
    const int ix = std::clamp(static_cast<int>(x), 0, n - 1), iy = std::clamp(static_cast<int>(y), 0, n - 1);
    return texels[static_cast<size_t>(iy) * n + static_cast<size_t>(ix)];
  };
  const glm::vec3 top = glm::mix(at(p0.x, p0.y), at(p0.x + 1.0f, p0.y), f.x);
  const glm::vec3 bottom = glm::mix(at(p0.x, p0.y + 1.0f), at(p0.x + 1.0f, p0.y + 1.0f), f.x);
  return glm::mix(top, bottom, f.y);
}

glm::ivec2 environmentFilteredOrigin(int level) {
  // Levels kEnvironmentFilteredLevel .. 5 stacked from the top, each inside its one-texel border; the table below.
  int y = 0;
  const int last = level < 0 ? kEnvironmentLevels : level;
  for (int j = kEnvironmentFilteredLevel; j < last; ++j) y += (kEnvironmentHeight >> j) + 2;
  return {1, y + 1};
}

glm::ivec2 environmentHalfFloatOrigin(int level) {
  int y = 0;
  for (int j = 0; j < level; ++j) y += (kEnvironmentHeight >> j) + 2;
  return {1, y + 1};
}

namespace {

// Texels inside a one-texel border, which repeats the far column (u wraps) and the edge rows (v clamps), or clamps
// both ways (wrap false), into an atlas `atlasWidth` wide: the hardware's bilinear filter then reads each block as
// the shader's addressing would.
template <typename T>
void placeBordered(std::vector<T>& atlas, int atlasWidth, const std::vector<T>& texels, int w, int h,
                   glm::ivec2 origin, bool wrap) {
  for (int y = -1; y <= h; ++y)
    for (int x = -1; x <= w; ++x) {
      const int sx = wrap ? (x + w) % w : std::clamp(x, 0, w - 1), sy = std::clamp(y, 0, h - 1);
      atlas[static_cast<size_t>(origin.y + y) * static_cast<size_t>(atlasWidth) + static_cast<size_t>(origin.x + x)] =
          texels[static_cast<size_t>(sy) * static_cast<size_t>(w) + static_cast<size_t>(sx)];
    }
}

using HalfTexel = std::array<std::uint16_t, 4>;
constexpr GLenum kRgba16f = 0x881A, kHalfFloat = 0x140B;  // desktop GL 3.0's sized format and type

}  // namespace

GpuEnvironment::GpuEnvironment(EnvironmentLayout layout, const PrefilteredEnvironment& specular,
                               const ShIrradiance& sh, bool desktopGl)
    : layout_(layout),
      texture_(gl::TextureHandle::create()),
      filtered_(gl::TextureHandle::create()),
      filteredFrom_(layout == EnvironmentLayout::HalfFloatAtlas ? kEnvironmentLevels : specular.filteredFrom()),
      filteredScale_(specular.filteredScale()),
      polynomial_(sh.polynomial()) {
  const TimedScope timed("environment upload");
  const float* floats = &polynomial_[0].x;  // glm::vec3 is three tightly packed floats
  for (size_t i = 0; i < 27; ++i) packedPolynomial_[i / 4][static_cast<glm::length_t>(i % 4)] = floats[i];
  glActiveTexture(GL_TEXTURE0);
  // The filtered texture: RGBM levels and (A, B), plain linear bytes, each inside a border (wrapping in u and
  // clamping in v for the levels, clamping for the table), so the hardware's bilinear filter reads each as its own.
  {
    std::vector<EnvironmentTexel> atlas(static_cast<size_t>(kEnvironmentFilteredWidth) * kEnvironmentFilteredHeight,
                                        EnvironmentTexel{0, 0, 0, 0});
    auto place = [&](const std::vector<EnvironmentTexel>& texels, int w, int h, glm::ivec2 origin, bool wrap) {
      placeBordered(atlas, kEnvironmentFilteredWidth, texels, w, h, origin, wrap);
    };
    for (int level = filteredFrom_; level < kEnvironmentLevels; ++level)
      place(specular.filteredLevel(level), kEnvironmentWidth >> level, kEnvironmentHeight >> level,
            environmentFilteredOrigin(level), true);
    const std::vector<std::uint8_t>& table = environmentBrdfTable();
    std::vector<EnvironmentTexel> brdf(table.size() / 4);
    for (size_t i = 0; i < brdf.size(); ++i) brdf[i] = {table[4 * i], table[4 * i + 1], table[4 * i + 2], table[4 * i + 3]};
    place(brdf, kEnvironmentBrdfSize, kEnvironmentBrdfSize, environmentFilteredOrigin(-1), false);
    glBindTexture(GL_TEXTURE_2D, filtered_.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, kEnvironmentFilteredWidth, kEnvironmentFilteredHeight, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, atlas.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  }

  glBindTexture(GL_TEXTURE_2D, texture_.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  const bool halfFloat = layout == EnvironmentLayout::HalfFloatAtlas;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, halfFloat ? GL_LINEAR : GL_NEAREST);
  if (halfFloat) {
    std::vector<HalfTexel> atlas(static_cast<size_t>(kEnvironmentHalfFloatWidth) * kEnvironmentHalfFloatHeight,
                                 HalfTexel{0, 0, 0, 0});
    const std::uint16_t one = halfFloatBits(1.0f);
    for (int level = 0; level < kEnvironmentLevels; ++level) {
      std::vector<HalfTexel> texels;
      texels.reserve(specular.levels[level].texels.size());
      for (const glm::vec3& c : specular.levels[level].texels)
        texels.push_back({halfFloatBits(c.r), halfFloatBits(c.g), halfFloatBits(c.b), one});
      placeBordered(atlas, kEnvironmentHalfFloatWidth, texels, kEnvironmentWidth >> level,
                    kEnvironmentHeight >> level, environmentHalfFloatOrigin(level), true);
    }
    glTexImage2D(GL_TEXTURE_2D, 0, desktopGl ? kRgba16f : GL_RGBA, kEnvironmentHalfFloatWidth,
                 kEnvironmentHalfFloatHeight, 0, GL_RGBA, desktopGl ? kHalfFloat : GL_HALF_FLOAT_OES, atlas.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    // The background's cube (skyCubeFaces).
    sky_ = gl::TextureHandle::create();
    glBindTexture(GL_TEXTURE_CUBE_MAP, sky_.id());
    const std::array<std::vector<glm::vec3>, 6> faces = skyCubeFaces(specular);
    std::vector<HalfTexel> texels(faces[0].size());
    for (int face = 0; face < 6; ++face) {
      for (size_t i = 0; i < texels.size(); ++i) {
        const glm::vec3& c = faces[static_cast<size_t>(face)][i];
        texels[i] = {halfFloatBits(c.r), halfFloatBits(c.g), halfFloatBits(c.b), one};
      }
      glTexImage2D(static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face), 0, desktopGl ? kRgba16f : GL_RGBA,
                   kEnvironmentSkyFace, kEnvironmentSkyFace, 0, GL_RGBA, desktopGl ? kHalfFloat : GL_HALF_FLOAT_OES,
                   texels.data());
    }
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    glBindTexture(GL_TEXTURE_2D, texture_.id());
  } else if (layout == EnvironmentLayout::MipChain) {
    // Levels 0 .. 5 the roughness levels; the rest, down to 1 x 1, hold level 5's mean (never read: the shader's
    // level stops at 5; GLES 2 samples only a complete chain).
    glm::vec3 mean(0.0f);
    for (const glm::vec3& c : specular.levels[kEnvironmentLevels - 1].texels) mean += c;
    mean /= static_cast<float>(specular.levels[kEnvironmentLevels - 1].texels.size());
    for (int level = 0;; ++level) {
      const int w = std::max(kEnvironmentWidth >> level, 1), h = std::max(kEnvironmentHeight >> level, 1);
      std::vector<HdrTexel> texels = level < kEnvironmentLevels
                                         ? specular.encodedLevel(level)
                                         : std::vector<HdrTexel>(static_cast<size_t>(w) * h, encodeHdr(mean));
      glTexImage2D(GL_TEXTURE_2D, level, GL_RGBA, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
      if (w == 1 && h == 1) break;
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  } else {
    // Level 0 at the left; level k >= 1 to its right at y = H (1 - 2^(1 - k)): 256 x 128 at the top, then 128 x 64,
    // .. (lib/environment.glsl's environmentTexel computes the same origins).
    const int atlasWidth = kEnvironmentWidth + kEnvironmentWidth / 2, atlasHeight = kEnvironmentHeight;
    std::vector<HdrTexel> atlas(static_cast<size_t>(atlasWidth) * atlasHeight, HdrTexel{0, 0, 0, 0});
    int originY = 0;
    for (int level = 0; level < kEnvironmentLevels; ++level) {
      const int w = kEnvironmentWidth >> level, h = kEnvironmentHeight >> level;
      const int originX = level == 0 ? 0 : kEnvironmentWidth;
      const std::vector<HdrTexel> texels = specular.encodedLevel(level);
      for (int y = 0; y < h; ++y)
        std::copy_n(&texels[static_cast<size_t>(y) * w], w,
                    &atlas[static_cast<size_t>(originY + y) * atlasWidth + originX]);
      if (level > 0) originY += h;
    }
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, atlasWidth, atlasHeight, 0, GL_RGBA, GL_UNSIGNED_BYTE, atlas.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace obscura
