// glTF 2.0 metallic-roughness shading (effects/lighting/LightingEffect.h, shaders_es2/lib/pbr.glsl): the CPU mirror
// against the BRDF's definition integrated numerically; the GPU's lighting pass read back (scene-color, decoded)
// against the mirror at sample angles, per texture slot (a quad whose texture differs only between its halves, only
// that slot set), under KHR_texture_transform, and for KHR_lights_punctual point and spot lights against the analytic
// falloff; tangent generation on meshes whose tangents are known.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "effects/lighting/LightingEffect.h"
#include "effects/lighting/PbrShading.h"
#include "encoding/HdrEncoding.h"
#include "encoding/NormalEncoding.h"
#include "scene/GltfLoader.h"
#include "scene/MeshProcessing.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

constexpr int kSide = 65;  // odd: the middle pixel's centre is the image's centre
constexpr float kFovy = 50.0f;

using test::HdrFrame;

// The uniform environment's radiance in these tests: ambient light comparable to the sun's, as the sky's is.
constexpr double kAmbientRadiance = 0.5;

RenderSettings plainSettings() {
  RenderSettings settings;
  settings.set("ao", "off");  // the AO texture is then white: occlusion is the material's alone
  settings.set("fxaa", "off");
  // A uniform environment (radiance 1 everywhere; the white furnace's) and a dimmer one: the mirror's ambient is
  // then exact, the SH irradiance and every prefiltered level being that radiance.
  settings.set("lighting.environment", "uniform");
  settings.set("lighting.environment-intensity", std::to_string(kAmbientRadiance));
  return settings;
}

HdrFrame renderHdr(const Scene& scene, const RenderSettings& settings, int width = kSide, int height = kSide) {
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  const Camera camera = test::makeCamera({0, 0, 5}, {0, 0, 0}, width, height, 0.1f, 100.0f, kFovy);
  test::render(renderer, camera, settings, View::Final, test::retaining({"scene-color"}));
  return {width, height, renderer.retained("scene-color").readRgba()};
}

// The camera of renderHdr is at (0, 0, 5) looking down -z with +y up: view space is world space moved by -5 in z.
// The view-space point where pixel (x, row)'s centre ray meets the plane through the origin with normal n.
glm::dvec3 viewPointOnPlane(int x, int row, int width, int height, const glm::dvec3& n) {
  const double tanY = std::tan(glm::radians(static_cast<double>(kFovy)) / 2.0);
  const double tanX = tanY * width / height;
  const glm::dvec3 d((2.0 * (x + 0.5) / width - 1.0) * tanX, (1.0 - 2.0 * (row + 0.5) / height) * tanY, -1.0);
  const glm::dvec3 eye(0.0, 0.0, 5.0);
  const double t = -glm::dot(n, eye) / glm::dot(n, d);
  return t * d;
}

// The lit colour the mirror expects at a view-space point of a surface with shading normal n, with the sun.
glm::dvec3 expectedColor(const glm::dvec3& p, const glm::dvec3& n, const pbr::SurfaceParameters& s,
                         const LightingSettings& sun, double occlusion = 1.0,
                         const glm::dvec3& emissive = glm::dvec3(0.0)) {
  const glm::dvec3 v = -glm::normalize(p);
  const glm::dvec3 l = glm::normalize(glm::dvec3(sun.directionToSun()));
  return pbr::ambientLight(glm::dvec3(kAmbientRadiance), n, v, s, occlusion) + emissive +
         pbr::brdfCosine(n, v, l, s) * glm::dvec3(sun.sunColor) * static_cast<double>(sun.sunIntensity);
}

double worstRelative(const glm::dvec3& got, const glm::dvec3& expected) {
  const double scale = std::max({expected.r, expected.g, expected.b, 0.05});
  return std::max({std::abs(got.r - expected.r), std::abs(got.g - expected.g), std::abs(got.b - expected.b)}) / scale;
}

// A square quad through the origin facing +z, 2 halfSize wide (uv (0,0) at its lower left; u along +x, v along +y),
// with material 0.
Scene quadScene(const Material& material, float halfSize = 2.0f) {
  Scene scene = test::sceneOf({test::makeRectangle({-halfSize, -halfSize, 0}, {2 * halfSize, 0, 0},
                                                   {0, 2 * halfSize, 0})});
  scene.materials.push_back(material);
  scene.meshes[0].material = 0;
  return scene;
}

// A 2 x 1 texture, NEAREST and clamped: `left` on the quad's left half (u < 0.5), `right` on its right half.
int addTwoTexelTexture(Scene& scene, std::array<std::uint8_t, 4> left, std::array<std::uint8_t, 4> right,
                       int wrap = 0x812F) {
  Image image;
  image.width = 2;
  image.height = 1;
  image.rgba = {left[0], left[1], left[2], left[3], right[0], right[1], right[2], right[3]};
  scene.images.push_back(image);
  Texture texture;
  texture.image = static_cast<int>(scene.images.size()) - 1;
  texture.sampler = {0x2600, 0x2600, wrap, wrap};  // GL_NEAREST; GL_CLAMP_TO_EDGE or the wrap asked for
  scene.textures.push_back(texture);
  return static_cast<int>(scene.textures.size()) - 1;
}

double channel(std::uint8_t byte) { return byte / 255.0; }

// A quad of `material` tilted by `tiltDegrees` about x, under plainSettings() with the sun at (elevation, azimuth):
// the HDR colour of its centre pixel (where the view direction is exactly +z), that pixel's view-space point and the
// quad's normal, with the settings it was drawn with.
struct TiltedQuadCentre {
  RenderSettings settings;
  glm::dvec3 color, point, normal;
};
TiltedQuadCentre renderTiltedQuadCentre(const Material& material, double tiltDegrees, float elevation,
                                        float azimuth) {
  Scene scene = quadScene(material);
  const glm::mat4 tilt = glm::rotate(glm::mat4(1.0f), glm::radians(static_cast<float>(tiltDegrees)), {1, 0, 0});
  scene.instances[0].world = tilt;
  TiltedQuadCentre out{plainSettings(), {}, {}, {}};
  out.settings.of<LightingSettings>().sunElevation = elevation;
  out.settings.of<LightingSettings>().sunAzimuth = azimuth;
  const HdrFrame frame = renderHdr(scene, out.settings);
  out.normal = glm::normalize(glm::dvec3(glm::dmat3(glm::dmat4(tilt)) * glm::dvec3(0, 0, 1)));
  const int middle = kSide / 2;
  out.point = viewPointOnPlane(middle, middle, kSide, kSide, out.normal);
  out.color = frame.at(middle, middle);
  return out;
}

}  // namespace

// The mirror is the BRDF of glTF 2.0 Appendix B: white furnace checks (a white Lambertian surface reflects its
// irradiance, the GGX distribution's projected area integrates to 1) and the Fresnel and Smith terms' limits.
TEST(Pbr, TheMirrorIsTheBrdfOfTheSpecification) {
  const glm::dvec3 n(0.0, 0.0, 1.0);
  for (double roughness : {0.2, 0.5, 1.0}) {
    const double alpha = roughness * roughness;
    // integral of D(h) (n.h) over the hemisphere = 1.
    double integral = 0.0;
    const int steps = 4000;
    for (int i = 0; i < steps; ++i) {
      const double theta = (i + 0.5) / steps * pbr::kPi / 2.0;
      integral += pbr::distributionGgx(std::cos(theta), alpha) * std::cos(theta) * std::sin(theta) *
                  (pbr::kPi / 2.0 / steps) * 2.0 * pbr::kPi;
    }
    EXPECT_NEAR(integral, 1.0, 2e-3) << roughness;
  }
  // Lambert: a black-Fresnel-free check: (1 - F) c / pi NL with F0 = 0.04 at normal incidence.
  pbr::SurfaceParameters white{glm::dvec3(1.0), 0.0, 1.0};
  const glm::dvec3 head = pbr::brdfCosine(n, n, n, white);
  const double f = 0.04;
  const double alpha = 1.0;
  const double specular = f * pbr::distributionGgx(1.0, alpha) * pbr::visibilitySmithGgx(1.0, 1.0, alpha);
  EXPECT_NEAR(head.r, (1.0 - f) / pbr::kPi + specular, 1e-12);
  EXPECT_NEAR(pbr::visibilitySmithGgx(1.0, 1.0, 0.5), 0.25, 1e-12);  // G = 1 at normal incidence: 1 / (4 NL NV)
  EXPECT_NEAR(pbr::fresnelSchlick(glm::dvec3(0.04), glm::dvec3(1.0), 0.0).r, 1.0, 1e-12);
  EXPECT_NEAR(pbr::fresnelSchlick(glm::dvec3(0.04), glm::dvec3(1.0), 1.0).r, 0.04, 1e-12);
  EXPECT_EQ(pbr::brdfCosine(n, n, glm::dvec3(0.0, 0.6, -0.8), white), glm::dvec3(0.0));  // light below the surface
  // KHR_lights_punctual's falloff and cone.
  EXPECT_NEAR(pbr::punctualFalloff(2.0, 0.0), 0.25, 1e-12);
  EXPECT_NEAR(pbr::punctualFalloff(2.0, 4.0), std::pow(1.0 - 1.0 / 16.0, 2.0) / 4.0, 1e-12);
  EXPECT_EQ(pbr::punctualFalloff(5.0, 4.0), 0.0);
  EXPECT_NEAR(pbr::spotCone(std::cos(0.1), 0.2, 0.4), 1.0, 1e-12);
  EXPECT_EQ(pbr::spotCone(std::cos(0.5), 0.2, 0.4), 0.0);
  // Specular occlusion: no AO, no occlusion; full AO, full.
  EXPECT_NEAR(pbr::specularOcclusion(0.7, 1.0, 0.3), 1.0, 1e-12);
  EXPECT_NEAR(pbr::specularOcclusion(0.7, 0.0, 0.3), 0.0, 1e-12);
}

// The lighting pass against the mirror at sample angles: a flat quad tilted about x, its centre pixel (where the
// view direction is exactly +z), under suns from several directions, for a rough dielectric, a rough metal and
// smooth ones.
TEST(Pbr, TheLightingPassMatchesTheMirrorAtSampleAngles) {
  struct Case {
    double tilt;  // degrees about x
    float elevation, azimuth;
    glm::dvec3 base;
    double metallic, roughness;
  };
  const std::vector<Case> cases = {
      {0, 54.5f, 52.1f, {0.8, 0.8, 0.8}, 0.0, 1.0},  {0, 80.0f, 0.0f, {0.9, 0.5, 0.2}, 0.0, 0.3},
      {30, 20.0f, 90.0f, {0.9, 0.5, 0.2}, 1.0, 0.4}, {-40, 60.0f, 180.0f, {0.95, 0.9, 0.8}, 1.0, 0.2},
      {60, 10.0f, 30.0f, {0.3, 0.6, 0.9}, 0.5, 0.6}, {20, 70.0f, -20.0f, {0.5, 0.5, 0.5}, 0.0, 0.15},
  };
  double worst = 0.0;
  for (const Case& c : cases) {
    Material material;
    material.baseColorFactor = glm::vec4(glm::vec3(c.base), 1.0f);
    material.metallicFactor = static_cast<float>(c.metallic);
    material.roughnessFactor = static_cast<float>(c.roughness);
    const TiltedQuadCentre centre = renderTiltedQuadCentre(material, c.tilt, c.elevation, c.azimuth);
    const glm::dvec3& n = centre.normal;
    const glm::dvec3& p = centre.point;
    const RenderSettings& settings = centre.settings;
    const glm::dvec3 expected =
        expectedColor(p, n, {c.base, c.metallic, c.roughness}, settings.of<LightingSettings>());
    const glm::dvec3& got = centre.color;
    const double error = worstRelative(got, expected);
    worst = std::max(worst, error);
    std::printf("tilt %5.1f sun (%4.1f, %5.1f) metallic %.1f roughness %.2f: gpu (%.4f %.4f %.4f) mirror "
                "(%.4f %.4f %.4f) error %.4f\n",
                c.tilt, c.elevation, c.azimuth, c.metallic, c.roughness, got.r, got.g, got.b, expected.r,
                expected.g, expected.b, error);
    EXPECT_LT(error, 0.01) << "case tilt " << c.tilt << " metallic " << c.metallic << " roughness " << c.roughness;
  }
  std::printf("BRDF at sample angles: worst error %.5f of the brightest channel\n", worst);
}

// Each texture slot seen in the image: a quad whose only texture is that slot's, with one texel on its left half and
// another on its right; both halves against the mirror given the texel's value, and the halves must differ.
TEST(Pbr, EachTextureSlotIsSeenInTheImage) {
  const int width = kSide, height = kSide;
  const int leftX = width / 4, rightX = 3 * width / 4, row = height / 2;
  const glm::dvec3 base(0.8, 0.5, 0.3);
  struct Slot {
    const char* name;
    std::array<std::uint8_t, 4> left, right;
  };
  const std::vector<Slot> slots = {
      {"metallicRoughness", {0, 255, 0, 255}, {0, 77, 255, 255}},  // G roughness, B metallic
      // flat, then tilted towards +u and +v: towards the sun (under the uniform ambient the sun shows the tilt)
      {"normal", {128, 128, 255, 255}, {191, 156, 238, 255}},
      {"occlusion", {255, 0, 0, 255}, {64, 0, 0, 255}},
      {"emissive", {0, 0, 0, 255}, {255, 128, 0, 255}},
  };
  const LightingSettings sun;
  for (const Slot& slot : slots) {
    Material material;
    material.baseColorFactor = glm::vec4(glm::vec3(base), 1.0f);
    material.metallicFactor = 1.0f;
    material.roughnessFactor = 1.0f;
    material.emissiveStrength = 4.0f;  // KHR_materials_emissive_strength: brighter than 1
    material.occlusionStrength = 0.75f;
    Scene scene = quadScene(material);
    const int texture = addTwoTexelTexture(scene, slot.left, slot.right);
    const std::string name = slot.name;
    Material& m = scene.materials[0];
    if (name == "metallicRoughness") m.metallicRoughnessTexture = texture;
    if (name == "normal") m.normalTexture = texture;
    if (name == "occlusion") m.occlusionTexture = texture;
    if (name == "emissive") {
      m.emissiveTexture = texture;
      m.emissiveFactor = glm::vec3(1.0f);
    }
    if (name != "metallicRoughness") m.metallicFactor = 0.0f;  // a dielectric, so the diffuse term shows the slot
    const HdrFrame frame = renderHdr(scene, plainSettings(), width, height);

    glm::dvec3 got[2], expected[2];
    for (int side = 0; side < 2; ++side) {
      const std::array<std::uint8_t, 4>& texel = side == 0 ? slot.left : slot.right;
      const int x = side == 0 ? leftX : rightX;
      const glm::dvec3 geometric(0.0, 0.0, 1.0);
      pbr::SurfaceParameters s{base, m.metallicFactor, m.roughnessFactor};
      glm::dvec3 n = geometric, emissive(0.0);
      double occlusion = 1.0;
      if (name == "metallicRoughness") {
        s.metallic = channel(texel[2]);
        s.roughness = channel(texel[1]);
      } else if (name == "normal") {
        // The frame of makeRectangle's quad: tangent +x (along u), bitangent +y (along v), normal +z.
        const glm::dvec3 t(channel(texel[0]) * 2 - 1, channel(texel[1]) * 2 - 1, channel(texel[2]) * 2 - 1);
        n = glm::normalize(glm::dvec3(t.x, t.y, t.z));
      } else if (name == "occlusion") {
        occlusion = 1.0 + 0.75 * (channel(texel[0]) - 1.0);
      } else {
        emissive = 4.0 * glm::dvec3(std::pow(channel(texel[0]), 2.2), std::pow(channel(texel[1]), 2.2),
                                    std::pow(channel(texel[2]), 2.2));
      }
      const glm::dvec3 p = viewPointOnPlane(x, row, width, height, geometric);
      expected[side] = expectedColor(p, n, s, sun, occlusion, emissive);
      got[side] = frame.at(x, row);
      std::printf("%s %s: gpu (%.4f %.4f %.4f) mirror (%.4f %.4f %.4f)\n", slot.name, side == 0 ? "left " : "right",
                  got[side].r, got[side].g, got[side].b, expected[side].r, expected[side].g, expected[side].b);
      EXPECT_LT(worstRelative(got[side], expected[side]), 0.01) << slot.name << (side == 0 ? " left" : " right");
    }
    // The slot must show: the halves differ by much more than the tolerance.
    EXPECT_GT(glm::length(got[1] - got[0]), 0.05 * glm::length(got[0])) << slot.name;
  }
}

// A node mirrored by a negative scale keeps its normal texture's meaning: the texture's u runs along -x on screen, its
// v still along +y, so a texel tilted towards +u and +v tilts the shading normal towards -x and +y (geometry.vert
// turns the bitangent's sign with the transform's determinant; before, the mirrored quad's normal tilted towards -y).
TEST(Pbr, TheNormalTextureFollowsAMirroredNode) {
  const int width = kSide, height = kSide, row = height / 2;
  const glm::dvec3 base(0.8, 0.5, 0.3);
  const std::array<std::uint8_t, 4> flat = {128, 128, 255, 255}, tilted = {191, 156, 238, 255};
  Material material;
  material.baseColorFactor = glm::vec4(glm::vec3(base), 1.0f);
  material.metallicFactor = 0.0f;
  material.roughnessFactor = 1.0f;
  const LightingSettings sun;
  for (const bool mirrored : {false, true}) {
    Scene scene = quadScene(material);
    scene.materials[0].normalTexture = addTwoTexelTexture(scene, flat, tilted);
    if (mirrored) scene.instances[0].world = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
    const HdrFrame frame = renderHdr(scene, plainSettings(), width, height);
    // The tilted texel covers u > 0.5: the right half, or the left one mirrored.
    const int x = mirrored ? width / 4 : 3 * width / 4;
    const glm::dvec3 t(channel(tilted[0]) * 2 - 1, channel(tilted[1]) * 2 - 1, channel(tilted[2]) * 2 - 1);
    const glm::dvec3 n = glm::normalize(glm::dvec3(mirrored ? -t.x : t.x, t.y, t.z));
    const glm::dvec3 wrongN = glm::normalize(glm::dvec3(mirrored ? -t.x : t.x, -t.y, t.z));
    const glm::dvec3 p = viewPointOnPlane(x, row, width, height, glm::dvec3(0.0, 0.0, 1.0));
    const pbr::SurfaceParameters s{base, 0.0, 1.0};
    const glm::dvec3 expected = expectedColor(p, n, s, sun), wrong = expectedColor(p, wrongN, s, sun);
    const glm::dvec3 got = frame.at(x, row);
    std::printf("%s: gpu (%.4f %.4f %.4f) mirror (%.4f %.4f %.4f); with the bitangent reversed (%.4f %.4f %.4f)\n",
                mirrored ? "mirrored" : "as made", got.r, got.g, got.b, expected.r, expected.g, expected.b, wrong.r,
                wrong.g, wrong.b);
    EXPECT_LT(worstRelative(got, expected), 0.01) << (mirrored ? "mirrored" : "as made");
    EXPECT_GT(worstRelative(wrong, expected), 0.05) << "the bitangent's sign must show for the test to tell";
  }
}

// KHR_texture_transform on a slot other than the base colour: an offset of half the texture (REPEAT) swaps the
// emissive texture's halves, and the emission is then seen on the left.
TEST(Pbr, TheTextureTransformMovesItsSlot) {
  const int width = kSide, height = kSide;
  auto emissionAt = [&](bool transformed) {
    Material material;
    material.emissiveFactor = glm::vec3(1.0f);
    material.emissiveStrength = 3.0f;
    Scene scene = quadScene(material);
    scene.materials[0].emissiveTexture = addTwoTexelTexture(scene, {0, 0, 0, 255}, {255, 255, 255, 255}, 0x2901);
    if (transformed)
      scene.materials[0].uvTransforms[static_cast<size_t>(TextureSlot::Emissive)] =
          glm::mat3(1, 0, 0, 0, 1, 0, 0.5f, 0, 1);  // columns: translate u by 0.5
    const HdrFrame frame = renderHdr(scene, plainSettings(), width, height);
    return std::make_pair(frame.at(width / 4, height / 2).g, frame.at(3 * width / 4, height / 2).g);
  };
  const auto [plainLeft, plainRight] = emissionAt(false);
  const auto [movedLeft, movedRight] = emissionAt(true);
  std::printf("emission left/right: plain %.3f %.3f, offset by half %.3f %.3f\n", plainLeft, plainRight, movedLeft,
              movedRight);
  EXPECT_GT(plainRight, plainLeft + 2.5);
  EXPECT_NEAR(movedLeft, plainRight, 0.01 * plainRight);
  EXPECT_NEAR(movedRight, plainLeft, 0.01 * plainRight);
}

// KHR_lights_punctual: a point light and a spot light in front of a wall; the lit image minus the same frame with the
// light at intensity 0 is the light's own contribution, per pixel against BRDF x intensity x falloff x cone.
TEST(Pbr, PunctualLightsMatchTheAnalyticFalloff) {
  const int width = 97, height = 65;
  struct Case {
    const char* name;
    PunctualLight light;
  };
  PunctualLight point;
  point.type = LightType::Point;
  point.color = {1.0f, 0.8f, 0.6f};
  point.intensity = 6.0f;
  point.range = 2.2f;  // the window reaches 0 on the wall 1.96 m around the light's foot
  point.world = glm::translate(glm::mat4(1.0f), glm::vec3(0.4f, -0.3f, 1.0f));
  PunctualLight spot = point;
  spot.type = LightType::Spot;
  spot.range = 0.0f;
  spot.intensity = 15.0f;
  spot.innerConeAngle = 0.2f;
  spot.outerConeAngle = 0.4f;
  // Shining along its -z at the wall, from 1.5 m, turned a little about y.
  spot.world = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-0.3f, 0.2f, 1.5f)), 0.15f, glm::vec3(0, 1, 0));
  for (const Case& c : {Case{"point", point}, Case{"spot", spot}}) {
    Material material;
    material.baseColorFactor = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
    material.roughnessFactor = 0.5f;  // forward lighting, and a specular lobe to see
    Scene scene = quadScene(material, 8.0f);  // filling the frame
    scene.lights.push_back(c.light);
    const HdrFrame lit = renderHdr(scene, plainSettings(), width, height);
    scene.lights[0].intensity = 0.0f;
    const HdrFrame unlit = renderHdr(scene, plainSettings(), width, height);

    const glm::dvec3 n(0.0, 0.0, 1.0);
    const glm::dvec3 lightPosition = glm::dvec3(c.light.world[3]) - glm::dvec3(0.0, 0.0, 5.0);  // view space
    const glm::dvec3 axis = glm::normalize(glm::dvec3(glm::dmat3(glm::dmat4(c.light.world)) * glm::dvec3(0, 0, -1)));
    const pbr::SurfaceParameters s{glm::dvec3(0.7), 0.0, 0.5};
    double worst = 0.0, peak = 0.0;
    int dark = 0, bright = 0;
    std::vector<std::pair<glm::dvec3, glm::dvec3>> samples;
    for (int row = 0; row < height; row += 2) {
      for (int x = 0; x < width; x += 2) {
        const glm::dvec3 p = viewPointOnPlane(x, row, width, height, n);
        const glm::dvec3 toLight = lightPosition - p;
        const double distance = glm::length(toLight);
        const glm::dvec3 l = toLight / distance;
        double attenuation = pbr::punctualFalloff(distance, c.light.range);
        if (c.light.type == LightType::Spot)
          attenuation *= pbr::spotCone(glm::dot(axis, -l), c.light.innerConeAngle, c.light.outerConeAngle);
        const glm::dvec3 expected = pbr::brdfCosine(n, -glm::normalize(p), l, s) *
                                    glm::dvec3(c.light.color) * static_cast<double>(c.light.intensity) * attenuation;
        samples.emplace_back(lit.at(x, row) - unlit.at(x, row), expected);
        peak = std::max(peak, expected.r);
        dark += expected.r == 0.0;
        bright += expected.r > 0.2;
      }
    }
    // Relative to the light's brightest contribution: RGB9E5 keeps about 9 bits of each pixel's brightest channel,
    // and the pixels carry the ambient and the sun besides (up to about 1.0).
    for (const auto& [got, expected] : samples)
      worst = std::max(worst, std::max({std::abs(got.r - expected.r), std::abs(got.g - expected.g),
                                        std::abs(got.b - expected.b)}) / peak);
    std::printf("%s light: %zu pixels, peak %.3f, %d unlit by it, %d brighter than 0.2; worst error %.5f of the peak\n",
                c.name, samples.size(), peak, dark, bright, worst);
    EXPECT_LT(worst, 0.01) << c.name;
    EXPECT_GT(dark, 10) << c.name << ": the range or the cone must leave pixels unlit for the test to tell";
    EXPECT_GT(bright, 10) << c.name;
  }
}

// The punctual lights per draw follow the context's fragment uniform vectors (LightingEffect::punctualLightsPerDraw):
// a renderer limited to GLES 2's 16 draws none of the file's lights (the sun and the ambient light the wall as
// with the lights at intensity 0), one limited to 18 the strongest at the camera alone, and an unlimited one both.
TEST(Pbr, PunctualLightsPerDrawFollowTheFragmentUniformVectors) {
  EXPECT_EQ(LightingEffect::punctualLightsPerDraw(16), 0);
  EXPECT_EQ(LightingEffect::punctualLightsPerDraw(18), 1);
  EXPECT_EQ(LightingEffect::punctualLightsPerDraw(24), 3);
  EXPECT_EQ(LightingEffect::punctualLightsPerDraw(27), 4);
  EXPECT_EQ(LightingEffect::punctualLightsPerDraw(1024), 4);

  Material material;
  material.baseColorFactor = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
  material.roughnessFactor = 0.5f;
  Scene scene = quadScene(material, 8.0f);
  PunctualLight strong;
  strong.type = LightType::Point;
  strong.color = {1.0f, 0.8f, 0.6f};
  strong.intensity = 6.0f;
  strong.world = glm::translate(glm::mat4(1.0f), glm::vec3(0.6f, 0.0f, 1.0f));
  PunctualLight weak = strong;
  weak.color = {0.5f, 0.7f, 1.0f};
  weak.intensity = 3.0f;
  weak.world = glm::translate(glm::mat4(1.0f), glm::vec3(-0.6f, 0.0f, 1.0f));
  scene.lights = {weak, strong};  // the order of the file is not the order of choice

  auto render = [&](const Scene& s, std::optional<int> fragmentVectors) {
    RendererOptions options;
    if (fragmentVectors) options.simulateFragmentLimits = FragmentLimits{*fragmentVectors, 8, 8};
    Renderer renderer = test::makeRenderer(options);
    renderer.setScene(s);
    const Camera camera = test::makeCamera({0, 0, 5}, {0, 0, 0}, kSide, kSide, 0.1f, 100.0f, kFovy);
    test::render(renderer, camera, plainSettings(), View::Final, test::retaining({"scene-color"}));
    return HdrFrame{kSide, kSide, renderer.retained("scene-color").readRgba()};
  };
  auto worstDifference = [](const HdrFrame& a, const HdrFrame& b) {
    double worst = 0.0, mean = 0.0;
    for (int row = 0; row < a.height; ++row)
      for (int x = 0; x < a.width; ++x) {
        const double d = worstRelative(a.at(x, row), b.at(x, row));
        worst = std::max(worst, d);
        mean += d / (a.width * a.height);
      }
    return std::make_pair(worst, mean);
  };
  Scene darkWeak = scene, dark = scene;
  darkWeak.lights[0].intensity = 0.0f;
  dark.lights[0].intensity = dark.lights[1].intensity = 0.0f;
  const HdrFrame both = render(scene, std::nullopt), strongOnly = render(darkWeak, std::nullopt),
                 none = render(dark, std::nullopt);
  const auto [noneAt16, noneAt16Mean] = worstDifference(render(scene, 16), none);
  const auto [oneAt18, oneAt18Mean] = worstDifference(render(scene, 18), strongOnly);
  const auto [bothVsOne, bothVsOneMean] = worstDifference(both, strongOnly);
  const auto [oneVsNone, oneVsNoneMean] = worstDifference(strongOnly, none);
  std::printf("relative difference, worst | mean: 16 vectors vs no light %.4f | %.5f, 18 vectors vs the strong light "
              "alone %.4f | %.5f; the weak light's own %.3f | %.4f, the strong light's %.3f | %.4f\n",
              noneAt16, noneAt16Mean, oneAt18, oneAt18Mean, bothVsOne, bothVsOneMean, oneVsNone, oneVsNoneMean);
  // RGB9E5 rounds each pixel's channels to about 1/512 of its brightest.
  EXPECT_LT(noneAt16, 0.01);
  EXPECT_LT(oneAt18, 0.01);
  EXPECT_GT(bothVsOne, 0.1) << "the weak light must show for the test to tell";
  EXPECT_GT(oneVsNone, 0.1);
}

// Tangents generated (scene/MeshProcessing.h) on meshes whose tangent frames are known: a rectangle (tangent along u,
// bitangent sign +1), the same with u mirrored (sign -1), and a UV sphere (tangent along the longitude, d/du).
TEST(Pbr, GeneratedTangentsFollowTheTextureCoordinates) {
  Mesh quad = test::makeRectangle({0, 0, 0}, {2, 0, 0}, {0, 0, -3});  // normal +y, u along +x, v along -z
  generateTangents(quad);
  for (const glm::vec4& t : quad.tangents) {
    EXPECT_NEAR(glm::distance(glm::vec3(t), glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
    EXPECT_EQ(t.w, 1.0f);  // N x T = +y x +x = -z, along dP/dv
  }
  Mesh mirrored = test::makeRectangle({0, 0, 0}, {2, 0, 0}, {0, 0, -3});
  mirrored.texcoords = {{1, 0}, {0, 0}, {0, 1}, {1, 1}};
  generateTangents(mirrored);
  for (const glm::vec4& t : mirrored.tangents) {
    EXPECT_NEAR(glm::distance(glm::vec3(t), glm::vec3(-1, 0, 0)), 0.0f, 1e-6f);
    EXPECT_EQ(t.w, -1.0f);
  }
  Mesh sphere = makeSphere(1.5f, 48, 24);
  generateTangents(sphere);
  float worstDegrees = 0.0f, sumDegrees = 0.0f;
  int counted = 0;
  for (size_t v = 0; v < sphere.positions.size(); ++v) {
    const glm::vec3 n = sphere.normals[v];
    const float sinTheta = std::sqrt(n.x * n.x + n.z * n.z);
    if (sinTheta < 0.2f) continue;  // the poles, where d/du vanishes
    const float phi = sphere.texcoords[v].x * 2.0f * 3.14159265f;
    const glm::vec3 analytic(-std::sin(phi), 0.0f, -std::cos(phi));  // d/dphi of (sin cos phi, ., -sin sin phi)
    const glm::vec3 t(sphere.tangents[v]);
    const float degrees = glm::degrees(std::acos(std::clamp(glm::dot(t, analytic), -1.0f, 1.0f)));
    worstDegrees = std::max(worstDegrees, degrees);
    sumDegrees += degrees;
    ++counted;
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-5f);
    // dP/dv points down the sphere (theta grows with v): B = w (N x T) must too.
    const glm::vec3 b = sphere.tangents[v].w * glm::cross(n, t);
    EXPECT_LT(b.y, 0.0f);
  }
  // The faces' dP/du is the analytic d/du at some point of each face: a vertex's average is off by at most half a
  // slice (3.75 degrees at 48 slices), near the poles where the triangles are most unequal.
  std::printf("UV sphere (48 x 24): generated tangents within %.3f degrees of d/du away from the poles, %.3f on "
              "average\n",
              worstDegrees, sumDegrees / static_cast<float>(counted));
  EXPECT_LT(worstDegrees, 3.75f);
  EXPECT_LT(sumDegrees / static_cast<float>(counted), 0.5f);
}

// The loader reads every input of the material model and KHR_lights_punctual from a file
// (assets/scenes/pbr-samples.glb, written by obscura-make-pbr-samples): factors, the four other texture slots, each
// slot's KHR_texture_transform, KHR_materials_emissive_strength, and point and spot lights placed by their nodes;
// the normal-mapped floor, which has no TANGENT, gets generated tangents.
TEST(Pbr, TheLoaderReadsEveryMaterialInputAndTheLights) {
  GltfLoadReport report;
  const Scene scene = loadGltfFile(test::sourceDir() + "/assets/scenes/pbr-samples.glb", &report);
  for (const std::string& warning : report.warnings) ADD_FAILURE() << warning;
  ASSERT_EQ(scene.materials.size(), 13u);  // ten spheres, the floor, the wall, the panel
  const Material& gold = scene.materials[9];
  EXPECT_FLOAT_EQ(gold.metallicFactor, 1.0f);
  EXPECT_NEAR(gold.roughnessFactor, 1.0f, 1e-6f);
  EXPECT_FALSE(gold.hasPbrTextures());
  const Material& floor = scene.materials[10];
  EXPECT_GE(floor.normalTexture, 0);
  EXPECT_GE(floor.occlusionTexture, 0);
  EXPECT_FLOAT_EQ(floor.metallicFactor, 0.0f);
  for (TextureSlot slot : {TextureSlot::Normal, TextureSlot::Occlusion}) {
    const glm::mat3& t = floor.uvTransforms[static_cast<size_t>(slot)];
    EXPECT_FLOAT_EQ(t[0][0], 6.0f);
    EXPECT_FLOAT_EQ(t[1][1], 4.0f);
  }
  const Material& wall = scene.materials[11];
  EXPECT_GE(wall.metallicRoughnessTexture, 0);
  EXPECT_FLOAT_EQ(wall.uvTransforms[static_cast<size_t>(TextureSlot::MetallicRoughness)][0][0], 4.0f);
  const Material& panel = scene.materials[12];
  EXPECT_GE(panel.emissiveTexture, 0);
  EXPECT_FLOAT_EQ(panel.emissiveStrength, 8.0f);
  EXPECT_NEAR(panel.emissiveFactor.g, 0.55f, 1e-6f);
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].type, LightType::Point);
  EXPECT_FLOAT_EQ(scene.lights[0].range, 5.0f);
  EXPECT_NEAR(glm::distance(glm::vec3(scene.lights[0].world[3]), glm::vec3(0.4f, 1.6f, 0.9f)), 0.0f, 1e-5f);
  EXPECT_EQ(scene.lights[1].type, LightType::Spot);
  EXPECT_FLOAT_EQ(scene.lights[1].outerConeAngle, 0.45f);
  // The spot's -z aims at (-1.2, 0, 0.2) from (-2.6, 2.4, 1.6).
  const glm::vec3 axis = -glm::vec3(scene.lights[1].world[2]);
  EXPECT_GT(glm::dot(glm::normalize(axis), glm::normalize(glm::vec3(1.4f, -2.4f, -1.4f))), 0.9999f);
  int normalMapped = 0;
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.material != 10) continue;
    ++normalMapped;
    ASSERT_EQ(mesh.tangents.size(), mesh.positions.size());
    for (size_t v = 0; v < mesh.tangents.size(); ++v) {
      EXPECT_NEAR(glm::dot(glm::vec3(mesh.tangents[v]), mesh.normals[v]), 0.0f, 1e-5f);
      // The floor's u runs along +x (its quad's first edge).
      EXPECT_NEAR(mesh.tangents[v].x, 1.0f, 1e-5f);
    }
  }
  EXPECT_EQ(normalMapped, 1);
}

// Where the AO goes: it darkens the ambient term only. In a corner (a floor, a wall and a box) with the AO on, the
// sun's contribution (the frame minus the same frame with the sun at intensity 0) is the one the AO-off frames give,
// pixel for pixel; and the ambient term (the frame without the sun) is the mirror's ambientLight at the pixel's AO
// (the diffuse part times it, the specular part times Lagarde's specular occlusion), read from the G-buffer's
// normal and depth and the AO target, with a baked occlusion texture combined by the minimum.
TEST(Pbr, TheAoDarkensTheAmbientTermOnly) {
  const int width = 160, height = 90;
  Material material;
  material.baseColorFactor = glm::vec4(0.8f, 0.7f, 0.6f, 1.0f);
  material.metallicFactor = 0.5f;
  material.roughnessFactor = 0.4f;
  Scene scene = test::sceneOf({test::makeRectangle({-4, 0, 4}, {8, 0, 0}, {0, 0, -8}),  // floor, +y
                               test::makeRectangle({-4, 0, -1}, {8, 0, 0}, {0, 3, 0}),  // wall, +z
                               makeBox({-0.6f, 0.0f, -0.8f}, {0.4f, 0.8f, 0.2f})});
  scene.materials.push_back(material);
  for (Mesh& mesh : scene.meshes) mesh.material = 0;
  // A baked occlusion of 0.6 everywhere (one texel): where the AO sees less, the AO's value counts (their minimum).
  scene.materials[0].occlusionTexture = addTwoTexelTexture(scene, {153, 0, 0, 255}, {153, 0, 0, 255});
  const double baked = 153.0 / 255.0;
  const Camera camera = test::makeCamera({1.5f, 1.6f, 3.0f}, {-0.2f, 0.3f, -0.5f}, width, height, 0.1f, 30.0f);
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  auto frame = [&](bool ao, float sun) {
    RenderSettings settings = plainSettings();
    settings.set("ao", ao ? "on" : "off");
    settings.of<LightingSettings>().sunIntensity = sun;
    test::render(renderer, camera, settings, View::Final,
                 test::retaining(ao ? std::vector<std::string>{"scene-color", "ao", "gbuffer"}
                                    : std::vector<std::string>{"scene-color"}));
    HdrFrame f{width, height, renderer.retained("scene-color").readRgba()};
    return f;
  };
  const HdrFrame litOff = frame(false, 3.14159265f), darkOff = frame(false, 0.0f);
  const HdrFrame lit = frame(true, 3.14159265f), dark = frame(true, 0.0f);
  const std::vector<std::uint8_t> ao = renderer.retained("ao").readRgba();
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  const FrameCamera view = FrameCamera::from(camera, width, height);
  const LightingSettings sun;
  const pbr::SurfaceParameters s{{0.8, 0.7, 0.6}, 0.5, 0.4};
  double worstDirect = 0.0, worstAmbient = 0.0;
  int occluded = 0, covered = 0;
  for (int row = 0; row < height; ++row)
    for (int x = 0; x < width; ++x) {
      const size_t i = (static_cast<size_t>(row) * width + x) * 4;
      const int code = gbuffer[i + 2] * 256 + gbuffer[i + 3];
      if (code == 65535) continue;
      ++covered;
      const glm::dvec3 directOn = lit.at(x, row) - dark.at(x, row), directOff = litOff.at(x, row) - darkOff.at(x, row);
      const double scale = std::max({litOff.at(x, row).r, litOff.at(x, row).g, litOff.at(x, row).b});
      worstDirect = std::max(worstDirect, glm::length(directOn - directOff) / scale);
      // The ambient against the mirror, at pixels away from edges (the G-buffer's normal is the face's there).
      const glm::vec2 uv((static_cast<float>(x) + 0.5f) / width, 1.0f - (static_cast<float>(row) + 0.5f) / height);
      const glm::dvec3 p(view.reconstruction.viewPosition(uv, static_cast<float>(code) / 65535.0f));
      const glm::dvec3 n(decodeNormal(gbuffer[i], gbuffer[i + 1]));
      const double visibility = ao[i] / 255.0;
      occluded += visibility < baked - 0.05;  // where the AO, not the bake, sets the ambient
      const glm::dvec3 expected =
          pbr::ambientLight(glm::dvec3(kAmbientRadiance), n, -glm::normalize(p), s, std::min(visibility, baked));
      worstAmbient = std::max(worstAmbient, worstRelative(dark.at(x, row), expected));
    }
  std::printf("AO on the ambient only: %d pixels, %d with the AO below the baked 0.6; the sun's light with the AO on differs from "
              "it with the AO off by %.5f at most; the ambient's worst error against the mirror %.4f\n",
              covered, occluded, worstDirect, worstAmbient);
  EXPECT_GT(occluded, covered / 40) << "the corner must be occluded for the test to tell";
  EXPECT_LT(worstDirect, 0.01) << "direct light is never darkened by the AO";
  // The G-buffer's normal is 8 bits per octahedral axis (about 0.5 degrees): the mirror's ambient is within 2 %.
  EXPECT_LT(worstAmbient, 0.02);
}

namespace {

// The quad of quadScene with a normal texture of one tilted texel everywhere (tilted towards +u and +v), the
// dielectric `base`, rough.
Scene normalMappedQuad(const glm::dvec3& base) {
  Material material;
  material.baseColorFactor = glm::vec4(glm::vec3(base), 1.0f);
  material.metallicFactor = 0.0f;
  material.roughnessFactor = 1.0f;
  Scene scene = quadScene(material);
  scene.materials[0].normalTexture = addTwoTexelTexture(scene, {191, 156, 238, 255}, {191, 156, 238, 255});
  generateTangents(scene.meshes[0]);
  return scene;
}
const glm::dvec3 kTilted(191 / 255.0 * 2 - 1, 156 / 255.0 * 2 - 1, 238 / 255.0 * 2 - 1);

// The quad's mesh skinned to one joint (node 0, at rest the identity) of skin 0, placed by instance 0.
void skinToOneJoint(Scene& scene, const Node& joint) {
  Mesh& mesh = scene.meshes[0];
  mesh.joints.assign(mesh.positions.size(), glm::u16vec4(0));
  mesh.weights.assign(mesh.positions.size(), glm::vec4(1, 0, 0, 0));
  scene.nodes = {joint};
  Skin skin;
  skin.joints = {0};
  skin.inverseBind = {glm::mat4(1.0f)};
  scene.skins = {skin};
  scene.instances[0].skin = 0;
  scene.instances[0].node = -1;
}

HdrFrame renderWith(const Scene& scene, const RendererOptions& options, const RenderSettings& settings) {
  Renderer renderer = test::makeRenderer(options);
  renderer.setScene(scene);
  const Camera camera = test::makeCamera({0, 0, 5}, {0, 0, 0}, kSide, kSide, 0.1f, 100.0f, kFovy);
  test::render(renderer, camera, settings, View::Final, test::retaining({"scene-color"}));
  return {kSide, kSide, renderer.retained("scene-color").readRgba()};
}

}  // namespace

// KHR_materials_ior, _specular and _clearcoat against the mirror (PbrShading: f0, f90 and coated) at sample angles,
// each case also far enough from the core material that the test can tell.
TEST(Pbr, TheMaterialLayersMatchTheMirror) {
  struct Case {
    const char* name;
    double tilt;
    float elevation, azimuth;  // the sun (at elevation 40, azimuth 0 the tilt of -20 puts its highlight mid-frame)
    glm::dvec3 base;
    double metallic, roughness, ior, specular;
    glm::dvec3 specularColor;
    double clearcoat, clearcoatRoughness;
  };
  const std::vector<Case> cases = {
      {"ior 2.4", 30, 40, 10, {0.2, 0.2, 0.25}, 0.0, 0.3, 2.4, 1.0, {1, 1, 1}, 0.0, 0.0},
      {"specular 0.3 tinted", -20, 40, 10, {0.6, 0.6, 0.6}, 0.0, 0.25, 1.5, 0.3, {1.0, 0.4, 0.2}, 0.0, 0.0},
      {"clear coat on red", -20, 40, 0, {0.8, 0.1, 0.1}, 0.0, 0.9, 1.5, 1.0, {1, 1, 1}, 1.0, 0.15},
      {"half coat on metal", -20, 40, 0, {0.9, 0.7, 0.3}, 1.0, 0.8, 1.5, 1.0, {1, 1, 1}, 0.5, 0.3},
  };
  for (const Case& c : cases) {
    Material material;
    material.baseColorFactor = glm::vec4(glm::vec3(c.base), 1.0f);
    material.metallicFactor = static_cast<float>(c.metallic);
    material.roughnessFactor = static_cast<float>(c.roughness);
    material.ior = static_cast<float>(c.ior);
    material.specularFactor = static_cast<float>(c.specular);
    material.specularColorFactor = glm::vec3(c.specularColor);
    material.clearcoatFactor = static_cast<float>(c.clearcoat);
    material.clearcoatRoughnessFactor = static_cast<float>(c.clearcoatRoughness);
    const TiltedQuadCentre centre = renderTiltedQuadCentre(material, c.tilt, c.elevation, c.azimuth);
    const glm::dvec3& n = centre.normal;
    const glm::dvec3& p = centre.point;
    const RenderSettings& settings = centre.settings;
    pbr::SurfaceParameters s{c.base, c.metallic, c.roughness};
    const pbr::SurfaceParameters core = s;
    s.ior = c.ior;
    s.specular = c.specular;
    s.specularColor = c.specularColor;
    s.clearcoat = c.clearcoat;
    s.clearcoatRoughness = c.clearcoatRoughness;
    const LightingSettings& sun = settings.of<LightingSettings>();
    const glm::dvec3 illuminance = glm::dvec3(sun.sunColor) * static_cast<double>(sun.sunIntensity);
    const glm::dvec3 expected =
        pbr::coated(expectedColor(p, n, s, sun), glm::dvec3(kAmbientRadiance), n, -glm::normalize(p),
                    glm::normalize(glm::dvec3(sun.directionToSun())), illuminance, s, 1.0);
    const glm::dvec3 plain = expectedColor(p, n, core, sun);
    const glm::dvec3& got = centre.color;
    std::printf("%s: gpu (%.4f %.4f %.4f) mirror (%.4f %.4f %.4f) core material (%.4f %.4f %.4f)\n", c.name, got.r,
                got.g, got.b, expected.r, expected.g, expected.b, plain.r, plain.g, plain.b);
    EXPECT_LT(worstRelative(got, expected), 0.01) << c.name;
    EXPECT_GT(worstRelative(plain, expected), 0.05) << c.name << ": the layer must show for the test to tell";
  }
}

// TEXCOORD_1: an emissive texture sampled on the second set, whose coordinates split the quad in halves while the
// first set's sit on one texel, shows both halves; so it does through the CPU-deformed path (skinned on the CPU).
TEST(Pbr, ASlotOnTheSecondTextureCoordinateSetIsSeen) {
  for (bool cpu : {false, true}) {
    Material material;
    material.emissiveFactor = glm::vec3(1.0f);
    material.emissiveStrength = 3.0f;
    Scene scene = quadScene(material);
    scene.materials[0].emissiveTexture = addTwoTexelTexture(scene, {0, 0, 0, 255}, {255, 255, 255, 255});
    scene.materials[0].texCoords[static_cast<size_t>(TextureSlot::Emissive)] = 1;
    Mesh& mesh = scene.meshes[0];
    mesh.texcoords1 = mesh.texcoords;
    mesh.texcoords.assign(mesh.positions.size(), glm::vec2(0.25f, 0.5f));
    RendererOptions options;
    if (cpu) {
      skinToOneJoint(scene, Node{});
      options.skinning = SkinningPath::Cpu;
    }
    const HdrFrame frame = renderWith(scene, options, plainSettings());
    const double left = frame.at(kSide / 4, kSide / 2).g, right = frame.at(3 * kSide / 4, kSide / 2).g;
    std::printf("%s: emission left %.3f right %.3f\n", cpu ? "CPU-deformed" : "as drawn", left, right);
    EXPECT_GT(right, left + 2.5) << (cpu ? "CPU-deformed" : "as drawn");
  }
}

// Morph targets' TANGENT deltas: a target turning the quad's tangent from +x to +y, at weight 1, turns the normal
// texture's tilt with it (the mirror: the tilt's u along +y, its v along -x), on the GPU (the target in attributes)
// and on the CPU (a context with too few attributes for it).
TEST(Pbr, MorphTargetsMoveTheTangents) {
  const glm::dvec3 base(0.8, 0.5, 0.3);
  for (bool cpu : {false, true}) {
    Scene scene = normalMappedQuad(base);
    MorphTarget turn;
    turn.positions.assign(scene.meshes[0].positions.size(), glm::vec3(0.0f));
    turn.tangents.assign(scene.meshes[0].positions.size(), glm::vec3(-1.0f, 1.0f, 0.0f));
    scene.meshes[0].morphTargets = {turn};
    Node node;
    node.weights = {1.0f};
    scene.nodes = {node};
    scene.instances[0].node = 0;
    RendererOptions options;
    if (cpu) options.simulateVertexLimits = VertexLimits{128, 5, 0};  // pos, normal, uv, tangent and one more
    const HdrFrame frame = renderWith(scene, options, plainSettings());
    const int x = kSide / 2 + 5, row = kSide / 2;
    const glm::dvec3 p = viewPointOnPlane(x, row, kSide, kSide, glm::dvec3(0, 0, 1));
    const pbr::SurfaceParameters s{base, 0.0, 1.0};
    const glm::dvec3 turned = glm::normalize(glm::dvec3(-kTilted.y, kTilted.x, kTilted.z));
    const glm::dvec3 unturned = glm::normalize(kTilted);
    const glm::dvec3 expected = expectedColor(p, turned, s, LightingSettings{});
    const glm::dvec3 wrong = expectedColor(p, unturned, s, LightingSettings{});
    const glm::dvec3 got = frame.at(x, row);
    std::printf("%s: gpu (%.4f %.4f %.4f) mirror (%.4f %.4f %.4f); with the rest tangent (%.4f %.4f %.4f)\n",
                cpu ? "CPU-morphed" : "GPU-morphed", got.r, got.g, got.b, expected.r, expected.g, expected.b,
                wrong.r, wrong.g, wrong.b);
    EXPECT_LT(worstRelative(got, expected), 0.01) << (cpu ? "CPU" : "GPU");
    EXPECT_GT(worstRelative(wrong, expected), 0.05);
  }
}

// Skinned normal-mapped quads: a joint turning the quad a quarter about its normal turns the normal texture's tilt
// with it on every skinning path, the CPU's included (whose tangents once stayed at rest); a joint mirroring it
// (scale -1 along x) mirrors the tilt as a mirrored node does (w turned with the blended matrix's determinant).
TEST(Pbr, SkinnedTangentsFollowTheJointsOnEveryPathAndMirror) {
  const glm::dvec3 base(0.8, 0.5, 0.3);
  const pbr::SurfaceParameters s{base, 0.0, 1.0};
  struct Pose {
    const char* name;
    Node joint;
    glm::dvec3 normal;  // the shading normal the tilted texel gives, in view space
  };
  Node turned, mirrored;
  turned.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
  mirrored.scale = glm::vec3(-1.0f, 1.0f, 1.0f);
  const std::vector<Pose> poses = {
      {"turned", turned, glm::normalize(glm::dvec3(-kTilted.y, kTilted.x, kTilted.z))},
      {"mirrored", mirrored, glm::normalize(glm::dvec3(-kTilted.x, kTilted.y, kTilted.z))}};
  for (const Pose& pose : poses)
    for (SkinningPath path : {SkinningPath::Texture, SkinningPath::Uniforms, SkinningPath::Cpu}) {
      Scene scene = normalMappedQuad(base);
      skinToOneJoint(scene, pose.joint);
      scene.meshes[0].material = 0;
      RendererOptions options;
      options.skinning = path;
      const HdrFrame frame = renderWith(scene, options, plainSettings());
      const int x = kSide / 2 + 5, row = kSide / 2;
      const glm::dvec3 p = viewPointOnPlane(x, row, kSide, kSide, glm::dvec3(0, 0, 1));
      const glm::dvec3 expected = expectedColor(p, pose.normal, s, LightingSettings{});
      const glm::dvec3 got = frame.at(x, row);
      std::printf("%s, %s skinning: gpu (%.4f %.4f %.4f) mirror (%.4f %.4f %.4f)\n", pose.name,
                  skinningPathName(path), got.r, got.g, got.b, expected.r, expected.g, expected.b);
      EXPECT_LT(worstRelative(got, expected), 0.01) << pose.name << " " << skinningPathName(path);
    }
}

// KHR_lights_punctual directional lights beside the sun: a quad lit by a file's directional light (the sun off)
// against BRDF x illuminance; with lighting.sun file, the light is the sun (lit once, whatever lighting.sun-* say).
TEST(Pbr, DirectionalLightsFromTheFileAndTheSunThatFollowsThem) {
  const glm::dvec3 base(0.7, 0.6, 0.5);
  Material material;
  material.baseColorFactor = glm::vec4(glm::vec3(base), 1.0f);
  material.roughnessFactor = 0.5f;
  Scene scene = quadScene(material, 8.0f);
  PunctualLight light;
  light.type = LightType::Directional;
  light.color = {1.0f, 0.9f, 0.7f};
  light.intensity = 2.0f;
  // Shining along its -z: turned so it comes from the upper right, towards the quad.
  light.world = glm::rotate(glm::rotate(glm::mat4(1.0f), 0.6f, glm::vec3(0, 1, 0)), -0.4f, glm::vec3(1, 0, 0));
  scene.lights = {light};
  RenderSettings settings = plainSettings();
  settings.of<LightingSettings>().sunIntensity = 0.0f;
  const HdrFrame lit = renderHdr(scene, settings);
  Scene dark = scene;
  dark.lights[0].intensity = 0.0f;
  const HdrFrame unlit = renderHdr(dark, settings);
  const glm::dvec3 l = glm::normalize(glm::dvec3(glm::dmat3(glm::dmat4(light.world)) * glm::dvec3(0, 0, 1)));
  const pbr::SurfaceParameters s{base, 0.0, 0.5};
  double worst = 0.0, peak = 0.0;
  for (int row = 4; row < kSide; row += 8)
    for (int x = 4; x < kSide; x += 8) {
      const glm::dvec3 p = viewPointOnPlane(x, row, kSide, kSide, glm::dvec3(0, 0, 1));
      const glm::dvec3 expected = pbr::brdfCosine(glm::dvec3(0, 0, 1), -glm::normalize(p), l, s) *
                                  glm::dvec3(light.color) * static_cast<double>(light.intensity);
      peak = std::max(peak, expected.r);
      const glm::dvec3 got = lit.at(x, row) - unlit.at(x, row);
      worst = std::max(worst, std::max({std::abs(got.r - expected.r), std::abs(got.g - expected.g),
                                        std::abs(got.b - expected.b)}));
    }
  std::printf("directional light: peak %.3f, worst error %.5f\n", peak, worst / peak);
  EXPECT_GT(peak, 0.2);
  EXPECT_LT(worst / peak, 0.01);

  // lighting.sun file: the same image whatever the renderer's own sun says, and the light counted once.
  RenderSettings followed = plainSettings();
  followed.set("lighting.sun", "file");
  followed.of<LightingSettings>().sunIntensity = 50.0f;
  followed.of<LightingSettings>().sunElevation = 10.0f;
  const HdrFrame asSun = renderHdr(scene, followed);
  double sunDifference = 0.0;
  for (int row = 0; row < kSide; row += 4)
    for (int x = 0; x < kSide; x += 4)
      sunDifference = std::max(sunDifference, worstRelative(asSun.at(x, row), lit.at(x, row)));
  std::printf("lighting.sun file against the light beside a dark sun: worst %.5f\n", sunDifference);
  EXPECT_LT(sunDifference, 0.01);
}
