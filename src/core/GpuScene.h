#pragma once
// A Scene uploaded to GL: vertex/index buffers per mesh piece, textures per glTF texture, and the draw loop both
// geometry passes (G-buffer and lighting) share, so they draw exactly the same triangles with the same state.
//
// WebGL 1 rules: without OES_element_index_uint, meshes over 65535 vertices are split into 16-bit pieces
// (scene/MeshProcessing.h); textures follow the non-power-of-two and size rules of scene/TexturePreparation.h.
#include <functional>
#include <vector>

#include <glm/mat4x4.hpp>

#include "gl/GlCaps.h"
#include "gl/GlObjects.h"
#include "core/MaterialKind.h"
#include "gl/Program.h"
#include "scene/Scene.h"

namespace obscura {

// The uniforms of geometry.vert and lib/material.glsl that draw() sets per instance, resolved once per program. Only
// u_modelView is required: a fragment stage that reads no normal or no base colour (the G-buffer pass of opaque
// materials) lets the compiler drop the others.
struct GeometryUniforms {
  GeometryUniforms() = default;
  explicit GeometryUniforms(const gl::Program& program);
  GLint modelView = -1, normalMatrix = -1, baseColorFactor = -1, baseColorTexture = -1, alphaCutoff = -1;
};

class GpuScene {
 public:
  struct Options {
    bool allowUint32Indices = true;  // false simulates a context without OES_element_index_uint
  };

  GpuScene() = default;
  GpuScene(const Scene& scene, const gl::GlCaps& caps, const Options& options);
  GpuScene(const Scene& scene, const gl::GlCaps& caps) : GpuScene(scene, caps, Options{}) {}

  // Chooses the program for a kind of material (core/MaterialKind.h: masked or opaque, with or without a base-colour
  // texture). It makes the program current, sets its per-frame uniforms, and returns its per-instance ones.
  using ProgramChoice = std::function<const GeometryUniforms&(MaterialKind kind)>;
  // Draws every instance: opaque materials first, then masked ones, each group front to back (by the distance of
  // its bounds' centre from the eye), so early depth tests reject what a nearer surface hides. Sets u_modelView,
  // u_normalMatrix, the material uniforms of lib/material.glsl, face culling per material and winding per instance.
  // Leaves the baseline pipeline state except for the program, depth and framebuffer state it was given.
  void draw(const glm::mat4& view, const ProgramChoice& choose) const;

  // Each instance's world matrix, in draw order (the frame context keeps the previous frame's).
  std::vector<glm::mat4> worldMatrices() const;

  std::size_t pieceCount() const { return pieces_.size(); }
  bool usesUint32Indices() const;

 private:
  struct Piece {
    gl::BufferHandle vertices, indices;
    GLsizei indexCount = 0;
    GLenum indexType = GL_UNSIGNED_SHORT;
  };
  struct MaterialGpu {
    glm::vec4 baseColorFactor{1.0f};
    int texture = -1;  // index into textures_, -1: none (the factor alone)
    float alphaCutoff = -1.0f;
    bool doubleSided = false;
  };
  struct InstanceGpu {
    glm::mat4 world{1.0f};
    glm::vec3 centre{0.0f};  // of its world-space bounds, for the drawing order
    int material = 0;
    int firstPiece = 0, pieceCount = 0;
  };

  std::vector<Piece> pieces_;
  std::vector<MaterialGpu> materials_;  // last entry: the default material
  std::vector<InstanceGpu> instances_;
  std::vector<gl::TextureHandle> textures_;
};

}  // namespace obscura
