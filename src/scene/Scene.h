#pragma once
// A scene as the renderer consumes it: triangle meshes in local space, instances placing them in the world (in the
// scene's own units: metres for the built-in scene, whatever a glTF file was authored in; right-handed, +y up),
// materials and RGBA8 images. Built by the glTF loader or by the built-in scene generator; holds no GL objects
// (GpuScene uploads it).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_precision.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace obscura {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4, rows top to bottom
};

// glTF sampler state, as GL enums.
struct SamplerState {
  int magFilter = 0x2601;  // GL_LINEAR
  int minFilter = 0x2703;  // GL_LINEAR_MIPMAP_LINEAR
  int wrapS = 0x2901;      // GL_REPEAT
  int wrapT = 0x2901;
};

struct Texture {
  int image = -1;
  SamplerState sampler;
};

enum class AlphaMode { Opaque, Mask, Blend };

// The texture slots of a glTF 2.0 metallic-roughness material, in the order of Material::uvTransforms.
enum class TextureSlot { BaseColor = 0, MetallicRoughness = 1, Normal = 2, Occlusion = 3, Emissive = 4 };
inline constexpr int kTextureSlots = 5;

// glTF 2.0 metallic-roughness (effects/lighting/LightingEffect.h shades it). A Material made in code is a rough
// dielectric (metallic 0, roughness 1): what every scene made in code (the built-in scene, the tests) was drawn as
// before the material model; the glTF loader sets the file's values, whose defaults are glTF's (metallic 1, roughness
// 1).
struct Material {
  glm::vec4 baseColorFactor{1.0f};
  int baseColorTexture = -1;  // index into Scene::textures
  float metallicFactor = 0.0f;
  float roughnessFactor = 1.0f;
  int metallicRoughnessTexture = -1;  // B metallic, G roughness (linear)
  int normalTexture = -1;             // tangent-space normal (linear), needs tangents (Mesh::tangents)
  float normalScale = 1.0f;
  int occlusionTexture = -1;          // R the baked ambient occlusion (linear)
  float occlusionStrength = 1.0f;
  glm::vec3 emissiveFactor{0.0f};
  int emissiveTexture = -1;           // sRGB
  float emissiveStrength = 1.0f;      // KHR_materials_emissive_strength
    // KHR_texture_transform per slot (TextureSlot order), uv' = T uv, applied in the vertex stage. The loader bakes a
  // material's base-colour transform into the mesh's TEXCOORD_0 instead where the material has no other texture.
  std::array<glm::mat3, kTextureSlots> uvTransforms{glm::mat3(1.0f), glm::mat3(1.0f), glm::mat3(1.0f),
                                                     glm::mat3(1.0f), glm::mat3(1.0f)};
  // The texture coordinate set each slot samples (TextureSlot order): 0 TEXCOORD_0, 1 TEXCOORD_1 (Mesh::texcoords1).
  std::array<int, kTextureSlots> texCoords{0, 0, 0, 0, 0};
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;

  // KHR_materials_unlit: the base colour (times the vertex colour) is the colour seen; no light, no AO.
  bool unlit = false;
  // KHR_materials_ior, KHR_materials_specular: the dielectric's Fresnel at normal incidence is
  // min(((ior - 1) / (ior + 1))^2 specularColor, 1) specular, at grazing incidence specular (effects/lighting/
  // PbrShading.h: SurfaceParameters). glTF's defaults give 0.04 and 1, the core material's.
  float ior = 1.5f;
  float specularFactor = 1.0f;
  glm::vec3 specularColorFactor{1.0f};
  // KHR_materials_clearcoat: a second, dielectric (ior 1.5) GGX layer on top, of this strength and roughness, over
  // the base's normal (clearcoatNormalTexture is not read).
  float clearcoatFactor = 0.0f;
  float clearcoatRoughnessFactor = 0.0f;
  // KHR_materials_transmission (thin-walled: KHR_materials_volume is not applied): the fraction of the light not
  // reflected that passes through the surface, tinted by the base colour (effects/transparency).
  float transmissionFactor = 0.0f;

  // Textures besides the base colour (the PBR_TEXTURES shader variant: gpu/MaterialKind.h).
  bool hasPbrTextures() const {
    return metallicRoughnessTexture >= 0 || normalTexture >= 0 || occlusionTexture >= 0 || emissiveTexture >= 0;
  }
  // The dielectric Fresnel terms differ from the core material's, or a clear coat lies on top (the MATERIAL_LAYERS
  // shader variant).
  bool layered() const {
    return clearcoatFactor > 0.0f || ior != 1.5f || specularFactor != 1.0f || specularColorFactor != glm::vec3(1.0f);
  }
  // The dielectric's Fresnel at normal incidence: min(((ior - 1) / (ior + 1))^2 specularColor, 1) specular.
  glm::vec3 dielectricF0() const;
  // Drawn after the opaque frame, composited over it (effects/transparency): alphaMode BLEND, or transmission.
  bool transparent() const { return alphaMode == AlphaMode::Blend || transmissionFactor > 0.0f; }

  // Anything the deferred lighting's base-colour target cannot carry (effects/lighting/LightingEffect.h): the scene is
  // then lit by the forward form.
  bool needsForwardLighting() const {
    return hasPbrTextures() || metallicFactor != 0.0f || roughnessFactor != 1.0f ||
           emissiveFactor != glm::vec3(0.0f) || unlit || layered();
  }
};

// KHR_lights_punctual: a point, spot or directional light placed by a node (position: its origin; direction: its -z).
// A directional light's intensity is illuminance (lux), the others' luminous intensity (candela).
enum class LightType { Point, Spot, Directional };
struct PunctualLight {
  LightType type = LightType::Point;
  glm::vec3 color{1.0f};     // linear
  float intensity = 1.0f;    // candela (lux: directional)
  float range = 0.0f;        // metres; 0: unlimited
  float innerConeAngle = 0.0f, outerConeAngle = 0.7853982f;  // radians (spot)
  int node = -1;             // index into Scene::nodes; -1: fixed at `world`
  glm::mat4 world{1.0f};     // at rest
};

// A glTF camera ("cameras", placed by a node: scene/Camera.h's cameraOfScene poses it), perspective or orthographic,
// with the file's values. Front ends list them by `label()` and choose one by its index here, the name of its camera
// or the name of its node.
struct SceneCamera {
  std::string name;      // the glTF camera's name (may be empty)
  std::string nodeName;  // the name of the node that places it (may be empty)
  bool orthographic = false;
  float yfov = 0.8f;          // perspective: the vertical field of view, radians
  float aspectRatio = 0.0f;   // perspective: the frame's aspect ratio; 0: none given (the output's)
  float xmag = 1.0f, ymag = 1.0f;  // orthographic: the half width and half height of the view
  float znear = 0.1f;
  float zfar = 0.0f;     // 0: none given (glTF's infinite perspective projection)
  int node = -1;         // index into Scene::nodes; -1: fixed at `world`
  glm::mat4 world{1.0f};  // at rest
  // The aspect ratio the view was framed for: aspectRatio, or xmag / ymag; 0: none.
  float frameAspect() const { return orthographic ? xmag / ymag : aspectRatio; }
  // What a menu shows: the node's name, else the camera's, else "camera N" (N its index in Scene::cameras).
  std::string label(size_t index) const;
};

// A morph target: per-vertex displacements added, times the target's weight, to the mesh's rest attributes.
struct MorphTarget {
  std::vector<glm::vec3> positions;  // one per vertex
  std::vector<glm::vec3> normals;    // empty (the target moves no normal), or one per vertex
  std::vector<glm::vec3> tangents;   // empty, or one per vertex: the tangent's xyz (Mesh::tangents; w stays)
};

// A coarser triangle list over a mesh's own vertices (scene/MeshDetail.h makes them), with the geometric error it
// makes.
struct DetailLevel {
  std::vector<std::uint32_t> indices;  // a triangle list over the mesh's own vertices
  // The simplifier's error, in the mesh's units: the distance of the simplified surface from the mesh's, with a
  // change of unit normal counted as kDetailNormalWeight times the mesh's extent (scene/MeshDetail.h).
  float error = 0.0f;
};

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;    // one per position, unit length
  std::vector<glm::vec2> texcoords;  // empty, or one per position
  std::vector<glm::vec2> texcoords1;  // TEXCOORD_1: empty, or one per position (Material::texCoords chooses)
  std::vector<glm::vec4> colors;      // COLOR_0 (linear RGBA): empty, or one per position; multiplies the base colour
  // Empty, or one per position: xyz the unit tangent (along +u), w the bitangent's sign (+-1): B = w (N x T). From the
  // file's TANGENT, else generated (scene/MeshProcessing.h: generateTangents) where a normal texture needs them.
  std::vector<glm::vec4> tangents;
  std::vector<std::uint32_t> indices;  // triangle list
  int material = -1;                   // -1: the default material
  // Skinning (glTF JOINTS_0 / WEIGHTS_0): empty, or one per position. Joint indices index the instance's skin's
  // `joints`; weights are non-negative and sum to 1 (the loader renormalises).
  std::vector<glm::u16vec4> joints;
  std::vector<glm::vec4> weights;
  std::vector<MorphTarget> morphTargets;  // the node's morph weights scale them (Node::weights)
  // Levels of detail, finest first: made once, where a scene is loaded (scene/MeshDetail.h: addDetailLevels), and
  // drawn at gbuffer.lod. They index `positions`: whatever changes the vertices or the indices clears them.
  std::vector<DetailLevel> levels;
  bool skinned() const { return !joints.empty(); }
};

// A node of the hierarchy: its rest transform (TRS, or a matrix that animation never targets) and, for nodes with
// a morphed mesh, its rest morph weights (the glTF node's weights, else the mesh's, else zeros).
struct Node {
  std::string name;
  int parent = -1;  // index into Scene::nodes, lower than this node's; -1: a root
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
  glm::vec3 scale{1.0f};
  bool hasMatrix = false;  // the local transform is `matrix` (a glTF matrix node: not animated)
  glm::mat4 matrix{1.0f};
  std::vector<float> weights;
  glm::mat4 localRest() const;  // the local transform without animation
};

// A glTF skin: the nodes that are its joints and their inverse bind matrices. A skinned vertex's world position is
// sum_i w_i * world(joints[j_i]) * inverseBind[j_i] * p; the skinned mesh's own node transform is ignored, as the glTF
// spec says, and `skeleton` is only the hint of the common root.
struct Skin {
  std::string name;
  std::vector<int> joints;                  // node indices
  std::vector<glm::mat4> inverseBind;       // one per joint (identity where the file gives none)
  int skeleton = -1;
};

// Points and lines (glTF modes POINTS, LINES, LINE_LOOP, LINE_STRIP): not surfaces, so they have no G-buffer entry and
// no AO; effects/lines/LinesEffect.h draws them unlit into the lit image, depth-tested against the surfaces.
struct LineMesh {
  bool points = false;               // GL_POINTS, else GL_LINES
  std::vector<glm::vec3> positions;  // points: one per point; lines: two per segment (strips and loops expanded)
  std::vector<glm::vec4> colors;     // empty, or one per position: COLOR_0 (linear RGBA)
  int material = -1;                 // its base colour factor tints them; -1: white
};

struct LineInstance {
  int mesh = 0;           // index into Scene::lineMeshes
  glm::mat4 world{1.0f};  // at rest
  int node = -1;          // the node that places it (posed by animation; skins and morph targets are not applied)
};

struct Instance {
  int mesh = 0;
  glm::mat4 world{1.0f};  // at rest (the node's world matrix without animation)
  int node = -1;          // the node that places it, -1: none (fixed at `world`)
  int skin = -1;          // index into Scene::skins, -1: rigid (the mesh must then have no joints)
};

// glTF animation data, as loaded (validated: times finite and strictly increasing, values finite, counts agreeing
// with the interpolation). scene/Animation.h samples it.
enum class Interpolation { Linear, Step, CubicSpline };
enum class AnimationPath { Translation, Rotation, Scale, Weights };

struct AnimationSampler {
  std::vector<float> times;   // seconds, strictly increasing, at least one
  // Per key, `components` floats (3 for translation and scale, 4 for a rotation quaternion x, y, z, w, the node's
  // morph target count for weights); CUBICSPLINE keys hold in-tangent, value, out-tangent, so 3 x that.
  std::vector<float> values;
  int components = 0;
  Interpolation interpolation = Interpolation::Linear;
};

struct AnimationChannel {
  int sampler = 0;  // index into Animation::samplers
  int node = 0;     // index into Scene::nodes
  AnimationPath path = AnimationPath::Translation;
};

struct Animation {
  std::string name;  // may be empty
  std::vector<AnimationSampler> samplers;
  std::vector<AnimationChannel> channels;
  float duration() const;  // the last key time over all samplers (0 for a single key)
};

struct Bounds {
  glm::vec3 min{1e30f}, max{-1e30f};
  bool empty() const { return min.x > max.x; }
  void add(const glm::vec3& p);
  glm::vec3 center() const { return (min + max) * 0.5f; }
  float radius() const;  // half the diagonal
  // The eight corners seen through `toClip` (model-view-projection), in clip space: corner k takes max along each
  // axis whose bit is set in k (x 1, y 2, z 4).
  std::array<glm::vec4, 8> clipCorners(const glm::mat4& toClip) const;
  // The box seen through `toClip` lies wholly outside the clip volume: all eight corners beyond one of its six
  // planes (-w <= x, y, z <= w), so that nothing of what the box holds can reach a pixel. A box that only straddles
  // planes (around a frustum's corner, or across the near plane behind the eye) counts as inside: the test is
  // conservative. An empty box is outside.
  bool outsideClip(const glm::mat4& toClip) const;
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Image> images;
  std::vector<Node> nodes;        // empty for a scene without hierarchy (all instances fixed)
  std::vector<Skin> skins;
  std::vector<Animation> animations;
  std::vector<LineMesh> lineMeshes;        // points and lines
  std::vector<LineInstance> lineInstances;
  std::vector<PunctualLight> lights;       // KHR_lights_punctual point and spot lights
  std::vector<SceneCamera> cameras;        // the file's cameras, one per node that has one, in node order
  // The AO radius the scene was designed for, in its units; 0 for none (a loaded file), when defaultAoRadius
  // (scene/SceneScale.h) derives one from the scene's size. The built-in scene: 1 (metre).
  float designedAoRadius = 0.0f;

  Bounds worldBounds() const;  // at rest, points and lines included
  std::size_t triangleCount() const;
  // Something can move: an animation, or a skin or morph target a pose could change.
  bool animated() const;
};

}  // namespace obscura
