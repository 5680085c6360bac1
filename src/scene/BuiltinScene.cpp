#include "scene/BuiltinScene.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/Primitives.h"

namespace obscura {
namespace {

// A 256x256 tile texture: soft grey tiles with darker grout, power of two so it may repeat under WebGL 1.
Image tileImage() {
  Image image;
  image.width = image.height = 256;
  image.rgba.resize(256 * 256 * 4);
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) {
      const bool grout = (x % 128) < 4 || (y % 128) < 4;
      const bool alternate = ((x / 128) + (y / 128)) % 2 == 0;
      const auto value = static_cast<std::uint8_t>(grout ? 150 : (alternate ? 235 : 222));
      std::uint8_t* p = &image.rgba[static_cast<size_t>(y * 256 + x) * 4];
      p[0] = value;
      p[1] = value;
      p[2] = static_cast<std::uint8_t>(value - (grout ? 0 : 6));
      p[3] = 255;
    }
  }
  return image;
}

}  // namespace

Scene makeBuiltinScene() {
  Scene scene;
  scene.name = "built-in scene";
  // The radius the defaults and the fitted estimator parameters were designed on, kept as this scene's default
  // (scene/SceneScale.h: the rule would give it 5 % of its own size instead).
  scene.designedAoRadius = 1.0f;
  scene.images.push_back(tileImage());
  scene.textures.push_back(Texture{0, SamplerState{}});

  enum MaterialId { kFloor, kWall, kStone, kRed, kBlue, kWood, kGold };
  auto material = [&](glm::vec3 color, int texture = -1) {
    Material m;
    m.baseColorFactor = glm::vec4(color, 1.0f);
    m.baseColorTexture = texture;
    scene.materials.push_back(m);
  };
  material({1.0f, 1.0f, 1.0f}, 0);     // floor: tiles
  material({0.82f, 0.80f, 0.76f});     // walls
  material({0.70f, 0.68f, 0.64f});     // stone columns, arch, stairs
  material({0.80f, 0.22f, 0.18f});     // red sphere
  material({0.20f, 0.35f, 0.80f});     // blue sphere
  material({0.72f, 0.52f, 0.32f});     // wooden boxes
  material({0.90f, 0.72f, 0.25f});     // small gold sphere

  auto add = [&](Mesh mesh, int materialId, const glm::mat4& world = glm::mat4(1.0f)) {
    mesh.material = materialId;
    scene.meshes.push_back(std::move(mesh));
    scene.instances.push_back({static_cast<int>(scene.meshes.size()) - 1, world});
    return static_cast<int>(scene.meshes.size()) - 1;
  };
  auto instance = [&](int mesh, const glm::mat4& world) { scene.instances.push_back({mesh, world}); };
  const auto at = [](float x, float y, float z) { return glm::translate(glm::mat4(1.0f), glm::vec3(x, y, z)); };

  // Room: a 12 m x 10 m floor (top at y = 0), a back wall and a left wall, 4 m high, 0.2 m thick.
  add(makeBox({-6.0f, -0.2f, -5.0f}, {6.0f, 0.0f, 5.0f}, 0.5f), kFloor);
  add(makeBox({-6.0f, 0.0f, -5.2f}, {6.0f, 4.0f, -5.0f}), kWall);
  add(makeBox({-6.2f, 0.0f, -5.2f}, {-6.0f, 4.0f, 5.0f}), kWall);
  // A skirting ledge along the back wall: a small step that SAO should darken at both creases.
  add(makeBox({-6.0f, 0.0f, -5.0f}, {6.0f, 0.15f, -4.85f}), kStone);

  // Columns along the left wall, with square plinths (contact creases at two heights).
  const int column = add(makeCylinder(0.28f, 3.4f, 40), kStone, at(-4.6f, 0.25f, -3.0f));
  const int plinth = add(makeBox({-0.45f, 0.0f, -0.45f}, {0.45f, 0.25f, 0.45f}), kStone, at(-4.6f, 0.0f, -3.0f));
  for (float z : {-0.5f, 2.0f}) {
    instance(column, at(-4.6f, 0.25f, z));
    instance(plinth, at(-4.6f, 0.0f, z));
  }

  // An arch on two piers in front of the back wall.
  const int pier = add(makeBox({-0.3f, 0.0f, -0.3f}, {0.3f, 2.2f, 0.3f}), kStone, at(-1.6f, 0.0f, -3.6f));
  instance(pier, at(1.6f, 0.0f, -3.6f));
  add(makeArchRing(1.3f, 1.9f, 0.6f, 32), kStone, at(0.0f, 2.2f, -3.6f));

  // Stairs against the right side: six steps of 0.2 m rise and 0.35 m run, up to a landing at the back wall.
  for (int step = 0; step < 6; ++step) {
    const float h = 0.2f * static_cast<float>(step + 1);
    const float zFront = -1.0f - 0.35f * static_cast<float>(step);
    add(makeBox({3.4f, 0.0f, -5.0f}, {5.2f, h, zFront}), kStone);
  }

  // Spheres resting on the floor: each touches y = 0 at one point (contact shadows).
  add(makeSphere(0.6f, 64, 32), kRed, at(0.2f, 0.6f, 0.4f));
  add(makeSphere(0.35f, 48, 24), kBlue, at(1.5f, 0.35f, 1.4f));
  add(makeSphere(0.18f, 32, 16), kGold, at(-0.9f, 0.18f, 1.6f));
  // A sphere tucked into the corner between the wall and the floor.
  add(makeSphere(0.5f, 48, 24), kBlue, at(-5.5f, 0.5f, 3.8f));

  // Stacked boxes: each rests on the one below, turned a little, creating creases and overhangs.
  add(makeBox({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}), kWood, at(2.4f, 0.0f, -1.2f));
  add(makeBox({-0.35f, 0.0f, -0.35f}, {0.35f, 0.7f, 0.35f}), kWood,
      at(2.35f, 1.0f, -1.15f) * glm::rotate(glm::mat4(1.0f), glm::radians(25.0f), glm::vec3(0, 1, 0)));
  add(makeBox({-0.2f, 0.0f, -0.2f}, {0.2f, 0.4f, 0.2f}), kWood,
      at(2.4f, 1.7f, -1.2f) * glm::rotate(glm::mat4(1.0f), glm::radians(-15.0f), glm::vec3(0, 1, 0)));
  // A low box pushed against the back wall and one lying beside the stack.
  add(makeBox({-0.6f, 0.0f, -0.3f}, {0.6f, 0.5f, 0.3f}), kWood, at(-3.0f, 0.0f, -4.7f));
  add(makeBox({-0.4f, 0.0f, -0.25f}, {0.4f, 0.3f, 0.25f}), kWood,
      at(1.4f, 0.0f, -0.9f) * glm::rotate(glm::mat4(1.0f), glm::radians(40.0f), glm::vec3(0, 1, 0)));
  return scene;
}

Camera builtinSceneCamera(int width, int height) {
  Camera camera;
  camera.eye = glm::vec3(3.2f, 2.6f, 6.2f);
  camera.target = glm::vec3(-0.4f, 0.8f, -1.6f);
  camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
  camera.fovyDegrees = 55.0f;
  camera.near = 0.1f;
  camera.far = 40.0f;
  camera.width = width;
  camera.height = height;
  return camera;
}

}  // namespace obscura
