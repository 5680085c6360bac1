#pragma once
// A Scene uploaded to GL: vertex/index buffers per mesh piece, textures per glTF texture, the pose of this frame and
// of the previous one (setPose), and the draw loop every geometry pass (G-buffer, lighting, velocity) shares, so they
// draw exactly the same triangles with the same state.
//
// WebGL 1 rules: without OES_element_index_uint, meshes over 65535 vertices are split into 16-bit pieces
// (scene/MeshProcessing.h); textures follow the non-power-of-two and size rules of scene/TexturePreparation.h.
//
// Skinning, sized to what GLES 2 guarantees (gpu/VertexKind.h, shaders_es2/lib/geometry.vert):
//   - the joint texture (SkinningPath::Texture) where the vertex stage has a texture unit and float textures exist:
//     one RGBA float texture per skin holding this frame's and the previous frame's joint matrices;
//   - else a uniform palette (SkinningPath::Uniforms) of paletteSize() joints, from the vertex uniform vectors left
//     once the other uniforms are counted, with room for the previous frame's palette (the velocity pass): 16 joints
//     at GLES 2's minimum of 128 vectors. A mesh whose skin has more joints is split into pieces whose joints fit;
//   - else, or where forced, on the CPU (SkinningPath::Cpu): deformed vertices uploaded every frame.
// Morph targets go to the vertex stage as attributes as far as the context's vertex attributes allow (2 targets with
// normals on a rigid mesh at GLES 2's 8, capped at 4), choosing per draw the targets with a non-zero weight now or in
// the previous frame; a draw that needs more is morphed on the CPU that frame.
#include <array>
#include <functional>
#include <optional>
#include <unordered_map>
#include <vector>

#include <glm/mat4x4.hpp>

#include "gl/GlCaps.h"
#include "gl/GlObjects.h"
#include "gl/Program.h"
#include "gl/RenderTarget.h"
#include "gpu/GpuLines.h"
#include "gpu/MaterialKind.h"
#include "gpu/VertexKind.h"
#include "scene/Animation.h"
#include "scene/Scene.h"

namespace obscura {

// The uniforms and attributes of geometry.vert and lib/material.glsl that draw() sets per instance, resolved once
// per program. Only u_instanceTransforms is required: a fragment stage that reads no normal or no base colour (the
// G-buffer pass of opaque materials) lets the compiler drop the others, and a variant without deformation has none of
// the skinning or morphing ones.
struct GeometryUniforms {
  GeometryUniforms() = default;
  explicit GeometryUniforms(const gl::Program& program);
  GLint instanceTransforms = -1;  // the model-view and the normal matrix, columns of one vec4 array
  GLint baseColorFactor = -1, baseColorTexture = -1, alphaCutoff = -1;
  GLint baseColorSrgb = -1;  // the G-buffer's base colour output for a factor-only material
  GLint metallicRoughness = -1, emissive = -1, uvTransforms = -1, uvSets = -1;
  GLint specular = -1, clearcoat = -1, clearcoatRoughness = -1;  // MATERIAL_LAYERS
  GLint transmission = -1, transmissionIor = -1;                   // TRANSMISSION
  GLint pbrTextures[4] = {-1, -1, -1, -1};  // metallic-roughness, normal, occlusion, emissive samplers
  GLint joints = -1, previousJoints = -1, jointTexture = -1, jointTextureSize = -1;
  GLint morphWeights = -1, previousMorphWeights = -1, previousModel = -1;
  GLint jointsAttribute = -1, weightsAttribute = -1, previousPositionAttribute = -1, tangentAttribute = -1;
  GLint colorAttribute = -1;
  GLint morphPositionAttribute[VertexKind::kMaxMorphTargets] = {-1, -1, -1, -1};
  GLint morphNormalAttribute[VertexKind::kMaxMorphTargets] = {-1, -1, -1, -1};
  GLint morphTangentAttribute[VertexKind::kMaxMorphTargets] = {-1, -1, -1, -1};
};

class GpuScene {
 public:
  struct Options {
    bool allowUint32Indices = true;  // false simulates a context without OES_element_index_uint
    std::optional<SkinningPath> skinning;  // RendererOptions::skinning
    // false draws without vertex array objects where the context has them (RendererOptions::allowVertexArrays)
    bool allowVertexArrays = true;
    // false draws every instance by itself (RendererOptions::batchStaticInstances; see staticBatchCount)
    bool batchStaticInstances = true;
  };

  GpuScene() = default;
  GpuScene(const Scene& scene, const gl::GlCaps& caps, const Options& options);
  GpuScene(const Scene& scene, const gl::GlCaps& caps) : GpuScene(scene, caps, Options{}) {}

  // This frame's pose and the previous frame's (scene/Animation.h), before the frame's passes draw: places the
  // instances, uploads joint textures and CPU-deformed vertices. Both poses must come from this scene.
  void setPose(const ScenePose& current, const ScenePose& previous);

  // Chooses the program for a draw: the material's kind (gpu/MaterialKind.h) and the vertex stage's
  // (gpu/VertexKind.h). It makes the program current, sets its per-frame uniforms, and returns it; the scene sets
  // the per-draw ones by location (GeometryUniforms, resolved once per program).
  using ProgramChoice = std::function<const gl::Program&(MaterialKind material, VertexKind vertex)>;
  struct DrawOptions {
    bool onlyMoving = false;  // only instances whose pose differs from the previous frame's (velocity)
    // Every face of every material, front or back (culling off): the AO's second depth layer, where an occluder's
    // back faces bound its thickness (effects/ao/DepthPeelPass.h).
    bool bothFaces = false;
  };
  // Chooses each instance's level of detail for this frame's draws (scene/MeshDetail.h): the coarsest whose error,
  // projected at the nearest point of the instance's bounds, is at most `maxPixelError` pixels of a frame
  // `heightPixels` high; full detail where none is that fine, where the bounds reach the eye, and everywhere for 0.
  // Every draw until the next call draws the same triangles (the G-buffer, the lighting and the velocity agree).
  void chooseDetail(const glm::mat4& view, const glm::mat4& projection, int heightPixels, float maxPixelError);
  // Frustum culling: every draw until the next call leaves out the instances whose bounds lie wholly outside the view
  // of `viewProjection` (Bounds::outsideClip), and a static batch's members likewise (the G-buffer, the lighting, the
  // velocity, the AO's second layer and the transparent layer agree). Skinned and morphed instances, whose pose may
  // leave their rest bounds, are always drawn. Nothing outside the view reaches a pixel, so the frame is the same;
  // what it saves is the vertex work and the draws of what lies outside (docs/benchmarks.md, "Frustum culling").
  // drawWholeScene() undoes it (RendererOptions::cullToView off).
  void cullToView(const glm::mat4& viewProjection);
  void drawWholeScene();

  // Draws every instance of the opaque layer (every material but the transparent ones, Material::transparent, which
  // drawTransparent draws): opaque materials first, then masked ones, each group front to back (by the distance of
  // its bounds' centre from the eye), so early depth tests reject what a nearer surface hides. Sets
  // u_instanceTransforms, the material uniforms of lib/material.glsl, the deformation's uniforms and attributes (this
  // frame's and, where the program has them, the previous frame's), face culling per material and winding per
  // instance. Leaves the baseline pipeline state except for the program, depth and framebuffer state it was given.
  void draw(const glm::mat4& view, const ProgramChoice& choose, const DrawOptions& options) const;
  void draw(const glm::mat4& view, const ProgramChoice& choose) const { draw(view, choose, DrawOptions{}); }

  // The transparent layer (effects/transparency): each instance's draws back to front by the view-space depth of its
  // bounds' centre (a double-sided material's back faces, then its front faces), grouped into batches in that order
  // whose draws cover pairwise disjoint pixel rectangles, so that all the draws of a batch can read one copy of
  // what lies behind them. `rect`: x, y, width, height in pixels of the frame, covering the batch's draws.
  struct TransparentDraw {
    int instance = 0;
    GLenum cullFace = GL_BACK;  // the faces not drawn (GL_FRONT: the back faces of a double-sided material)
  };
  struct TransparentBatch {
    glm::ivec4 rect{0};
    std::vector<TransparentDraw> draws;
  };
  std::vector<TransparentBatch> transparentBatches(const glm::mat4& view, const glm::mat4& projection,
                                                   glm::ivec2 size) const;
  void drawTransparent(const glm::mat4& view, const ProgramChoice& choose, const TransparentBatch& batch) const;
  // The pixels the scene's draws may cover, x, y, width, height in a frame of `size` pixels (GL window coordinates):
  // the union of every instance's projected bounds (the whole frame for a skinned or morphed one, or one reaching
  // behind the eye); empty for an empty scene.
  glm::ivec4 coveredRect(const glm::mat4& viewProjection, glm::ivec2 size) const;
  // The scene has transparent instances; some has transmission (effects/transparency reads the blurred levels).
  bool hasTransparent() const { return hasTransparent_; }
  bool hasTransmission() const { return hasTransmission_; }

  std::size_t pieceCount() const { return pieces_.size(); }
  // A material the deferred lighting cannot shade (Material::needsForwardLighting) is drawn, or the scene has
  // punctual lights: the lighting takes its forward form (effects/lighting/LightingEffect.h).
  bool needsForwardLighting() const { return needsForwardLighting_; }
  // The scene's KHR_lights_punctual lights, placed by this frame's pose (setPose).
  const std::vector<PunctualLight>& lights() const { return lights_; }
  // The scene's points and lines (not surfaces: no G-buffer, no AO), posed by setPose; effects/lines/LinesEffect.h
  // draws them.
  const GpuLines& lines() const { return lines_; }
  // While withheld, the draws choose their programs and set their state but draw nothing, the lines included
  // (FullscreenTriangle::withholdDraws: Renderer::prepare's rehearsal).
  void withholdDraws(bool withheld) {
    withheld_ = withheld;
    lines_.withholdDraws(withheld);
  }
  bool usesUint32Indices() const;
  // The pieces' vertex streams are kept in vertex array objects (OES_vertex_array_object, not refused by
  // Options::allowVertexArrays): a draw that neither morphs on the GPU nor is deformed on the CPU binds its piece's
  // object instead of setting each stream, about ten calls fewer per draw (a browser's WebGL calls each cost the page
  // host time). The object is made on the piece's first draw with a program, per set of attribute locations.
  bool usesVertexArrays() const { return vertexArrays_; }
  // Static batches: the rigid, opaque instances that no animation moves, sharing a material (and the vertex streams
  // its program reads), are uploaded once more, placed in world space, as one piece per batch of up to 65536
  // vertices; each frame's draws draw the batch, one draw where its members all take their full detail (a member at
  // a coarser level breaks the batch's index range into runs). A browser pays about a microsecond of host time for
  // each WebGL call, and a draw of a built-in scene's box is three of them (docs/benchmarks.md, "Static batches").
  // Only meshes of at most kBatchMemberVertices vertices join one (a larger one's draw costs more than its calls), and
  // the copies hold at most as many vertices as the scene's meshes, or one batch's worth where those are fewer: a
  // mesh instanced many times would otherwise be copied as many times (a forest of one tree). The smallest meshes
  // join first: their draws cost the most for what they draw. A batch whose member's pose differs from the one it
  // was placed at (a pose not made by this scene's animations) draws its members by themselves until the pose
  // returns.
  static constexpr int kBatchMemberVertices = 4096;
  int staticBatchCount() const { return static_cast<int>(batches_.size()); }
  std::size_t staticBatchVertices() const;  // the copies' vertices, over every batch
  // Something moves between the previous pose and this one (an instance, a joint or a morph weight).
  bool anyMoving() const;
  // How skinned meshes are drawn, and the uniform palette's size in joints (0 where the path is not Uniforms).
  SkinningPath skinningPath() const { return skinningPath_; }
  int paletteSize() const { return paletteSize_; }
  // Morph targets a draw can take as attributes: those left once `otherAttributes` are bound, `perTarget` each.
  int morphTargetSlots(int perTarget, int otherAttributes) const;
  // Draws of the last draw() call that were deformed on the CPU (tests, benchmarks).
  struct Counts {
    int draws = 0, cpuDeformed = 0, gpuMorphed = 0, skinned = 0;
    int vertexArrays = 0;  // draws that bound a vertex array object instead of setting their streams
    long triangles = 0;    // drawn, at the levels of detail chosen
    int coarser = 0;       // draws (a static batch's: members) at a level of detail below the full one
    int batchedInstances = 0;  // instances drawn within a static batch's draw (one draw, however many members)
    int drawCalls = 0;  // glDrawElements calls: one a draw, a static batch's one per run of members (drawIndices)
  };
  Counts lastDrawCounts() const { return counts_; }

 private:
  struct Piece {
    gl::BufferHandle vertices, indices;
    GLsizei indexCount = 0;
    GLenum indexType = GL_UNSIGNED_SHORT;
    // The coarser levels of detail (scene/MeshDetail.h), finest first, after the full list in `indices`; none for a
    // mesh drawn in several pieces (the levels index the whole mesh's vertices).
    struct Level {
      GLsizei indexCount = 0;
      size_t offset = 0;  // bytes into `indices`
      float error = 0.0f;  // in the mesh's units
    };
    std::vector<Level> levels;
    gl::BufferHandle skinAttributes;  // joints (4 floats) then weights (4 floats) per vertex; none if rigid
    // Per target (normals, tangents: none where the target has none).
    std::vector<gl::BufferHandle> morphPositions, morphNormals, morphTangents;
    gl::BufferHandle tangents;  // vec4 per vertex, for PBR_TEXTURES materials; none otherwise
    gl::BufferHandle colors;    // COLOR_0, vec4 per vertex; none where the mesh has none
    std::vector<int> palette;  // the uniform path: the skin joint of each palette entry
    Mesh source;               // kept for CPU deformation (skinned on the CPU path, or morphed): the piece's mesh
    // A static batch's piece: its members in the order of its full index list, each with its own ranges of the
    // indices (after every member's full list, level by level each member's list at that level: makeBatch;
    // `levels` above stays empty).
    struct Member {
      int instance = 0;  // into instances_
      glm::mat4 world{1.0f};  // the world matrix its vertices were placed with
      Level full;
      std::vector<Level> levels;
    };
    std::vector<Member> members;
  };
  struct MaterialGpu {
    glm::vec4 baseColorFactor{1.0f};
    glm::vec3 baseColorSrgb{1.0f};  // the factor's rgb, sRGB-encoded: what the G-buffer stores where no texture is
    int texture = -1;  // index into textures_, -1: none (the factor alone)
    float alphaCutoff = -2.0f;  // the MASK cutoff; -1 BLEND, -2 OPAQUE
    bool doubleSided = false;
    bool pbr = false;  // PBR_TEXTURES: pbrTextures has one
    std::array<int, 4> pbrTextures{-1, -1, -1, -1};  // metallic-roughness, normal, occlusion, emissive; -1: neutral
    glm::vec4 metallicRoughness{0.0f, 1.0f, 0.0f, 1.0f};  // metallic, roughness, normal scale, occlusion strength
    glm::vec3 emissive{0.0f};                              // factor x strength
    std::array<glm::vec3, 2 * kTextureSlots> uvRows{};     // each slot's KHR_texture_transform, as two rows
    float uvSets = 0.0f;  // sum over slots k of texCoord_k 2^k (geometry.vert's u_uvSets)
    bool unlit = false, layered = false, transmission = false, transparent = false;
    glm::vec4 specular{0.04f, 0.04f, 0.04f, 1.0f};  // the dielectric's F0 (rgb) and F90 (a)
    float clearcoat = 0.0f, clearcoatRoughness = 0.0f, transmissionFactor = 0.0f;
    float transmissionIor = 1.0f;  // clamp(2 ior - 2, 0, 1): how much of the roughness blurs what shows through
    MaterialKind kind() const { return {alphaCutoff >= 0.0f, texture >= 0, pbr, unlit, layered, transmission}; }
  };
  struct InstanceGpu {
    glm::mat4 world{1.0f}, previousWorld{1.0f};
    glm::vec3 localCentre{0.0f};  // of its mesh's bounds, in the mesh's space
    glm::vec3 localMin{0.0f}, localMax{0.0f};  // its mesh's bounds (transparent batches' rectangles)
    glm::vec3 restCentre{0.0f};   // the same, placed at rest
    glm::vec3 centre{0.0f};      // of its posed bounds (approximately), for the drawing order
    int material = 0;
    int firstPiece = 0, pieceCount = 0;
    float localRadius = 0.0f;    // half its mesh's bounds' diagonal
    bool inView = true;          // this frame's view may see it (cullToView); a batch's: one of its members
    int detail = 0;              // this frame's level of detail: 0 the full one, k its piece's levels[k - 1]
    int batch = -1;              // the static batch (into batches_) that draws it while the batch is intact
    int skin = -1;               // index into skins_ where drawn skinned
    bool cpuSkinned = false;     // skinned on the CPU (SkinningPath::Cpu)
    bool morphed = false;        // its mesh has morph targets
    bool moving = false;
    bool transparent = false;    // its material is (drawTransparent)
    // This frame's deformation: the morph targets bound as attributes (GPU), or CPU-deformed vertex buffers.
    std::vector<int> gpuTargets;
    std::vector<float> weights, previousWeights;
    bool cpuDeformed = false;
    std::vector<gl::BufferHandle> deformed;  // per piece: position, normal, texcoord, previous position
  };
  struct SkinGpu {
    std::vector<glm::mat4> joints, previousJoints;  // world(joint) * inverseBind(joint)
    // Most of its joints mirror (a negative determinant): the winding of what it skins turns, as a mirroring node's.
    bool mirrored = false;
    gl::TextureHandle texture;                      // the joint texture path
    glm::vec3 textureSize{0.0f};                    // width, height, texels per palette
    bool uploaded = false;                          // the texture holds `joints` and `previousJoints`
  };

  // A static batch as drawn: an instance at the identity whose one piece holds its members in world space.
  struct StaticBatch {
    InstanceGpu drawn;
    std::size_t vertices = 0;  // the copy's
    bool intact = true;  // every member's pose, this frame's and the previous one's, is the one it was placed at
  };

  struct MeshPieces {  // a Scene mesh's pieces
    int first = 0, count = 0;
    bool cpuSkinned = false;
  };
  // What one draw() call carries from piece to piece: the current program, and the state to restore at the end.
  struct DrawState {
    explicit DrawState(const ProgramChoice& program) : choose(program) {}
    const ProgramChoice& choose;
    const GeometryUniforms* uniforms = nullptr;
    std::optional<GeometryUniforms> withheldUniforms;  // a withheld draw's, not kept (its program may be a stand-in)
    MaterialKind programMaterial;
    VertexKind programVertex;
    std::vector<GLuint> extraAttributes;  // enabled for the current piece, disabled after it
    bool jointTextureBound = false;
    bool pbrTexturesBound = false;
    // What this draw call has set already, so that a run of instances sharing it sets it once (each call costs a
    // browser more than the driver's work): face culling (-1 not yet), the winding (0 not yet), the material whose
    // textures are bound and the material whose uniforms the current program holds (-1: none; a program chosen
    // since, which may bind textures of its own, resets both).
    int culling = -1;
    GLenum frontFace = 0;
    int texturesOf = -1;
    int uniformsOf = -1;
    GLuint vertexArray = 0;  // bound now (0: the context's default, where the streams are set per draw)
    bool defaultStreams = false;  // slots 0..2 enabled on the default object (by the first draw that sets them)
    // Points an attribute the program has (location >= 0) at a buffer.
    void attribute(GLint location, GLuint buffer, GLint size, GLsizei stride, size_t offset);
  };
  // CPU-deformed vertices: position, normal, previous position, tangent (the texture coordinates and colours stay in
  // the piece's own buffers).
  static constexpr int kDeformedFloats = 13;
  static constexpr int kVertexFloats = 10;  // the piece's vertices: position, normal, TEXCOORD_0, TEXCOORD_1

  // Upload (the constructor, in this order).
  void chooseSkinningPath(const gl::GlCaps& caps, const Options& options);  // GpuSkinning.cpp
  void uploadTextures(const Scene& scene, const gl::GlCaps& caps);
  void uploadMaterials(const Scene& scene);
  std::vector<MeshPieces> uploadMeshes(const Scene& scene, bool uint32);
  Piece uploadPiece(Mesh mesh, const std::vector<int>& palette, bool tangents,
                    const std::vector<DetailLevel>& levels);
  void createSkins(const Scene& scene, const gl::GlCaps& caps);  // GpuSkinning.cpp
  void placeInstances(const Scene& scene, const std::vector<MeshPieces>& meshPieces);
  // The mesh as uploaded: `source`, or a copy in `storage` with tangents generated where its material's normal
  // texture needs them and the file has none.
  const Mesh& meshToUpload(const Scene& scene, const Mesh& source, Mesh& storage) const;
  // StaticBatches.cpp: the batches of the still instances, placed at `rest`; one batch of `memberInstances`.
  void batchStaticInstances(const Scene& scene, const ScenePose& rest);
  StaticBatch makeBatch(const Scene& scene, const ScenePose& rest, const std::vector<size_t>& memberInstances,
                        int material, bool tangents);

  // Pose.
  std::vector<bool> poseSkins(const ScenePose& current, const ScenePose& previous);  // GpuSkinning.cpp
  bool chooseGpuMorphTargets(InstanceGpu& instance) const;
  void uploadCpuDeformed(InstanceGpu& instance, const ScenePose& current, const ScenePose& previous,
                         size_t index);  // GpuSkinning.cpp

  // Draw.
  std::vector<const InstanceGpu*> drawOrder(const glm::mat4& view, const DrawOptions& options) const;
  // Its pose keeps it within its mesh's rest bounds, placed by its world transform: not skinned, not morphed.
  static bool withinRestBounds(const InstanceGpu& instance) { return instance.skin < 0 && !instance.morphed; }
  void drawInstance(const InstanceGpu& instance, const glm::mat4& view, DrawState& state) const;
  glm::ivec4 screenRect(const InstanceGpu& instance, const glm::mat4& viewProjection, glm::ivec2 size) const;
  VertexKind vertexKind(const InstanceGpu& instance, const Piece& piece) const;  // GpuSkinning.cpp
  void bindMaterialTextures(const MaterialGpu& material, DrawState& state) const;
  void drawPiece(const InstanceGpu& instance, int p, const MaterialGpu& material, const glm::mat4& modelView,
                 DrawState& state) const;
  void setInstanceUniforms(const InstanceGpu& instance, const MaterialGpu& material, const glm::mat4& modelView,
                           const VertexKind& vertexKind, DrawState& state) const;
  void bindSkin(const InstanceGpu& instance, const Piece& piece, const VertexKind& vertexKind,
                DrawState& state) const;  // GpuSkinning.cpp
  void bindVertices(const InstanceGpu& instance, int p, const VertexKind& vertexKind, DrawState& state) const;
  // The piece's vertex array object for the current program's attribute locations (made and filled on first use),
  // or 0 where this draw sets its streams itself (no objects, a withheld draw, GPU morphing or CPU deformation,
  // whose streams change from frame to frame).
  GLuint pieceVertexArray(const InstanceGpu& instance, int p, const VertexKind& vertexKind, DrawState& state) const;
  void bindVertexArray(GLuint vertexArray, DrawState& state) const;
  // glDrawElements of the piece's indices at level of detail `detail` (InstanceGpu::detail), counted; a static
  // batch's at each member's level.
  void drawIndices(const Piece& piece, int detail) const;
  void drawBatchMembers(const Piece& batch) const;  // StaticBatches.cpp
  void restoreAfterDraw(const DrawState& state) const;

  std::vector<Piece> pieces_;
  std::vector<MaterialGpu> materials_;  // last entry: the default material
  std::vector<InstanceGpu> instances_;
  std::vector<StaticBatch> batches_;
  std::vector<SkinGpu> skins_;
  std::vector<gl::TextureHandle> textures_;
  gl::Texture2D neutralWhite_, neutralNormal_;
  std::vector<PunctualLight> lights_;
  bool needsForwardLighting_ = false;
  bool hasTransparent_ = false, hasTransmission_ = false;
  GpuLines lines_;
  bool withheld_ = false;
  SkinningPath skinningPath_ = SkinningPath::Uniforms;
  int paletteSize_ = 0;
  VertexLimits limits_;
  bool desktopGl_ = false;
  bool vertexArrays_ = false;
  mutable Counts counts_;
  // Per piece, its vertex array objects, keyed by the attribute locations beside the three fixed ones that the
  // piece's streams need (vertexArrayKey): one entry in the common case of one set of programs. Made while drawing
  // (a const draw), hence mutable; they go with the scene.
  mutable std::vector<std::vector<std::pair<std::uint32_t, gl::VertexArrayHandle>>> pieceVertexArrays_;
  // The per-draw uniforms of each program drawn with, resolved on its first draw (programs outlive the scene's
  // draws: they belong to the Renderer).
  mutable std::unordered_map<const gl::Program*, GeometryUniforms> geometryUniforms_;
};

}  // namespace obscura
