// The transparent layer (effects/transparency/TransparencyEffect.h): a half-transparent pane composited over a wall
// in linear light against the analytic blend (unlit, and lit against the lighting's own frames), two overlapping
// panes from both sides, the opaque layer's AO unchanged by a pane in front of it, thin-walled transmission (the
// scene behind shows through, blurred by the roughness), and the unlit material (KHR_materials_unlit).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "TestSupport.h"
#include "effects/dof/DepthOfFieldEffect.h"
#include "encoding/CocPacking.h"
#include "encoding/HdrEncoding.h"
#include "encoding/VelocityPacking.h"
#include "effects/tonemap/TonemapEffect.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

constexpr int kSide = 64;

using test::HdrFrame;

RenderSettings plainSettings() {
  RenderSettings settings;
  settings.set("ao", "off");
  settings.set("fxaa", "off");
  settings.set("lighting.environment", "uniform");
  settings.set("lighting.environment-intensity", "0.5");
  return settings;
}

HdrFrame renderHdr(const Scene& scene, const RenderSettings& settings, const glm::vec3& eye = {0, 0, 5},
                   const RendererOptions& options = {}) {
  Renderer renderer = test::makeRenderer(options);
  renderer.setScene(scene);
  const Camera camera = test::makeCamera(eye, {0, 0, 0}, kSide, kSide, 0.1f, 100.0f, 50.0f);
  test::render(renderer, camera, settings, View::Final, test::retaining({"scene-color"}));
  return {kSide, kSide, renderer.retained("scene-color").readRgba()};
}

int addUnlit(Scene& scene, const glm::vec4& color, AlphaMode mode, bool doubleSided = true) {
  Material m;
  m.baseColorFactor = color;
  m.unlit = true;
  m.alphaMode = mode;
  m.doubleSided = doubleSided;
  scene.materials.push_back(m);
  return static_cast<int>(scene.materials.size()) - 1;
}

// A square facing +z at depth z, `half` wide each side of the axis, in material `material`.
void addPane(Scene& scene, float z, float half, int material) {
  Mesh pane = test::makeRectangle({-half, -half, z}, {2 * half, 0, 0}, {0, 2 * half, 0});
  pane.material = material;
  scene.meshes.push_back(pane);
  Instance instance;
  instance.mesh = static_cast<int>(scene.meshes.size()) - 1;
  scene.instances.push_back(instance);
}

double worstDifference(const glm::dvec3& a, const glm::dvec3& b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

}  // namespace

// A 50 % red pane over a grey wall: in linear light the frame is 0.5 red + 0.5 grey, within 2/255. Unlit, the
// analytic blend is known exactly; lit, it is the blend of the lighting's own frames of the wall alone and of the
// pane drawn opaque (the pane is lit as the opaque layer is).
TEST(Transparency, AHalfRedPaneOverAGreyWallIsTheAnalyticBlend) {
  for (bool lit : {false, true}) {
    auto wallAndPane = [&](AlphaMode paneMode, float paneAlpha, bool withPane) {
      Scene scene;
      Material wall;
      wall.baseColorFactor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
      wall.unlit = !lit;
      scene.materials.push_back(wall);
      addPane(scene, -1.0f, 3.0f, 0);
      if (withPane) {
        Material pane;
        pane.baseColorFactor = glm::vec4(1.0f, 0.0f, 0.0f, paneAlpha);
        pane.unlit = !lit;
        pane.alphaMode = paneMode;
        pane.doubleSided = true;
        scene.materials.push_back(pane);
        addPane(scene, 0.5f, 1.0f, 1);
      }
      return scene;
    };
    const RenderSettings settings = plainSettings();
    const HdrFrame blended = renderHdr(wallAndPane(AlphaMode::Blend, 0.5f, true), settings);
    const HdrFrame wallAlone = renderHdr(wallAndPane(AlphaMode::Opaque, 1.0f, false), settings);
    const HdrFrame paneOpaque = renderHdr(wallAndPane(AlphaMode::Opaque, 1.0f, true), settings);
    double worst = 0.0;
    int covered = 0;
    for (int row = 24; row < 40; ++row)
      for (int x = 24; x < 40; ++x) {
        const glm::dvec3 expected = lit ? 0.5 * paneOpaque.at(x, row) + 0.5 * wallAlone.at(x, row)
                                        : glm::dvec3(0.5 * 1.0 + 0.5 * 0.5, 0.5 * 0.5, 0.5 * 0.5);
        worst = std::max(worst, worstDifference(blended.at(x, row), expected));
        ++covered;
      }
    std::printf("%s pane over a wall: worst |frame - analytic blend| %.5f (linear) over %d pixels\n",
                lit ? "lit" : "unlit", worst, covered);
    EXPECT_LT(worst, 2.0 / 255.0) << (lit ? "lit" : "unlit");
    // Outside the pane the wall is the wall's (to the last step of the HDR encoding: another frame, another plan).
    EXPECT_LT(worstDifference(blended.at(4, 4), wallAlone.at(4, 4)), 2.0 / 255.0);
  }
}

// Two overlapping half-transparent panes (red at z = 0, blue at z = 1, both double-sided) over the background, seen
// from the front and from behind: each side sees its nearer pane over the farther one.
TEST(Transparency, TwoOverlappingPanesAreOrderedFromBothSides) {
  Scene scene;
  const int red = addUnlit(scene, {1, 0, 0, 0.5f}, AlphaMode::Blend);
  const int blue = addUnlit(scene, {0, 0, 1, 0.5f}, AlphaMode::Blend);
  addPane(scene, 0.0f, 1.0f, red);
  addPane(scene, 1.0f, 1.0f, blue);
  RenderSettings settings = plainSettings();
  const double background = 0.5;  // the uniform environment's radiance times its intensity
  const glm::dvec3 b(background), r(1, 0, 0), u(0, 0, 1);
  const glm::dvec3 fromFront = 0.5 * u + 0.5 * (0.5 * r + 0.5 * b);
  const glm::dvec3 fromBehind = 0.5 * r + 0.5 * (0.5 * u + 0.5 * b);
  const HdrFrame front = renderHdr(scene, settings, {0, 0, 6});
  const HdrFrame behind = renderHdr(scene, settings, {0, 0, -6});
  const int middle = kSide / 2;
  const glm::dvec3 f = front.at(middle, middle), k = behind.at(middle, middle);
  std::printf("front (%.4f %.4f %.4f) expected (%.4f %.4f %.4f); behind (%.4f %.4f %.4f) expected (%.4f %.4f %.4f)\n",
              f.r, f.g, f.b, fromFront.r, fromFront.g, fromFront.b, k.r, k.g, k.b, fromBehind.r, fromBehind.g,
              fromBehind.b);
  EXPECT_LT(worstDifference(f, fromFront), 2.0 / 255.0);
  EXPECT_LT(worstDifference(k, fromBehind), 2.0 / 255.0);
  // The two orders differ by far more than the tolerance: a wrong order fails.
  EXPECT_GT(worstDifference(fromFront, fromBehind), 0.2);
}

// The pane is not in the G-buffer: the AO of the opaque layer (a wall and a box on it) is the same with and without
// a pane in front of them, within 1/255.
TEST(Transparency, TheOpaqueAoUnderThePaneIsUnchanged) {
  auto scene = [](bool withPane) {
    Scene s = test::sceneOf({test::makeRectangle({-4, 0, 4}, {8, 0, 0}, {0, 0, -8}),  // floor, +y
                             test::makeRectangle({-4, 0, -1}, {8, 0, 0}, {0, 3, 0}),  // wall, +z
                             makeBox({-0.6f, 0.0f, -0.8f}, {0.4f, 0.8f, 0.2f})});
    s.designedAoRadius = 1.0f;
    const int grey = test::addMaterial(s, glm::vec3(0.7f));
    for (Mesh& mesh : s.meshes) mesh.material = grey;
    if (withPane) addPane(s, 1.0f, 1.0f, addUnlit(s, {0.2f, 0.6f, 1.0f, 0.4f}, AlphaMode::Blend));
    return s;
  };
  RenderSettings settings = plainSettings();
  settings.set("ao", "on");
  const Camera camera = test::makeCamera({1.5f, 1.6f, 3.0f}, {-0.2f, 0.3f, -0.5f}, kSide, kSide, 0.1f, 30.0f);
  auto aoOf = [&](bool withPane) {
    Renderer renderer = test::makeRenderer();
    renderer.setScene(scene(withPane));
    test::render(renderer, camera, settings, View::Final, test::retaining({"ao"}));
    return renderer.retained("ao").readRgba();
  };
  const std::vector<std::uint8_t> without = aoOf(false), with = aoOf(true);
  int worst = 0;
  double darkest = 1.0;
  for (size_t i = 0; i < without.size(); i += 4) {
    worst = std::max(worst, std::abs(int(without[i]) - int(with[i])));
    darkest = std::min(darkest, without[i] / 255.0);
  }
  std::printf("AO under the pane: worst difference %d/255 (the box darkens its surroundings to %.3f)\n", worst,
              darkest);
  EXPECT_LE(worst, 1);
  EXPECT_LT(darkest, 0.8);  // the AO has something to show
}

// KHR_materials_transmission, thin-walled: a clear (roughness 0) white pane of transmission 1 in front of a striped
// wall shows the stripes through it at nearly their contrast, a rough one (0.6) blurs them; both let through about
// the wall's mean light.
TEST(Transparency, TransmissionShowsTheSceneBehindBlurredByTheRoughness) {
  auto scene = [](float roughness) {
    Scene s;
    // Stripes 4 pixels wide on the wall (a 2 x 1 nearest texture repeated), unlit so that they are exact.
    Image image;
    image.width = 2;
    image.height = 1;
    image.rgba = {255, 255, 255, 255, 0, 0, 0, 255};
    s.images.push_back(image);
    s.textures.push_back({0, {0x2600, 0x2600, 0x2901, 0x2901}});
    Material wall;
    wall.unlit = true;
    wall.baseColorTexture = 0;
    s.materials.push_back(wall);
    Mesh w = test::makeRectangle({-3, -3, -1}, {6, 0, 0}, {0, 6, 0});
    for (glm::vec2& uv : w.texcoords) uv *= glm::vec2(12.0f, 1.0f);
    w.material = 0;
    s.meshes.push_back(w);
    s.instances.push_back({0, glm::mat4(1.0f), -1, -1});
    Material glass;
    glass.metallicFactor = 0.0f;
    glass.roughnessFactor = roughness;
    glass.transmissionFactor = 1.0f;
    glass.doubleSided = true;
    s.materials.push_back(glass);
    addPane(s, 0.5f, 1.5f, 1);
    return s;
  };
  RenderSettings settings = plainSettings();
  settings.set("lighting.sun-intensity", "0");
  settings.set("lighting.environment-intensity", "0.05");
  auto stats = [&](float roughness) {
    const HdrFrame frame = renderHdr(scene(roughness), settings);
    double low = 1e9, high = -1e9, sum = 0.0;
    int n = 0;
    for (int x = 24; x < 40; ++x) {
      const double v = frame.at(x, kSide / 2).g;
      low = std::min(low, v);
      high = std::max(high, v);
      sum += v;
      ++n;
    }
    return std::make_tuple(low, high, sum / n);
  };
  const auto [sharpLow, sharpHigh, sharpMean] = stats(0.0f);
  const auto [roughLow, roughHigh, roughMean] = stats(0.6f);
  std::printf("through clear glass: %.3f .. %.3f (mean %.3f); through rough glass: %.3f .. %.3f (mean %.3f)\n",
              sharpLow, sharpHigh, sharpMean, roughLow, roughHigh, roughMean);
  EXPECT_GT(sharpHigh - sharpLow, 0.8);                        // the stripes show through clear glass
  EXPECT_LT(roughHigh - roughLow, 0.5 * (sharpHigh - sharpLow));  // and blur through rough glass
  EXPECT_NEAR(roughMean, sharpMean, 0.15);
}

// Through an orthographic camera every eye ray is parallel, so a flat clear pane facing the camera transmits the same
// share of the wall behind it at the image's centre and at its corner. The transmission's Fresnel term takes the eye
// ray's direction (lib/reconstruct.glsl's eyeRayDirection), not the direction from the eye's point: with the latter,
// the corner, seen at 76 degrees from that point, would transmit about a quarter less.
TEST(Transparency, TransmissionThroughAnOrthographicCameraIsTheSameAcrossAFlatPane) {
  Scene scene;
  scene.materials.push_back({});
  scene.materials[0].unlit = true;
  scene.materials[0].baseColorFactor = glm::vec4(1.0f);
  Mesh wall = test::makeRectangle({-3, -3, -1}, {6, 0, 0}, {0, 6, 0});
  wall.material = 0;
  scene.meshes.push_back(wall);
  scene.instances.push_back({0, glm::mat4(1.0f), -1, -1});
  Material glass;
  glass.metallicFactor = 0.0f;
  glass.roughnessFactor = 0.0f;
  glass.transmissionFactor = 1.0f;
  glass.doubleSided = true;
  scene.materials.push_back(glass);
  addPane(scene, 0.5f, 2.0f, 1);
  RenderSettings settings = plainSettings();
  settings.set("lighting.sun-intensity", "0");
  settings.set("lighting.environment-intensity", "0");
  Renderer renderer = test::makeRenderer();
  renderer.setScene(scene);
  Camera camera = test::makeCamera({0, 0, 1}, {0, 0, 0}, kSide, kSide, 0.1f, 100.0f, 50.0f);
  camera.orthographic = true;
  camera.ymag = 1.4f;  // the corner pixel's point lies 1.9 m off the axis, 0.5 m in front of the eye's plane
  test::render(renderer, camera, settings, View::Final, test::retaining({"scene-color"}));
  const HdrFrame frame{kSide, kSide, renderer.retained("scene-color").readRgba()};
  const double centre = frame.at(kSide / 2, kSide / 2).g, corner = frame.at(1, 1).g;
  std::printf("transmitted through the pane: %.4f at the centre, %.4f at the corner\n", centre, corner);
  EXPECT_GT(centre, 0.5);
  EXPECT_NEAR(corner, centre, 0.02 * centre);
}

// KHR_materials_unlit: a cube's faces, however they face the sun and the sky, show its base colour through the tone
// curve alone, one colour within 1/255 (display); with COLOR_0, the base colour times the vertex colour.
TEST(Unlit, AnUnlitCubesFacesShowOneColour) {
  for (bool vertexColors : {false, true}) {
    Scene scene;
    Material m;
    m.baseColorFactor = glm::vec4(0.8f, 0.4f, 0.2f, 1.0f);
    m.unlit = true;
    scene.materials.push_back(m);
    Mesh cube = makeBox({-1, -1, -1}, {1, 1, 1});
    if (vertexColors) cube.colors.assign(cube.positions.size(), glm::vec4(0.5f, 1.0f, 1.0f, 1.0f));
    cube.material = 0;
    scene.meshes.push_back(cube);
    scene.instances.push_back({0, glm::mat4(1.0f), -1, -1});
    RenderSettings settings;
    settings.set("fxaa", "off");
    settings.set("dither", "off");  // one colour: dithering would spread it over a step each side
    const Camera camera = test::makeCamera({3, 2.5f, 4}, {0, 0, 0}, kSide, kSide, 0.1f, 100.0f, 50.0f);
    Renderer renderer = test::makeRenderer();
    renderer.setScene(scene);
    const test::RenderedImage image = test::render(renderer, camera, settings, View::Final);
    // The cube's pixels: those its mask view covers (three faces are seen, each lit very differently were it lit).
    const test::RenderedImage mask = test::render(renderer, camera, settings, View::Mask);
    int low[3] = {255, 255, 255}, high[3] = {0, 0, 0}, covered = 0;
    glm::ivec2 any(0);
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        if (mask.channel(x, y, 0) < 128) continue;
        ++covered;
        any = {x, y};
        for (int c = 0; c < 3; ++c) {
          low[c] = std::min(low[c], int(image.channel(x, y, c)));
          high[c] = std::max(high[c], int(image.channel(x, y, c)));
        }
      }
    int spread = 0;
    for (int c = 0; c < 3; ++c) spread = std::max(spread, high[c] - low[c]);
    ASSERT_GT(covered, kSide * kSide / 8);
    const glm::vec3 linear = glm::vec3(m.baseColorFactor) * (vertexColors ? glm::vec3(0.5f, 1, 1) : glm::vec3(1));
    const ToneMapInUse tone = ToneMapInUse::of(settings.of<TonemapSettings>());
    const glm::vec4 display = tone.displayColor(linear, false);
    std::printf("unlit cube%s: %d pixels spread %d/255; (%d %d %d) against the tone-mapped base colour "
                "(%.1f %.1f %.1f)\n",
                vertexColors ? " with vertex colours" : "", covered, spread, image.channel(any.x, any.y, 0),
                image.channel(any.x, any.y, 1), image.channel(any.x, any.y, 2), display.r * 255, display.g * 255,
                display.b * 255);
    EXPECT_LE(spread, 1);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.channel(any.x, any.y, c), display[c] * 255.0f, 1.5f) << c;
  }
}

// The transparent layer's passes run where the scene has one (transmission-levels only with transmission), after
// the fog and before TAA, bloom and the tone mapping; the lighting then cannot apply the tone curve itself (the pass
// reads its HDR colour). `transparency off` leaves the layer out.
TEST(Transparency, ItsPassesRunOnlyForATransparentLayer) {
  auto passes = [](const Scene& scene, bool on) {
    Renderer renderer = test::makeRenderer();
    renderer.setScene(scene);
    RenderSettings settings;
    settings.set("fog", "on");
    settings.set("transparency", on ? "on" : "off");
    const Camera camera = test::makeCamera({0, 0, 5}, {0, 0, 0}, kSide, kSide, 0.1f, 100.0f, 50.0f);
    test::render(renderer, camera, settings, View::Final);
    // The passes in the order they run, each followed by the per-pixel stages fused into it (fog into the lighting).
    std::vector<std::string> out;
    for (const PlannedPass& p : renderer.lastPlan().passes()) {
      if (!p.live) continue;
      out.push_back(p.decl.name);
      out.insert(out.end(), p.absorbed.begin(), p.absorbed.end());
    }
    return out;
  };
  auto has = [](const std::vector<std::string>& list, const char* name) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  auto index = [](const std::vector<std::string>& list, const char* name) {
    return std::find(list.begin(), list.end(), name) - list.begin();
  };
  Scene opaque;
  addPane(opaque, 0.0f, 1.0f, test::addMaterial(opaque, glm::vec3(0.5f)));
  EXPECT_FALSE(has(passes(opaque, true), "transparency"));

  Scene blended = opaque;
  addPane(blended, 0.5f, 0.5f, addUnlit(blended, {1, 0, 0, 0.5f}, AlphaMode::Blend));
  const std::vector<std::string> withLayer = passes(blended, true);
  EXPECT_TRUE(has(withLayer, "transparency"));
  EXPECT_FALSE(has(withLayer, "transmission-levels"));
  EXPECT_LT(index(withLayer, "fog"), index(withLayer, "transparency"));
  EXPECT_LT(index(withLayer, "transparency"), index(withLayer, "tonemap"));
  EXPECT_FALSE(has(passes(blended, false), "transparency"));

  Scene glass = opaque;
  Material m;
  m.transmissionFactor = 1.0f;
  glass.materials.push_back(m);
  addPane(glass, 0.5f, 0.5f, static_cast<int>(glass.materials.size()) - 1);
  const std::vector<std::string> withGlass = passes(glass, true);
  EXPECT_TRUE(has(withGlass, "transmission-levels"));
  EXPECT_LT(index(withGlass, "transmission-levels"), index(withGlass, "transparency"));
}

// The G-buffer effects see the opaque layer through a pane (docs/transparency.md, their behaviour measured): a pane
// 2 m from the camera before a wall at 5 m. Depth of field focused on the pane blurs it with the wall's circle of
// confusion instead of none; a sideways camera step gives the pane's pixels the wall's motion (what motion blur
// smears and TAA reprojects them by) instead of its own.
TEST(Transparency, TheGBufferEffectsSeeTheOpaqueLayerBehindAPane) {
  Scene scene;
  addPane(scene, -3.0f, 6.0f, test::addMaterial(scene, glm::vec3(0.6f)));
  addPane(scene, 0.0f, 0.6f, addUnlit(scene, {0.2f, 0.5f, 0.9f, 0.4f}, AlphaMode::Blend));
  const int middle = kSide / 2;
  // Depth of field, focused on the pane.
  {
    Renderer renderer = test::makeRenderer();
    renderer.setScene(scene);
    RenderSettings settings;
    settings.set("dof", "on");
    settings.set("dof.focus", "2");
    settings.set("dof.fstop", "1.4");
    const Camera camera = test::makeCamera({0, 0, 2}, {0, 0, 0}, kSide, kSide, 0.1f, 100.0f, 50.0f);
    test::render(renderer, camera, settings, View::Final, test::retaining({"dof-coc"}));
    const float range = 2.0f * settings.of<DofSettings>().maxRadiusPixels(kSide);
    const std::vector<std::uint8_t> bytes = renderer.retained("dof-coc").readRgba();
    const float atPane = CocPacking::cocFromBytes(&bytes[(static_cast<size_t>(middle) * kSide + middle) * 4], range);
    const ThinLens lens = ThinLens::of(settings.of<DofSettings>(), kSide);
    const float wall = lens.coc(5.0f, 2.0f), pane = lens.coc(2.0f, 2.0f);
    std::printf("depth of field on the pane: CoC %.2f px (the wall's %.2f px; the pane's own %.2f px)\n", atPane, wall,
                pane);
    EXPECT_NEAR(atPane, wall, 0.05f * std::abs(wall) + 0.1f);
    EXPECT_GT(std::abs(wall - pane), 1.0f);
  }
  // Motion: the camera steps 5 cm to the right between two frames.
  {
    Renderer renderer = test::makeRenderer();
    renderer.setScene(scene);
    RenderSettings settings;
    settings.set("motion-blur", "on");
    const Camera before = test::makeCamera({0, 0, 2}, {0, 0, 0}, kSide, kSide, 0.1f, 100.0f, 50.0f);
    const Camera after = test::makeCamera({0.05f, 0, 2}, {0.05f, 0, 0}, kSide, kSide, 0.1f, 100.0f, 50.0f);
    test::render(renderer, before, settings, View::Final);
    test::render(renderer, after, settings, View::Final, test::retaining({"velocity"}));
    const std::vector<std::uint8_t> bytes = renderer.retained("velocity").readRgba();
    const glm::vec2 atPane = VelocityPacking::velocityFromBytes(&bytes[(static_cast<size_t>(middle) * kSide + middle) * 4]);
    // A point straight ahead at depth d moved by -0.05 m sideways in view: its uv moves by -0.05 / (2 d tan(25°)).
    const float halfWidth = std::tan(glm::radians(25.0f));
    const float wall = -0.05f / (2.0f * 5.0f * halfWidth), pane = -0.05f / (2.0f * 2.0f * halfWidth);
    std::printf("motion on the pane: %.5f of the width per frame, %.2f px (the wall's %.2f px; the pane's own %.2f "
                "px)\n",
                atPane.x, atPane.x * kSide, wall * kSide, pane * kSide);
    EXPECT_NEAR(atPane.x, wall, 0.05f * std::abs(wall));
    EXPECT_GT(std::abs(wall - pane) * kSide, 0.3f);
  }
}
