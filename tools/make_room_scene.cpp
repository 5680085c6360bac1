// obscura-make-room: writes assets/scenes/room-mm.glb, a furnished room modelled in millimetres, for the AO
// accuracy views (tools/tuning-views.json, docs/accuracy.md, docs/test-scenes.md).
//
// Why it exists: issue 12 asks for reference views of an interior with clutter and thin features (chair and table
// legs, railings, pillars), and of a model in millimetres, as CAD and marketplace exports often are. None of the
// glTF files Debian ships is one, so the scene is generated here from boxes, cylinders and spheres
// (scene/Primitives.h) and written as an ordinary binary glTF, which reaches the renderer and the reference tracer
// through the same loader as any user's file. One glTF unit is one millimetre: the room is 6 m x 5 m, 3 m high.
//
// Deterministic: the same bytes on every run. Usage: obscura-make-room OUT.glb
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <tiny_gltf.h>

#include "GltfMeshWriter.h"
#include "scene/Primitives.h"
#include "scene/Scene.h"

using namespace obscura;

namespace {

// --- Dimensions, millimetres ---
constexpr float kRoomX = 6000, kRoomZ = 5000, kRoomHeight = 3000, kWall = 120;
constexpr float kTableTop = 740, kTableX = 1600, kTableZ = 900, kTableLeg = 45, kTableTopThickness = 40;
constexpr float kSeat = 450, kSeatSize = 440, kChairLeg = 28, kBackHeight = 900, kSlat = 30;
constexpr float kPillarRadius = 150, kPlatformHeight = 450, kBaluster = 22, kBalusterGap = 110, kRail = 50;

struct Builder {
  Scene scene;
  int material(glm::vec3 colour) {
    Material m;
    m.baseColorFactor = glm::vec4(colour, 1.0f);
    scene.materials.push_back(m);
    return static_cast<int>(scene.materials.size()) - 1;
  }
  void add(Mesh mesh, int materialId, const glm::mat4& world = glm::mat4(1.0f)) {
    mesh.material = materialId;
    scene.meshes.push_back(std::move(mesh));
    scene.instances.push_back({static_cast<int>(scene.meshes.size()) - 1, world});
  }
  void box(glm::vec3 lo, glm::vec3 hi, int materialId) { add(makeBox(lo, hi), materialId); }
  void cylinder(glm::vec3 base, float radius, float height, int materialId, int slices = 24) {
    add(makeCylinder(radius, height, slices), materialId, glm::translate(glm::mat4(1.0f), base));
  }
  void sphere(glm::vec3 centre, float radius, int materialId) {
    add(makeSphere(radius, 32, 16), materialId, glm::translate(glm::mat4(1.0f), centre));
  }
};

// A chair at `at` (the seat's centre on the floor), facing +z rotated by `turns` quarter turns: four thin legs, a
// seat, two back posts and three slats.
void chair(Builder& b, glm::vec2 at, int quarterTurns, int wood, int seat) {
  const glm::mat4 place = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(at.x, 0, at.y)),
                                      glm::radians(90.0f * static_cast<float>(quarterTurns)), glm::vec3(0, 1, 0));
  auto add = [&](glm::vec3 lo, glm::vec3 hi, int m) { b.add(makeBox(lo, hi), m, place); };
  const float h = kSeatSize / 2, l = kChairLeg;
  for (float x : {-h, h - l})
    for (float z : {-h, h - l}) add({x, 0, z}, {x + l, kSeat - 30, z + l}, wood);
  add({-h, kSeat - 30, -h}, {h, kSeat, h}, seat);
  for (float x : {-h, h - l}) add({x, kSeat, -h}, {x + l, kBackHeight, -h + l}, wood);
  for (int i = 0; i < 3; ++i) {
    const float y = kSeat + 180 + 110 * static_cast<float>(i);
    add({-h + l, y, -h}, {h - l, y + kSlat, -h + 20}, wood);
  }
}

Scene buildRoom() {
  Builder b;
  b.scene.name = "furnished room (millimetres)";
  const int floor = b.material({0.78f, 0.72f, 0.64f});
  const int wall = b.material({0.86f, 0.85f, 0.82f});
  const int wood = b.material({0.55f, 0.38f, 0.24f});
  const int fabric = b.material({0.35f, 0.45f, 0.60f});
  const int metal = b.material({0.40f, 0.40f, 0.42f});
  const int stone = b.material({0.70f, 0.68f, 0.64f});
  const int red = b.material({0.75f, 0.25f, 0.20f});
  const int books[] = {b.material({0.80f, 0.65f, 0.30f}), b.material({0.30f, 0.55f, 0.35f}), red, fabric};

  // Floor and three walls (the side towards +z is open, so cameras see in; no ceiling).
  b.box({0, -60, 0}, {kRoomX, 0, kRoomZ}, floor);
  b.box({-kWall, 0, -kWall}, {kRoomX + kWall, kRoomHeight, 0}, wall);
  b.box({-kWall, 0, 0}, {0, kRoomHeight, kRoomZ}, wall);
  b.box({kRoomX, 0, 0}, {kRoomX + kWall, kRoomHeight, kRoomZ}, wall);
  // Skirting boards: a small step at every wall's foot.
  b.box({0, 0, 0}, {kRoomX, 90, 15}, wall);
  b.box({0, 0, 0}, {15, 90, kRoomZ}, wall);

  // Table on four thin legs, with a vase, a bowl and spheres on it.
  const glm::vec3 table(2600, 0, 2600);
  for (float x : {0.0f, kTableX - kTableLeg})
    for (float z : {0.0f, kTableZ - kTableLeg})
      b.box(table + glm::vec3(x, 0, z), table + glm::vec3(x + kTableLeg, kTableTop - kTableTopThickness, z + kTableLeg),
            wood);
  b.box(table + glm::vec3(-40, kTableTop - kTableTopThickness, -40),
        table + glm::vec3(kTableX + 40, kTableTop, kTableZ + 40), wood);
  b.cylinder(table + glm::vec3(500, kTableTop, 450), 70, 260, stone);
  b.sphere(table + glm::vec3(900, kTableTop + 90, 380), 90, red);
  b.sphere(table + glm::vec3(1080, kTableTop + 55, 560), 55, fabric);
  b.box(table + glm::vec3(1200, kTableTop, 200), table + glm::vec3(1450, kTableTop + 35, 380), books[0]);

  // Four chairs around it, facing it: two on the far side (facing +z), one on the near side (-z), one at the end (-x).
  chair(b, {table.x + 450, table.z - 330}, 0, wood, fabric);
  chair(b, {table.x + 1150, table.z - 330}, 0, wood, fabric);
  chair(b, {table.x + 450, table.z + kTableZ + 330}, 2, wood, fabric);
  chair(b, {table.x + kTableX + 330, table.z + 450}, 3, wood, fabric);

  // Bookshelf against the back wall: sides, five shelves, books and boxes of several sizes (clutter).
  const float shelfX = 300, shelfWidth = 1800, shelfDepth = 320, shelfHeight = 2100;
  b.box({shelfX, 0, 0}, {shelfX + 30, shelfHeight, shelfDepth}, wood);
  b.box({shelfX + shelfWidth - 30, 0, 0}, {shelfX + shelfWidth, shelfHeight, shelfDepth}, wood);
  for (int shelf = 0; shelf < 5; ++shelf) {
    const float y = 80 + 480 * static_cast<float>(shelf);
    b.box({shelfX + 30, y - 25, 0}, {shelfX + shelfWidth - 30, y, shelfDepth}, wood);
    if (shelf == 4) break;
    float x = shelfX + 50;
    for (int i = 0; x < shelfX + shelfWidth - 120; ++i) {
      // A deterministic pattern of widths and heights: books, with a box every fifth.
      const float width = 30.0f + 12.0f * static_cast<float>((i * 7 + shelf * 3) % 5);
      const float height = (i % 5 == 4) ? 180.0f : 220.0f + 25.0f * static_cast<float>((i * 5 + shelf) % 6);
      const float depth = (i % 5 == 4) ? 280.0f : 200.0f + 15.0f * static_cast<float>(i % 4);
      b.box({x, y, 20}, {x + width * ((i % 5 == 4) ? 4.0f : 1.0f), y + height, 20 + depth},
            books[static_cast<size_t>((i + shelf) % 4)]);
      x += width * ((i % 5 == 4) ? 4.0f : 1.0f) + ((i % 9 == 8) ? 90.0f : 4.0f);
    }
  }

  // Two pillars on square plinths.
  for (float x : {1800.0f, 4300.0f}) {
    b.box({x - 230, 0, 1400 - 230}, {x + 230, 120, 1400 + 230}, stone);
    b.cylinder({x, 120, 1400}, kPillarRadius, kRoomHeight - 120, stone, 32);
  }

  // A raised platform in the right corner with three steps and a railing of thin balusters along its front.
  const float platformX = 4500, platformZ = 2600;
  b.box({platformX, 0, 0}, {kRoomX, kPlatformHeight, platformZ}, stone);
  for (int step = 0; step < 3; ++step) {
    const float h = kPlatformHeight * static_cast<float>(step + 1) / 4.0f;
    const float z = platformZ + 280.0f * static_cast<float>(3 - step);
    b.box({platformX + 950, 0, platformZ}, {platformX + 1450, h, z}, stone);
  }
  for (float x = platformX + 30; x < kRoomX - 30; x += kBalusterGap) {
    if (x > platformX + 900 && x < platformX + 1480) continue;  // the opening above the steps
    b.box({x, kPlatformHeight, platformZ - 60}, {x + kBaluster, kPlatformHeight + 900, platformZ - 60 + kBaluster},
          metal);
  }
  b.box({platformX, kPlatformHeight + 900, platformZ - 75},
        {platformX + 910, kPlatformHeight + 900 + kRail, platformZ - 25}, wood);
  b.box({platformX + 1470, kPlatformHeight + 900, platformZ - 75},
        {kRoomX, kPlatformHeight + 900 + kRail, platformZ - 25}, wood);

  // A sofa of blocks along the left wall, and a floor lamp beside it (a thin pole on a disc).
  const float sofaZ = 2800;
  b.box({150, 0, sofaZ}, {1050, 420, sofaZ + 2000}, fabric);
  b.box({150, 420, sofaZ}, {350, 850, sofaZ + 2000}, fabric);
  b.box({350, 420, sofaZ}, {1050, 650, sofaZ + 220}, fabric);
  b.box({350, 420, sofaZ + 1780}, {1050, 650, sofaZ + 2000}, fabric);
  b.box({500, 420, sofaZ + 600}, {900, 560, sofaZ + 1000}, red);  // a cushion
  b.cylinder({1300, 0, sofaZ - 200}, 160, 25, metal);
  b.cylinder({1300, 25, sofaZ - 200}, 14, 1600, metal, 12);
  b.sphere({1300, 1700, sofaZ - 200}, 120, books[0]);
  return b.scene;
}

// --- The room as glTF 2.0: positions, normals, indices and base colours ---
tinygltf::Model toGltf(const Scene& scene) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "obscura-make-room (tools/make_room_scene.cpp); units: millimetres";
  model.buffers.resize(1);
  for (const Material& m : scene.materials) {
    tinygltf::Material material;
    material.pbrMetallicRoughness.baseColorFactor = {m.baseColorFactor.r, m.baseColorFactor.g, m.baseColorFactor.b,
                                                     m.baseColorFactor.a};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.8;
    model.materials.push_back(material);
  }
  tinygltf::Scene root;
  for (const Instance& instance : scene.instances) {
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    root.nodes.push_back(tools::appendMeshNode(model, mesh, mesh.material, instance.world, false));
  }
  model.scenes.push_back(root);
  model.defaultScene = 0;
  return model;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 || std::strcmp(argv[1], "--help") == 0) {
    std::cerr << "usage: obscura-make-room OUT.glb   (writes the furnished room in millimetres; see the source)\n";
    return argc == 2 ? 0 : 2;
  }
  tinygltf::Model model = toGltf(buildRoom());
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&model, argv[1], true, true, false, true)) {
    std::cerr << "obscura-make-room: cannot write " << argv[1] << "\n";
    return 1;
  }
  std::printf("obscura-make-room: wrote %s (%zu meshes)\n", argv[1], model.meshes.size());
  return 0;
}
