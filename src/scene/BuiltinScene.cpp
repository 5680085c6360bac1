#include "scene/BuiltinScene.h"

#include <cmath>
#include <string>
#include <utility>

#include <glm/common.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include "scene/MeshDetail.h"
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

// The still room's materials, in the order it adds them (the moving parts' plinth is stone too).
enum MaterialId { kFloor, kWall, kStone, kRed, kBlue, kWood, kGold };

// The still room: everything the AO figures were measured on (BuiltinScene.h). Its meshes, instances and materials
// come first in both variants, in this order; keep it as it is, or re-measure what depends on it.
void addStillRoom(Scene& scene) {
  scene.images.push_back(tileImage());
  scene.textures.push_back(Texture{0, SamplerState{}});

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
}

// What moves (BuiltinSceneOptions::moving): added after the still room, so that its indices stay as they were.

constexpr float kTwoPi = 6.28318530717958648f;

// A periodic swing about a fixed axis over one loop of the animation: the angle is
// amplitude * sin(2 pi * cycles * t / kBuiltinMotionSeconds), 0 at time 0 (the rest pose) and again at the end.
struct Swing {
  glm::vec3 axis;   // unit, in the node's parent's space
  float amplitude;  // radians
  int cycles;       // whole periods per loop
  // Key k of `intervals` + 1 evenly spaced keys: its phase. k % intervals makes the last key's value the first's,
  // bit for bit (sin(2 pi) is not quite 0 in floats), so the loop closes exactly.
  float phase(int k, int intervals) const {
    return kTwoPi * static_cast<float>(cycles) * static_cast<float>(k % intervals) / static_cast<float>(intervals);
  }
  float angle(float phase) const { return amplitude * std::sin(phase); }
  float rate(float phase) const {  // d angle / dt, radians per second
    return amplitude * std::cos(phase) * kTwoPi * static_cast<float>(cycles) / kBuiltinMotionSeconds;
  }
};

float keyTime(int k, int intervals) {
  return kBuiltinMotionSeconds * static_cast<float>(k) / static_cast<float>(intervals);
}

void appendRotation(std::vector<float>& values, const glm::quat& q) {
  values.insert(values.end(), {q.x, q.y, q.z, q.w});  // glTF's order: x, y, z, w
}

// LINEAR rotation keys sampled from the swing at `intervals` + 1 evenly spaced times.
AnimationSampler linearSwing(const Swing& swing, int intervals) {
  AnimationSampler sampler;
  sampler.components = 4;
  sampler.interpolation = Interpolation::Linear;
  for (int k = 0; k <= intervals; ++k) {
    sampler.times.push_back(keyTime(k, intervals));
    appendRotation(sampler.values, glm::angleAxis(swing.angle(swing.phase(k, intervals)), swing.axis));
  }
  return sampler;
}

// CUBICSPLINE rotation keys: each key's quaternion with its exact time derivative as both its in- and out-tangent
// (glTF tangents are per second), so that the Hermite spline follows the sine closely between sparse keys, where
// LINEAR keys would cut its corners.
AnimationSampler cubicSwing(const Swing& swing, int intervals) {
  AnimationSampler sampler;
  sampler.components = 4;
  sampler.interpolation = Interpolation::CubicSpline;
  for (int k = 0; k <= intervals; ++k) {
    const float phase = swing.phase(k, intervals);
    const float half = 0.5f * swing.angle(phase);
    // q(t) = (axis sin(angle / 2), cos(angle / 2)), so dq/dt = (axis cos(angle / 2), -sin(angle / 2)) * rate / 2.
    const float halfRate = 0.5f * swing.rate(phase);
    const glm::quat tangent(-std::sin(half) * halfRate, swing.axis * (std::cos(half) * halfRate));
    sampler.times.push_back(keyTime(k, intervals));
    appendRotation(sampler.values, tangent);  // in-tangent
    appendRotation(sampler.values, glm::angleAxis(2.0f * half, swing.axis));
    appendRotation(sampler.values, tangent);  // out-tangent
  }
  return sampler;
}

void addRotationChannel(Animation& animation, AnimationSampler sampler, int node) {
  animation.channels.push_back({static_cast<int>(animation.samplers.size()), node, AnimationPath::Rotation});
  animation.samplers.push_back(std::move(sampler));
}

int addNode(Scene& scene, const std::string& name, int parent, const glm::vec3& translation) {
  Node node;
  node.name = name;
  node.parent = parent;
  node.translation = translation;
  scene.nodes.push_back(std::move(node));
  return static_cast<int>(scene.nodes.size()) - 1;
}

// A node's world matrix at rest (parents come before their children).
glm::mat4 restWorld(const Scene& scene, int node) {
  const Node& n = scene.nodes[static_cast<size_t>(node)];
  return n.parent < 0 ? n.localRest() : restWorld(scene, n.parent) * n.localRest();
}

int addMaterial(Scene& scene, const glm::vec3& color) {
  Material material;
  material.baseColorFactor = glm::vec4(color, 1.0f);
  scene.materials.push_back(material);
  return static_cast<int>(scene.materials.size()) - 1;
}

int addMesh(Scene& scene, Mesh mesh, int material) {
  mesh.material = material;
  scene.meshes.push_back(std::move(mesh));
  return static_cast<int>(scene.meshes.size()) - 1;
}

Mesh translated(Mesh mesh, const glm::vec3& offset) {
  for (glm::vec3& p : mesh.positions) p += offset;
  return mesh;
}

// A pendulum hung from the arch's crown, swinging in the arch's plane (about z) 15 degrees either way, once per
// loop (LINEAR keys every quarter second): a steel rod on the swinging pivot's node and a bob on the pivot's child,
// 6 cm above the floor at rest, so that the bob's near-contact shadow on the floor and the crease where the rod
// meets the arch move with it. At 15 degrees the bob keeps 0.19 m from the piers.
void addPendulum(Scene& scene, Animation& motion) {
  const glm::vec3 pivotAt(0.0f, 3.5f, -3.6f);  // the arch's intrados at its crown: centre 2.2 m up, radius 1.3 m
  const float bobRadius = 0.3f, bobGap = 0.06f;
  const float length = pivotAt.y - bobGap - bobRadius;  // from the pivot to the bob's centre
  const int steel = addMaterial(scene, {0.45f, 0.46f, 0.48f});
  const int green = addMaterial(scene, {0.25f, 0.60f, 0.35f});

  const int pivot = addNode(scene, "pendulum pivot", -1, pivotAt);
  const int bob = addNode(scene, "pendulum bob", pivot, {0.0f, -length, 0.0f});
  // The rod runs from the bob's centre to 4 cm inside the arch, so that no gap opens at the crown as it swings.
  const int rod = addMesh(scene, translated(makeCylinder(0.025f, length + 0.04f, 16), {0.0f, -length, 0.0f}), steel);
  scene.instances.push_back({rod, restWorld(scene, pivot), pivot, -1});
  const int ball = addMesh(scene, makeSphere(bobRadius, 48, 24), green);
  scene.instances.push_back({ball, restWorld(scene, bob), bob, -1});

  addRotationChannel(motion, linearSwing({{0.0f, 0.0f, 1.0f}, glm::radians(15.0f), 1}, 16), pivot);
}

// A limb bending on a plinth left of the red sphere: a rounded tube skinned to three bones in a chain (root, middle,
// tip), the root fixed to the plinth, the other two bending in the xy plane, which the default camera sees nearly
// side-on: the middle joint 30 degrees either way once per loop (LINEAR keys every quarter second), the tip joint
// 40 degrees either way twice per loop (CUBICSPLINE keys every half second), so the limb curls one way, S-bends,
// curls the other way. The creases: the tube on the plinth, the plinth on the floor, the inside of each bend.
void addLimb(Scene& scene, Animation& motion) {
  const glm::vec3 footAt(-2.2f, 0.0f, 0.6f);  // the plinth's centre on the floor
  const float plinthHeight = 0.14f, radius = 0.15f;
  const float rootLength = 0.5f, middleLength = 0.65f, tipLength = 0.55f;  // the tip's rounded end above that
  // Within `blend` of a joint a vertex passes smoothly from the bone below to the bone above, so that the tube bends
  // in a curve, not a kink (linear blend skinning pinches a kink).
  const float blend = 0.14f;

  const int purple = addMaterial(scene, {0.55f, 0.40f, 0.70f});
  const int plinth = addMesh(scene, makeBox({-0.32f, 0.0f, -0.32f}, {0.32f, plinthHeight, 0.32f}), kStone);
  scene.instances.push_back({plinth, glm::translate(glm::mat4(1.0f), footAt)});

  const glm::vec3 baseAt = footAt + glm::vec3(0.0f, plinthHeight, 0.0f);
  const int root = addNode(scene, "limb root", -1, baseAt);
  const int middle = addNode(scene, "limb middle", root, {0.0f, rootLength, 0.0f});
  const int tip = addNode(scene, "limb tip", middle, {0.0f, middleLength, 0.0f});
  Skin skin;
  skin.name = "limb";
  skin.skeleton = root;
  for (int joint : {root, middle, tip}) {
    skin.joints.push_back(joint);
    // The mesh is modelled in place (bind space is world space at rest), so a vertex times the inverse of its
    // joint's rest world matrix is in that joint's local space, and every joint matrix is the identity at rest.
    skin.inverseBind.push_back(glm::inverse(restWorld(scene, joint)));
  }
  scene.skins.push_back(std::move(skin));

  Mesh tube = makeRoundedTube(radius, rootLength + middleLength + tipLength, 32, 48);
  const float middleJoint = rootLength, tipJoint = rootLength + middleLength;  // heights above the plinth
  for (glm::vec3& p : tube.positions) {
    const float intoMiddle = glm::smoothstep(middleJoint - blend, middleJoint + blend, p.y);
    const float intoTip = glm::smoothstep(tipJoint - blend, tipJoint + blend, p.y);
    // The blends do not overlap (blend < half a bone), so no weight goes negative; they sum to 1.
    tube.joints.emplace_back(0, 1, 2, 0);
    tube.weights.emplace_back(1.0f - intoMiddle, intoMiddle - intoTip, intoTip, 0.0f);
    p += baseAt;
  }
  const int limb = addMesh(scene, std::move(tube), purple);
  scene.instances.push_back({limb, glm::mat4(1.0f), -1, static_cast<int>(scene.skins.size()) - 1});

  addRotationChannel(motion, linearSwing({{0.0f, 0.0f, 1.0f}, glm::radians(30.0f), 1}, 16), middle);
  addRotationChannel(motion, cubicSwing({{0.0f, 0.0f, 1.0f}, glm::radians(40.0f), 2}, 8), tip);
}

}  // namespace

Scene makeBuiltinScene(const BuiltinSceneOptions& options) {
  Scene scene;
  scene.name = "built-in scene";
  // The radius the defaults and the fitted estimator parameters were designed on, kept as this scene's default
  // (scene/SceneScale.h: the rule would give it 5 % of its own size instead).
  scene.designedAoRadius = 1.0f;
  addStillRoom(scene);
  if (options.moving) {
    Animation motion;
    motion.name = kBuiltinMotionName;
    addPendulum(scene, motion);
    addLimb(scene, motion);
    scene.animations.push_back(std::move(motion));
  }
  addDetailLevels(scene);
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
