#pragma once
// A scene as the renderer consumes it: triangle meshes in local space, instances placing them in the world (in the
// scene's own units: metres for the built-in scene, whatever a glTF file was authored in; right-handed, +y up),
// materials and RGBA8 images. Built by the glTF loader or by the built-in scene generator; holds no GL objects
// (GpuScene uploads it).
#include <cstdint>
#include <string>
#include <vector>

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

struct Material {
  glm::vec4 baseColorFactor{1.0f};
  int baseColorTexture = -1;  // index into Scene::textures
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
};

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;    // one per position, unit length
  std::vector<glm::vec2> texcoords;  // empty, or one per position
  std::vector<std::uint32_t> indices;  // triangle list
  int material = -1;                   // -1: the default material
};

struct Instance {
  int mesh = 0;
  glm::mat4 world{1.0f};
};

struct Bounds {
  glm::vec3 min{1e30f}, max{-1e30f};
  bool empty() const { return min.x > max.x; }
  void add(const glm::vec3& p);
  glm::vec3 center() const { return (min + max) * 0.5f; }
  float radius() const;  // half the diagonal
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Image> images;
  // The AO radius the scene was designed for, in its units; 0 for none (a loaded file), when defaultAoRadius
  // (scene/SceneScale.h) derives one from the scene's size. The built-in scene: 1 (metre).
  float designedAoRadius = 0.0f;

  Bounds worldBounds() const;
  std::size_t triangleCount() const;
};

}  // namespace obscura
