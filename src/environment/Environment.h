#pragma once
// Image-based ambient light: the environment's radiance per direction, its irradiance as spherical harmonics and its
// specular reflection prefiltered per roughness (the CPU side; the GPU side is shaders_es2/lib/environment.glsl, read
// by the lighting pass, docs/lighting.md).
//
// Directions are world space, y up. An environment is an equirectangular image: u = atan2(x, -z) / 2 pi + 1/2 (u
// = 1/2 looks down -z), v = acos(y) / pi (v = 0 the zenith, the first row). Texels are linear radiance.
//
// Diffuse: Ramamoorthi & Hanrahan, "An Efficient Representation for Irradiance Environment Maps", SIGGRAPH 2001.
//   The radiance projected on the nine real spherical harmonics of order <= 2 (their eq. 10, basis constants eq. 3),
//   then the irradiance E(n) as the quadratic polynomial of their eq. 13 (c1 .. c5). The shader evaluates
//   E(n) / pi, the radiance a white Lambertian surface reflects, from nine vec3 coefficients of the monomials
//   1, x, y, z, xy, yz, xz, x^2 - y^2, z^2 (ShIrradiance::polynomial).
// Specular: the split sum of Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013 course notes:
//   L_spec ~ prefiltered(R, roughness) * (F0 A + B). The prefiltered radiance, with n = v = r,
//     P(r, alpha) = integral L(l) D(h) (n.l)+ dl / integral D(h) (n.l)+ dl,   h = (n + l) / |n + l|,
//   estimated by GGX importance sampling (Karis's PrefilterEnvMap, alpha = roughness^2) with filtered importance
//   sampling (Colbert & Krivanek, GPU Gems 3 ch. 20: each sample reads a source level whose texel covers the sample's
//   solid angle), stored for roughness 0, 0.2, .., 1 as the levels of one texture, halving in size.
//   (A, B): a 32 x 32 table over (n.v, roughness) integrated on the CPU (envBrdfIntegrated: Karis 2013's IntegrateBRDF)
//   and read with the hardware's bilinear filter, which is right for its plain linear bytes. Karis's analytic fit
//   ("Physically Based Shading on Mobile", 2014: envBrdfApprox) was measured too and is off by up to 0.18 in A
//   (tests/test_environment.cpp prints both against the integral).
//
// Storage (GpuEnvironment): two textures.
//   half floats  where the context filters half-float textures (OES_texture_half_float_linear; desktop GL 3.0), the
//             first texture holds every level as RGBA half floats, LINEAR, stacked from the top of a 514 x 516 atlas,
//             each inside a one-texel border that wraps in u and clamps in v (environmentHalfFloatOrigin): one fetch
//             per level, no decode. Half floats keep 11 significant bits, RGB9E5 9, so this is the most exact storage
//             as well as the cheapest: on SwiftShader it took the page's deferred lighting from about 56 to 39 ms at
//             1280 x 720 (docs/lighting.md). The filtered texture then holds the (A, B) table alone.
//             Otherwise:
//   by hand   every level in scene-color's RGB9E5 encoding (encoding/HdrEncoding.h), NEAREST. An encoded texel cannot
//             be filtered by the hardware, so the shader filters by hand: four texel centres of a level, each
//             decoded, weighted bilinearly (wrapping in u, clamped in v). Two layouts give the same texel centres:
//     mip chain  EXT_shader_texture_lod: the roughness levels are mip levels 0 .. 5 of one 512 x 256 texture (6 .. 9
//                hold level 5's mean, for a complete chain), read with texture2DLodEXT at integer levels.
//     atlas      otherwise (a documented fallback, core GLES 2 / WebGL 1): level 0 at the left, levels 1 .. 5
//                stacked in a column to its right (768 x 256), read with texture2D at computed coordinates.
//   filtered  LINEAR: levels 2 .. 5 (roughness 0.4 .. 1) as RGBM texels with one scale (encoding/
//             EnvironmentEncoding.h), each inside a one-texel border that repeats its far column and its edge rows,
//             so that the hardware's bilinear filter wraps in u and clamps in v: one fetch and a multiply per level;
//             and the (A, B) table below, inside a border that clamps. 130 x 162 texels (environmentFilteredOrigin).
// The shader reads levels from filteredFrom() on from the filtered texture, the others by hand. filteredFrom() is 2
// where levels 2 .. 5 read through the filter stay within kEnvironmentFilterBound of the linear texels (measured
// when the environment is prepared, for a filter whose output keeps only 8 bits, as llvmpipe's does), else 6: none.
// Two levels are blended by the fractional level.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "encoding/EnvironmentEncoding.h"
#include "encoding/HdrEncoding.h"
#include "environment/EnvironmentLayout.h"
#include "gl/GlCaps.h"
#include "gl/GlObjects.h"

namespace obscura {

glm::vec2 equirectUv(const glm::vec3& direction);  // unit direction -> (u, v) in [0, 1]^2
glm::vec3 equirectDirection(const glm::vec2& uv);  // and back (unit)

// Linear radiance over the sphere as an equirectangular image, rows from the zenith down.
struct EnvironmentImage {
  int width = 0, height = 0;
  std::vector<glm::vec3> texels;

  EnvironmentImage() = default;
  EnvironmentImage(int w, int h) : width(w), height(h), texels(static_cast<size_t>(w) * h) {}
  glm::vec3& at(int x, int y) { return texels[static_cast<size_t>(y) * width + x]; }
  const glm::vec3& at(int x, int y) const { return texels[static_cast<size_t>(y) * width + x]; }
  glm::vec3 texelDirection(int x, int y) const;  // through the texel's centre
  // Solid angle of a texel of row y: (2 pi / width) (cos theta0 - cos theta1).
  double texelSolidAngle(int y) const;
  // Bilinear between texel centres, wrapping in u, clamping in v.
  glm::vec3 radiance(const glm::vec3& direction) const;
  // A 2 x 2 box average (width and height even).
  EnvironmentImage halved() const;
};

// The direction towards a sun `elevationDegrees` above the horizon (+y up), `azimuthDegrees` from +z towards +x: unit.
glm::vec3 sunDirection(float elevationDegrees, float azimuthDegrees);
// The default sun (LightingSettings' lighting.sun-elevation and sun-azimuth): the built-in sky made for it is ready
// when a process starts (environment/BuiltinSky.h).
constexpr float kBuiltinSunElevation = 54.525961f, kBuiltinSunAzimuth = 52.125016f;

// The built-in sky: a zenith-to-horizon gradient, a ground below, and a sun disc with a glow around it towards
// `sunDirection` (the default sun's direction, LightingSettings::directionToSun).
struct ProceduralSky {
  glm::vec3 sunDirection{0.45f, 0.8f, 0.35f};  // normalised when used
  glm::vec3 zenith{0.30f, 0.45f, 0.75f};
  glm::vec3 horizon{0.78f, 0.80f, 0.84f};
  glm::vec3 ground{0.30f, 0.28f, 0.26f};
  glm::vec3 sun{40.0f, 37.0f, 33.0f};  // the disc's radiance (HDR: bloom and tone mapping see a bright sun)
  float sunCosRadius = 0.99966f;        // cos of the disc's angular radius, 1.5 degrees
  glm::vec3 glow{0.9f, 0.7f, 0.45f};   // glow = glow (cos gamma)^64 over the sky, gamma the angle to the sun

  glm::vec3 radiance(const glm::vec3& direction) const;
  // Each texel the mean of 4 x 4 directions over it (the disc's edge antialiased).
  EnvironmentImage image(int width, int height) const;
};

// The same radiance everywhere (the white furnace: 1).
EnvironmentImage uniformEnvironment(const glm::vec3& radiance, int width = 64, int height = 32);

// An equirectangular image from a file: Radiance .hdr (stb_image's HDR loader), or a PNG holding RGBE bytes (Ward's
// shared exponent, decoded (m + 0.5) 2^(E - 136) as encoding/HdrEncoding's Rgbe: what Radiance tools and three.js's
// RGBELoader write). Throws InputError naming the path. `maxWidth` downsamples (2 x 2 boxes) larger images.
EnvironmentImage loadEnvironmentImage(const std::string& path, int maxWidth = 2048);

// Ramamoorthi & Hanrahan 2001: the radiance's nine coefficients L_lm and the irradiance polynomial.
struct ShIrradiance {
  // L_00, L_1-1, L_10, L_11, L_2-2, L_2-1, L_20, L_21, L_22 (their order; y = sin th sin ph, z = cos th, x = ...).
  std::array<glm::vec3, 9> coefficients{};

  static ShIrradiance project(const EnvironmentImage& image);  // sum of L Y_lm dOmega over the texels
  static std::array<float, 9> basis(const glm::vec3& direction);  // Y_lm, R&H eq. 3
  // E(n) / pi from eq. 13: for a constant environment L, L; for L(w) = a.w, (2/3) a.n.
  glm::vec3 reflectedRadiance(const glm::vec3& normal) const;
  // The coefficients of 1, x, y, z, xy, yz, xz, x^2 - y^2, z^2 in E(n) / pi: the shader's u_shIrradiance.
  std::array<glm::vec3, 9> polynomial() const;
};

constexpr int kEnvironmentLevels = 6;  // roughness 0, 0.2, .., 1: level k holds roughness k / 5
constexpr int kEnvironmentWidth = 512, kEnvironmentHeight = 256;  // level 0; level k is 512 / 2^k x 256 / 2^k
inline float environmentLevelRoughness(int level) { return static_cast<float>(level) / (kEnvironmentLevels - 1); }

// GGX's normal distribution D(h) (Walter et al. 2007, Trowbridge-Reitz), alpha = roughness^2.
double ggxDistribution(double nDotH, double alpha);

// The filtered texture (Storage above): its first level, its encoding, and the error its levels may have against
// the bilinear filter over their linear texels, relative to the reference's brightest channel at the point (floored
// at 1 % of the level's mean): at the 99th percentile and at worst, over environmentFilterSamples points per level.
constexpr int kEnvironmentFilteredLevel = 2;
constexpr EnvironmentEncodingKind kEnvironmentEncoding = EnvironmentEncodingKind::Rgbm;
struct EnvironmentFilterError {
  double mean = 0.0, p99 = 0.0, worst = 0.0;
};
inline constexpr EnvironmentFilterError kEnvironmentFilterBound{0.0, 0.02, 0.05};
constexpr int kEnvironmentFilterSamples = 4096;
// One level encoded with `kind` and `scale` and read through the bilinear filter at `samples` random points (seeded),
// against the filter over its linear texels. eightBitFilter: the filter's output rounded to 8 bits per channel.
EnvironmentFilterError environmentFilterError(const EnvironmentImage& level, EnvironmentEncodingKind kind, float scale,
                                              bool eightBitFilter, int samples, unsigned seed);

// The environment prefiltered per roughness level (linear radiance).
struct PrefilteredEnvironment {
  std::array<EnvironmentImage, kEnvironmentLevels> levels;

  // `samples`: GGX samples per texel of level 5 (roughness 1); each finer level takes a quarter as many, at least
  // 64 (its texels are four times as many and its lobe narrower). Level 0, roughness 0, is the image resampled.
  // `filtering`: which levels the filtered texture holds (Storage above).
  static PrefilteredEnvironment of(const EnvironmentImage& image, int samples = 4096,
                                   EnvironmentFiltering filtering = EnvironmentFiltering::Measured);
  // Levels made elsewhere (environment/BuiltinSky.h: at build time), encoded for `filtering` as of() encodes its own.
  static PrefilteredEnvironment fromLevels(std::array<EnvironmentImage, kEnvironmentLevels> levels,
                                           EnvironmentFiltering filtering);
  // P(r, roughness) for one texel direction by the importance-sampled estimator above.
  static glm::vec3 prefilter(const std::vector<EnvironmentImage>& sourceLevels, const glm::vec3& r, double roughness,
                             int samples);
  // The mirror of environmentSpecular() in lib/environment.glsl over these levels as `layout`'s textures hold them:
  // in the two levels around roughness * 5, bilinear over the decoded RGB9E5 texels, or (from filteredFrom() on) the
  // decoded bilinear blend of the RGBM bytes, as the hardware's filter reads them, or (HalfFloatAtlas) bilinear over
  // the texels rounded to half floats; blended.
  glm::vec3 sample(const glm::vec3& direction, float roughness,
                   EnvironmentLayout layout = EnvironmentLayout::Atlas) const;
  // Each level's texels in the RGB9E5 encoding, rows in the image's order.
  std::vector<HdrTexel> encodedLevel(int level) const;
  // A level from kEnvironmentFilteredLevel on in kEnvironmentEncoding with filteredScale().
  std::vector<EnvironmentTexel> filteredLevel(int level) const;
  // The first level read through the hardware's filter: kEnvironmentFilteredLevel, or kEnvironmentLevels (none).
  int filteredFrom() const { return filteredFrom_; }
  // The RGBM scale of the filtered levels: their brightest channel.
  float filteredScale() const { return filteredScale_; }
  // The largest error of the filtered levels (an 8-bit filter), which chose filteredFrom().
  const EnvironmentFilterError& filterError() const { return filterError_; }

 private:
  std::array<std::vector<glm::vec3>, kEnvironmentLevels> decoded_;  // the RGB9E5 texels decoded (sample())
  // The filtered levels' bytes as normalised channels (the hardware filters these, then the shader decodes).
  std::array<std::vector<glm::vec4>, kEnvironmentLevels> filtered_;
  int filteredFrom_ = kEnvironmentLevels;
  float filteredScale_ = 1.0f;
  EnvironmentFilterError filterError_;
  void encodeLevels(EnvironmentFiltering filtering);
};

// The same integral as prefilter() by brute force: every texel of `image` weighted by D(h) (n.l)+ dOmega.
glm::vec3 prefilterReference(const EnvironmentImage& image, const glm::vec3& r, double roughness);

// The split sum's (A, B): specular reflectance = F0 A + B (Karis 2013). envBrdfApprox is Karis 2014's fit, mirrored
// by lib/environment.glsl; envBrdfIntegrated the integral of the GGX / Smith (Schlick-GGX, k = alpha / 2) BRDF with
// Schlick's Fresnel, importance-sampled with `samples` Hammersley points (Karis 2013's IntegrateBRDF).
glm::vec2 envBrdfApprox(float roughness, float nDotV);
glm::vec2 envBrdfIntegrated(float roughness, float nDotV, int samples = 2048);

// The table the shader reads: texel (i, j) holds round(255 A), round(255 B) in R and G at n.v = (i + 0.5) / size,
// roughness = (j + 0.5) / size, rows from roughness 0. computeEnvironmentBrdfTable() integrates it (about 2 million
// samples); environmentBrdfTable() is the one made when the library was built (environment/BuiltinSky.h).
constexpr int kEnvironmentBrdfSize = 32;
std::vector<std::uint8_t> computeEnvironmentBrdfTable();
const std::vector<std::uint8_t>& environmentBrdfTable();
// The table read as the GPU's LINEAR, clamped lookup at (n.v, roughness) reads it: lib/environment.glsl's
// environmentBrdf().
glm::vec2 environmentBrdf(float roughness, float nDotV);

// The ambient term of lib/environment.glsl's ambientLight() with occlusion 1, on the CPU, for an environment given by
// its irradiance and its prefiltered levels: diffuse (1 - s) E/pi + s P, s = F0 A + B from environmentBrdf().
glm::vec3 ambientLightMirror(const ShIrradiance& sh, const PrefilteredEnvironment& specular, const glm::vec3& n,
                             const glm::vec3& v, const glm::vec3& diffuseColor, const glm::vec3& f0, float roughness);

// The background's cube map (GpuEnvironment::skyTexture, where the levels are half floats): level 0 resampled onto
// six faces of kEnvironmentSkyFace texels, half floats the hardware filters (LINEAR, clamped at each face's edge).
// The background is the one place the environment is read at roughness 0 over most of the frame: a cube is read
// along the eye's ray as the rasteriser interpolates it, with no normalisation, atan, acos or atlas addressing at
// each pixel (docs/benchmarks.md: the sky in the bands). Faces in GL's order (+x, -x, +y, -y, +z, -z), rows from
// t = 0; each texel the equirectangular level 0 as the half-float atlas filters it (PrefilteredEnvironment::sample),
// at the texel centre's direction, rounded to half floats (RGBA, 1.8 MB). 192 texels to a face: 0.0104 rad at a
// face's centre, finer than level 0's 0.0123, so the resampling blurs the sky by less than a texel of level 0.
constexpr int kEnvironmentSkyFace = 192;
// The direction of GL's cube-map coordinates (s, t) in [0, 1]^2 on `face` (OpenGL ES 2.0, sec. 3.7.5), not unit.
glm::vec3 cubeFaceDirection(int face, const glm::vec2& st);
// The faces' texels, kEnvironmentSkyFace^2 each.
std::array<std::vector<glm::vec3>, 6> skyCubeFaces(const PrefilteredEnvironment& specular);
// The mirror of textureCube on those faces: the face of the largest component, bilinear, clamped at its edges.
glm::vec3 skyCubeSample(const std::array<std::vector<glm::vec3>, 6>& faces, const glm::vec3& direction);

// One environment on the GPU: the specular texture and the irradiance polynomial. Owns its texture.
class GpuEnvironment {
 public:
  // The half-float atlas where the context filters half floats, else the mip chain where it has
  // EXT_shader_texture_lod, else the atlas; `forced` picks one (a forced layout the context lacks falls back the
  // same way).
  static EnvironmentLayout layoutFor(const gl::GlCaps& caps, std::optional<EnvironmentLayout> forced);
  // Uploads `specular`'s levels as `layout` keeps them and keeps `sh`'s polynomial. `desktopGl`: the context takes
  // the sized half-float format (GL_RGBA16F) where GLES 2 takes GL_RGBA with HALF_FLOAT_OES.
  GpuEnvironment(EnvironmentLayout layout, const PrefilteredEnvironment& specular, const ShIrradiance& sh,
                 bool desktopGl = false);

  EnvironmentLayout layout() const { return layout_; }
  // The levels: RGB9E5, NEAREST, filtered by hand (MipChain, Atlas), or half floats, LINEAR (HalfFloatAtlas).
  GLuint texture() const { return texture_.id(); }
  // LINEAR: the RGBM levels (from filteredFrom(); none when it is kEnvironmentLevels) and environmentBrdfTable().
  GLuint filteredTexture() const { return filtered_.id(); }
  // The background's cube map (skyCubeFaces) in the half-float layout; 0 in the others, which read level 0 by hand.
  GLuint skyTexture() const { return sky_.id(); }
  // kEnvironmentLevels in the half-float atlas: its own levels are exact under the filter.
  int filteredFrom() const { return filteredFrom_; }
  float filteredScale() const { return filteredScale_; }
  const std::array<glm::vec3, 9>& irradiancePolynomial() const { return polynomial_; }
  // The polynomial as the shader's u_shIrradiance holds it: its 27 floats in order in 7 vec4 (the last float 0), so
  // it takes 7 fragment uniform vectors instead of the 9 that 9 vec3 take under GLSL ES 1.00's packing (Appendix A):
  // the forward lighting must fit GLES 2's 16 (LightingEffect.h).
  const std::array<glm::vec4, 7>& irradianceUniform() const { return packedPolynomial_; }
  // The shader's defines: ENVIRONMENT_LOD 1 (mip chain) or 0 (atlas), ENVIRONMENT_FILTERED_FROM (filteredFrom()),
  // ENVIRONMENT_SKY_CUBE (skyTexture() exists), the level count and the textures' sizes.
  static std::vector<std::pair<std::string, std::string>> shaderDefines(EnvironmentLayout layout, int filteredFrom);

 private:
  EnvironmentLayout layout_;
  gl::TextureHandle texture_, filtered_, sky_;
  int filteredFrom_;
  float filteredScale_;
  std::array<glm::vec3, 9> polynomial_{};
  std::array<glm::vec4, 7> packedPolynomial_{};
};

// The filtered texture's size, and where a level's texels (kEnvironmentFilteredLevel .. 5) or the (A, B) table's
// begin in it (level -1), inside their borders: the levels stacked from the top, the table below them.
constexpr int kEnvironmentFilteredWidth = (kEnvironmentWidth >> kEnvironmentFilteredLevel) + 2;  // 130
constexpr int kEnvironmentFilteredHeight = 162;  // 66 + 34 + 18 + 10 + the table's 34
glm::ivec2 environmentFilteredOrigin(int level);
// The half-float atlas's size, and where level k's texels begin in it, inside their border: levels 0 .. 5 stacked
// from the top, at y = 1 + sum over j < k of (256 / 2^j + 2) = 513 - 2^(9 - k) + 2 k (lib/environment.glsl).
constexpr int kEnvironmentHalfFloatWidth = kEnvironmentWidth + 2;  // 514
constexpr int kEnvironmentHalfFloatHeight = 516;                   // 258 + 130 + 66 + 34 + 18 + 10
glm::ivec2 environmentHalfFloatOrigin(int level);
// A value as the half-float texture holds it: rounded to the nearest half float (IEEE 754 binary16), at most 65504.
float roundedToHalfFloat(float value);

}  // namespace obscura
