#include "gpu/GpuScene.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>

#include "base/Error.h"
#include "base/TimeSpent.h"
#include "encoding/ToneMapping.h"
#include "gpu/TextureUnits.h"
#include "scene/MeshProcessing.h"
#include "scene/TexturePreparation.h"

namespace obscura {
namespace {

gl::TextureHandle uploadTexture(const Image& source, const SamplerState& sampler, const gl::GlCaps& caps) {
  const PreparedTexture prepared = prepareTextureForGles2(source, sampler, caps.maxTextureSize);
  gl::TextureHandle texture = gl::TextureHandle::create();
  glBindTexture(GL_TEXTURE_2D, texture.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, prepared.image.width, prepared.image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               prepared.image.rgba.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, prepared.sampler.minFilter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, prepared.sampler.magFilter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, prepared.sampler.wrapS);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, prepared.sampler.wrapT);
  if (prepared.mipmaps) glGenerateMipmap(GL_TEXTURE_2D);
  glBindTexture(GL_TEXTURE_2D, 0);
  return texture;
}

// Position, normal, TEXCOORD_0, TEXCOORD_1 (GpuScene::kVertexFloats): a_texcoord reads both sets as one vec4.
std::vector<float> interleave(const Mesh& part) {
  std::vector<float> interleaved;
  interleaved.reserve(part.positions.size() * 10);
  for (size_t v = 0; v < part.positions.size(); ++v) {
    const glm::vec2 uv = part.texcoords.empty() ? glm::vec2(0.0f) : part.texcoords[v];
    const glm::vec2 uv1 = part.texcoords1.empty() ? glm::vec2(0.0f) : part.texcoords1[v];
    interleaved.insert(interleaved.end(), {part.positions[v].x, part.positions[v].y, part.positions[v].z,
                                           part.normals[v].x, part.normals[v].y, part.normals[v].z, uv.x, uv.y,
                                           uv1.x, uv1.y});
  }
  return interleaved;
}

gl::BufferHandle arrayBuffer(const void* data, size_t bytes) {
  gl::BufferHandle buffer = gl::BufferHandle::create();
  glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes), data, GL_STATIC_DRAW);
  return buffer;
}

gl::BufferHandle vec3Buffer(const std::vector<glm::vec3>& values) {
  return arrayBuffer(values.data(), values.size() * sizeof(glm::vec3));
}

}  // namespace

GpuScene::GpuScene(const Scene& scene, const gl::GlCaps& caps, const Options& options) {
  const TimedScope timed("scene upload");
  desktopGl_ = caps.desktopGl;
  vertexArrays_ = caps.vertexArrayObject && options.allowVertexArrays;
  // The caps carry the limits a test simulates (RendererOptions::simulateVertexLimits, applied by the Renderer).
  limits_ = {caps.maxVertexUniformVectors, caps.maxVertexAttribs, caps.maxVertexTextureImageUnits};
  chooseSkinningPath(caps, options);
  uploadTextures(scene, caps);
  uploadMaterials(scene);
  const std::vector<MeshPieces> meshPieces = uploadMeshes(scene, caps.elementIndexUint && options.allowUint32Indices);
  lines_ = GpuLines(scene);
  createSkins(scene, caps);
  placeInstances(scene, meshPieces);
  lights_ = scene.lights;
  needsForwardLighting_ = !scene.lights.empty();
  // The transparent layer is lit by its own pass (effects/transparency), whatever form the lighting takes.
  for (const Mesh& mesh : scene.meshes)
    if (mesh.material >= 0) {
      const Material& material = scene.materials[static_cast<size_t>(mesh.material)];
      if (material.needsForwardLighting() && !material.transparent()) needsForwardLighting_ = true;
    }
  for (const InstanceGpu& instance : instances_) {
    hasTransparent_ = hasTransparent_ || instance.transparent;
    hasTransmission_ = hasTransmission_ || materials_[static_cast<size_t>(instance.material)].transmission;
  }
  // The rest pose, until the first setPose.
  const ScenePose rest = evaluatePose(scene, 0.0, PoseOptions{AnimationChoice::none(), false});
  if (options.batchStaticInstances) batchStaticInstances(scene, rest);
  setPose(rest, rest);
}

void GpuScene::uploadTextures(const Scene& scene, const gl::GlCaps& caps) {
  for (size_t t = 0; t < scene.textures.size(); ++t) {
    const Texture& texture = scene.textures[t];
    if (texture.image >= 0 && scene.images[static_cast<size_t>(texture.image)].width > 0)
      textures_.push_back(uploadTexture(scene.images[static_cast<size_t>(texture.image)], texture.sampler, caps));
    else
      textures_.emplace_back();
  }
  // Neutral texels for the slots a PBR_TEXTURES material lacks: white (the factor alone) and the flat normal.
  const std::uint8_t white[4] = {255, 255, 255, 255}, flat[4] = {128, 128, 255, 255};
  neutralWhite_ = gl::Texture2D(1, 1, GL_NEAREST, white);
  neutralNormal_ = gl::Texture2D(1, 1, GL_NEAREST, flat);
}

void GpuScene::uploadMaterials(const Scene& scene) {
  auto usable = [&](int texture) { return texture >= 0 && textures_[static_cast<size_t>(texture)] ? texture : -1; };
  for (const Material& m : scene.materials) {
    MaterialGpu gpu;
    gpu.baseColorFactor = m.baseColorFactor;
    gpu.baseColorSrgb = linearToSrgb(glm::vec3(m.baseColorFactor));
    gpu.texture = usable(m.baseColorTexture);
    gpu.doubleSided = m.doubleSided;
    gpu.pbrTextures = {usable(m.metallicRoughnessTexture), usable(m.normalTexture), usable(m.occlusionTexture),
                       usable(m.emissiveTexture)};
    gpu.pbr = std::any_of(gpu.pbrTextures.begin(), gpu.pbrTextures.end(), [](int t) { return t >= 0; });
    // A missing normal texture: scale 0 leaves the geometric normal whatever the neutral texel holds.
    const float normalScale = gpu.pbrTextures[1] >= 0 ? m.normalScale : 0.0f;
    gpu.metallicRoughness = glm::vec4(m.metallicFactor, m.roughnessFactor, normalScale, m.occlusionStrength);
    gpu.emissive = m.emissiveFactor * m.emissiveStrength;
    for (int slot = 0; slot < kTextureSlots; ++slot) {
      const glm::mat3& t = m.uvTransforms[static_cast<size_t>(slot)];
      // Rows of the 3x3 matrix (glm is column-major: t[column][row]).
      gpu.uvRows[static_cast<size_t>(2 * slot)] = glm::vec3(t[0][0], t[1][0], t[2][0]);
      gpu.uvRows[static_cast<size_t>(2 * slot + 1)] = glm::vec3(t[0][1], t[1][1], t[2][1]);
      if (m.texCoords[static_cast<size_t>(slot)] == 1) gpu.uvSets += static_cast<float>(1 << slot);
    }
    gpu.unlit = m.unlit;
    gpu.layered = m.layered() && !m.unlit;
    gpu.transparent = m.transparent();
    gpu.transmission = m.transmissionFactor > 0.0f && !m.unlit;
    gpu.specular = glm::vec4(m.dielectricF0(), m.specularFactor);
    gpu.clearcoat = m.clearcoatFactor;
    gpu.clearcoatRoughness = m.clearcoatRoughnessFactor;
    gpu.transmissionFactor = m.transmissionFactor;
    // The sample viewer's applyIorToRoughness; ior 0 (the extension's "infinite") blurs fully.
    gpu.transmissionIor = m.ior == 0.0f ? 1.0f : std::clamp(2.0f * m.ior - 2.0f, 0.0f, 1.0f);
    // u_alphaCutoff: the MASK cutoff; -1 for BLEND (alpha composites), -2 for OPAQUE (alpha ignored: transparency's
    // composite.glsl).
    gpu.alphaCutoff = m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : m.alphaMode == AlphaMode::Blend ? -1.0f : -2.0f;
    materials_.push_back(gpu);
  }
  materials_.push_back(MaterialGpu{});  // the default material (Material{}: a white rough dielectric)
}

// Uploads each mesh once, as one or more pieces (palette pieces where the uniform palette is too small for its skin,
// 16-bit pieces without OES_element_index_uint).
std::vector<GpuScene::MeshPieces> GpuScene::uploadMeshes(const Scene& scene, bool uint32) {
  std::vector<MeshPieces> meshPieces;
  for (const Mesh& source : scene.meshes) {
    const bool pbr = source.material >= 0 && materials_[static_cast<size_t>(source.material)].pbr;
    Mesh withTangents;
    const Mesh& mesh = meshToUpload(scene, source, withTangents);
    MeshPieces placed;
    placed.first = static_cast<int>(pieces_.size());
    std::vector<PalettePiece> parts;
    if (mesh.skinned() && skinningPath_ == SkinningPath::Uniforms) parts = splitForJointPalette(mesh, paletteSize_);
    if (parts.empty()) parts.push_back({mesh, {}});
    placed.cpuSkinned = mesh.skinned() && skinningPath_ == SkinningPath::Cpu;
    for (const PalettePiece& part : parts) {
      std::vector<Mesh> pieces = uint32 ? std::vector<Mesh>{part.mesh} : splitForShortIndices(part.mesh);
      // The scene's levels of detail (made once, at its load: scene/MeshDetail.h), only for a mesh drawn whole:
      // they index its own vertices.
      static const std::vector<DetailLevel> kNone;
      const std::vector<DetailLevel>& levels = parts.size() == 1 && pieces.size() == 1 ? mesh.levels : kNone;
      for (Mesh& piece : pieces) pieces_.push_back(uploadPiece(std::move(piece), part.palette, pbr, levels));
    }
    placed.count = static_cast<int>(pieces_.size()) - placed.first;
    meshPieces.push_back(placed);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  return meshPieces;
}

const Mesh& GpuScene::meshToUpload(const Scene& scene, const Mesh& source, Mesh& storage) const {
  // A mesh drawn with PBR textures needs tangents (the vertex stage's a_tangent): the file's, else generated.
  const bool pbr = source.material >= 0 && materials_[static_cast<size_t>(source.material)].pbr;
  if (!pbr || source.tangents.size() == source.positions.size()) return source;
  storage = source;
  const int normalSet =
      scene.materials[static_cast<size_t>(source.material)].texCoords[static_cast<size_t>(TextureSlot::Normal)];
  generateTangents(storage, normalSet);
  return storage;
}

GpuScene::Piece GpuScene::uploadPiece(Mesh mesh, const std::vector<int>& palette, bool tangents,
                                     const std::vector<DetailLevel>& levels) {
  Piece piece;
  const std::vector<float> interleaved = interleave(mesh);
  piece.vertices = arrayBuffer(interleaved.data(), interleaved.size() * sizeof(float));
  // The full index list, then each coarser level's, in one buffer.
  std::vector<std::uint32_t> indices = mesh.indices;
  piece.indexCount = static_cast<GLsizei>(mesh.indices.size());
  const size_t indexBytes = mesh.positions.size() <= 65536 ? 2 : 4;
  for (const DetailLevel& level : levels) {
    piece.levels.push_back({static_cast<GLsizei>(level.indices.size()), indices.size() * indexBytes, level.error});
    indices.insert(indices.end(), level.indices.begin(), level.indices.end());
  }
  piece.indices = gl::BufferHandle::create();
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, piece.indices.id());
  if (indexBytes == 2) {
    const std::vector<std::uint16_t> shorts(indices.begin(), indices.end());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(shorts.size() * 2), shorts.data(), GL_STATIC_DRAW);
    piece.indexType = GL_UNSIGNED_SHORT;
  } else {
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * 4), indices.data(),
                 GL_STATIC_DRAW);
    piece.indexType = GL_UNSIGNED_INT;
  }
  if (mesh.skinned()) {
    std::vector<float> skin;
    skin.reserve(mesh.joints.size() * 8);
    for (size_t v = 0; v < mesh.joints.size(); ++v) {
      const glm::vec4 j(mesh.joints[v]);
      const glm::vec4& w = mesh.weights[v];
      skin.insert(skin.end(), {j.x, j.y, j.z, j.w, w.x, w.y, w.z, w.w});
    }
    piece.skinAttributes = arrayBuffer(skin.data(), skin.size() * sizeof(float));
  }
  for (const MorphTarget& target : mesh.morphTargets) {
    piece.morphPositions.push_back(vec3Buffer(target.positions));
    piece.morphNormals.push_back(target.normals.empty() ? gl::BufferHandle() : vec3Buffer(target.normals));
    piece.morphTangents.push_back(target.tangents.empty() || !tangents ? gl::BufferHandle()
                                                                        : vec3Buffer(target.tangents));
  }
  if (tangents) piece.tangents = arrayBuffer(mesh.tangents.data(), mesh.tangents.size() * sizeof(glm::vec4));
  if (!mesh.colors.empty()) piece.colors = arrayBuffer(mesh.colors.data(), mesh.colors.size() * sizeof(glm::vec4));
  piece.palette = palette;
  if (mesh.skinned() || !mesh.morphTargets.empty()) piece.source = std::move(mesh);
  return piece;
}

void GpuScene::placeInstances(const Scene& scene, const std::vector<MeshPieces>& meshPieces) {
  for (const Instance& instance : scene.instances) {
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    const MeshPieces& placed = meshPieces[static_cast<size_t>(instance.mesh)];
    InstanceGpu gpu;
    gpu.world = gpu.previousWorld = instance.world;
    Bounds local;
    for (const glm::vec3& p : mesh.positions) local.add(p);
    gpu.localCentre = local.empty() ? glm::vec3(0.0f) : local.center();
    gpu.localMin = local.empty() ? glm::vec3(0.0f) : local.min;
    gpu.localMax = local.empty() ? glm::vec3(0.0f) : local.max;
    gpu.localRadius = 0.5f * glm::length(gpu.localMax - gpu.localMin);
    gpu.restCentre = gpu.centre = glm::vec3(instance.world * glm::vec4(gpu.localCentre, 1.0f));
    gpu.material = mesh.material >= 0 ? mesh.material : static_cast<int>(materials_.size()) - 1;
    gpu.firstPiece = placed.first;
    gpu.pieceCount = placed.count;
    gpu.skin = instance.skin >= 0 && mesh.skinned() ? instance.skin : -1;
    gpu.cpuSkinned = gpu.skin >= 0 && placed.cpuSkinned;
    gpu.morphed = !mesh.morphTargets.empty();
    gpu.transparent = materials_[static_cast<size_t>(gpu.material)].transparent;
    instances_.push_back(std::move(gpu));
  }
}

void GpuScene::chooseDetail(const glm::mat4& view, const glm::mat4& projection, int heightPixels,
                            float maxPixelError) {
  // Pixels per unit of length at clip w = 1: the projection's vertical scale times half the frame's height.
  const float pixelsPerUnit = std::abs(projection[1][1]) * 0.5f * static_cast<float>(heightPixels);
  for (InstanceGpu& instance : instances_) {
    instance.detail = 0;
    if (!(maxPixelError > 0.0f) || instance.pieceCount != 1) continue;
    const Piece& piece = pieces_[static_cast<size_t>(instance.firstPiece)];
    if (piece.levels.empty()) continue;
    const glm::mat3 linear(instance.world);
    const float scale = std::max({glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2])});
    const glm::vec4 centre = view * instance.world * glm::vec4(instance.localCentre, 1.0f);
    // Clip w at the bounds' nearest point along the view axis: its distance in front of the eye (w = -z) in a
    // perspective projection, 1 in an orthographic one (glm is column-major: projection[column][row]).
    const float w = projection[2][3] * (centre.z + scale * instance.localRadius) + projection[3][3];
    if (!(w > 0.0f)) continue;
    const float pixelsPerMeshUnit = scale * pixelsPerUnit / w;
    // The levels' errors grow level by level (scene/MeshDetail.h): the coarsest within the bound is the last one.
    for (size_t level = 0; level < piece.levels.size(); ++level) {
      if (piece.levels[level].error * pixelsPerMeshUnit > maxPixelError) break;
      instance.detail = static_cast<int>(level) + 1;
    }
  }
}

void GpuScene::cullToView(const glm::mat4& viewProjection) {
  for (InstanceGpu& instance : instances_)
    instance.inView = !withinRestBounds(instance) ||
                      !Bounds{instance.localMin, instance.localMax}.outsideClip(viewProjection * instance.world);
  for (StaticBatch& batch : batches_) {
    const std::vector<Piece::Member>& members = pieces_[static_cast<size_t>(batch.drawn.firstPiece)].members;
    batch.drawn.inView = std::any_of(members.begin(), members.end(), [&](const Piece::Member& member) {
      return instances_[static_cast<size_t>(member.instance)].inView;
    });
  }
}

void GpuScene::drawWholeScene() {
  for (InstanceGpu& instance : instances_) instance.inView = true;
  for (StaticBatch& batch : batches_) batch.drawn.inView = true;
}

bool GpuScene::usesUint32Indices() const {
  return std::any_of(pieces_.begin(), pieces_.end(), [](const Piece& p) { return p.indexType == GL_UNSIGNED_INT; });
}

bool GpuScene::anyMoving() const {
  return std::any_of(instances_.begin(), instances_.end(), [](const InstanceGpu& i) { return i.moving; });
}

int GpuScene::morphTargetSlots(int perTarget, int otherAttributes) const {
  return std::clamp((limits_.attributes - otherAttributes) / std::max(perTarget, 1), 0, VertexKind::kMaxMorphTargets);
}

GeometryUniforms::GeometryUniforms(const gl::Program& program)
    : instanceTransforms(program.uniform("u_instanceTransforms[0]")),
      baseColorFactor(program.optionalUniform("u_baseColorFactor")),
      baseColorTexture(program.optionalUniform("u_baseColorTexture")),
      alphaCutoff(program.optionalUniform("u_alphaCutoff")),
      baseColorSrgb(program.optionalUniform("u_baseColorSrgb")),
      metallicRoughness(program.optionalUniform("u_metallicRoughness")),
      emissive(program.optionalUniform("u_emissive")),
      uvTransforms(program.optionalUniform("u_uvTransforms[0]")),
      uvSets(program.optionalUniform("u_uvSets")),
      specular(program.optionalUniform("u_specular")),
      clearcoat(program.optionalUniform("u_clearcoat")),
      clearcoatRoughness(program.optionalUniform("u_clearcoatRoughness")),
      transmission(program.optionalUniform("u_transmission")),
      transmissionIor(program.optionalUniform("u_transmissionIor")),
      pbrTextures{program.optionalUniform("u_metallicRoughnessTexture"), program.optionalUniform("u_normalTexture"),
                  program.optionalUniform("u_occlusionTexture"), program.optionalUniform("u_emissiveTexture")},
      joints(program.optionalUniform("u_joints[0]")),
      previousJoints(program.optionalUniform("u_previousJoints[0]")),
      jointTexture(program.optionalUniform("u_jointTexture")),
      jointTextureSize(program.optionalUniform("u_jointTextureSize")),
      morphWeights(program.optionalUniform("u_morphWeights")),
      previousMorphWeights(program.optionalUniform("u_previousMorphWeights")),
      previousModel(program.optionalUniform("u_previousModel")),
      jointsAttribute(glGetAttribLocation(program.id(), "a_joints")),
      weightsAttribute(glGetAttribLocation(program.id(), "a_weights")),
      previousPositionAttribute(glGetAttribLocation(program.id(), "a_previousPosition")),
      tangentAttribute(glGetAttribLocation(program.id(), "a_tangent")),
      colorAttribute(glGetAttribLocation(program.id(), "a_color")) {
  for (int t = 0; t < VertexKind::kMaxMorphTargets; ++t) {
    morphPositionAttribute[t] = glGetAttribLocation(program.id(), ("a_morphPosition" + std::to_string(t)).c_str());
    morphNormalAttribute[t] = glGetAttribLocation(program.id(), ("a_morphNormal" + std::to_string(t)).c_str());
    morphTangentAttribute[t] = glGetAttribLocation(program.id(), ("a_morphTangent" + std::to_string(t)).c_str());
  }
}

void GpuScene::setPose(const ScenePose& current, const ScenePose& previous) {
  lines_.setPose(current);
  for (PunctualLight& light : lights_)
    if (light.node >= 0 && static_cast<size_t>(light.node) < current.nodeWorld.size())
      light.world = current.nodeWorld[static_cast<size_t>(light.node)];
  const std::vector<bool> skinMoving = poseSkins(current, previous);
  for (size_t i = 0; i < instances_.size(); ++i) {
    InstanceGpu& instance = instances_[i];
    instance.world = current.instanceWorld[i];
    instance.previousWorld = previous.instanceWorld[i];
    // Only for the drawing order: a skinned instance keeps its rest centre.
    instance.centre = instance.skin >= 0 ? instance.restCentre
                                         : glm::vec3(instance.world * glm::vec4(instance.localCentre, 1.0f));
    instance.weights = instance.morphed ? current.instanceWeights[i] : std::vector<float>{};
    instance.previousWeights = instance.morphed ? previous.instanceWeights[i] : std::vector<float>{};
    instance.moving = instance.world != instance.previousWorld ||
                      (instance.skin >= 0 && skinMoving[static_cast<size_t>(instance.skin)]) ||
                      instance.weights != instance.previousWeights;
    const bool fitsGpu = chooseGpuMorphTargets(instance);
    instance.cpuDeformed = instance.cpuSkinned || !fitsGpu;
    if (instance.cpuDeformed) uploadCpuDeformed(instance, current, previous, i);
    else instance.deformed.clear();
  }
  for (StaticBatch& batch : batches_) {
    const Piece& piece = pieces_[static_cast<size_t>(batch.drawn.firstPiece)];
    batch.intact = std::all_of(piece.members.begin(), piece.members.end(), [&](const Piece::Member& member) {
      const InstanceGpu& instance = instances_[static_cast<size_t>(member.instance)];
      return instance.world == member.world && instance.previousWorld == member.world;
    });
  }
}

// Morph targets on the GPU: those with a weight now or in the previous frame, heaviest first, if they fit the
// attributes left beside the vertex stage's others. False where they do not (the CPU morphs the draw instead).
bool GpuScene::chooseGpuMorphTargets(InstanceGpu& instance) const {
  instance.gpuTargets.clear();
  if (!instance.morphed) return true;
  const Piece& first = pieces_[static_cast<size_t>(instance.firstPiece)];
  std::vector<int> needed;
  bool normals = false, tangents = false;
  for (size_t t = 0; t < instance.weights.size(); ++t)
    if (instance.weights[t] != 0.0f || instance.previousWeights[t] != 0.0f) {
      needed.push_back(static_cast<int>(t));
      normals = normals || first.morphNormals[t].id() != 0;
      tangents = tangents || first.morphTangents[t].id() != 0;
    }
  const auto heaviness = [&](int t) {
    return std::max(std::abs(instance.weights[static_cast<size_t>(t)]),
                    std::abs(instance.previousWeights[static_cast<size_t>(t)]));
  };
  std::stable_sort(needed.begin(), needed.end(), [&](int a, int b) { return heaviness(a) > heaviness(b); });
  // Beside the targets: position, normal, texture coordinates, and the tangent, colours and skin where drawn.
  const int others = 3 + (first.tangents ? 1 : 0) + (first.colors ? 1 : 0) +
                     (instance.skin >= 0 && !instance.cpuSkinned ? 2 : 0);
  if (static_cast<int>(needed.size()) > morphTargetSlots(1 + (normals ? 1 : 0) + (tangents ? 1 : 0), others))
    return false;
  instance.gpuTargets = needed;
  return true;
}

void GpuScene::DrawState::attribute(GLint location, GLuint buffer, GLint size, GLsizei stride, size_t offset) {
  if (location < 0) return;
  const auto slot = static_cast<GLuint>(location);
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glEnableVertexAttribArray(slot);
  glVertexAttribPointer(slot, size, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset));
  extraAttributes.push_back(slot);
}

// The opaque layer: opaque before masked, each front to back: the view-space z of the bounds' centre, nearest
// (largest) first.
std::vector<const GpuScene::InstanceGpu*> GpuScene::drawOrder(const glm::mat4& view, const DrawOptions& options) const {
  std::vector<std::pair<float, const InstanceGpu*>> keyed;
  keyed.reserve(instances_.size() + batches_.size());
  auto add = [&](const InstanceGpu& instance) {
    if (!instance.inView || instance.transparent || (options.onlyMoving && !instance.moving)) return;
    const bool masked = materials_[static_cast<size_t>(instance.material)].alphaCutoff >= 0.0f;
    keyed.emplace_back((masked ? 1e30f : 0.0f) - (view * glm::vec4(instance.centre, 1.0f)).z, &instance);
  };
  for (const InstanceGpu& instance : instances_)
    if (instance.batch < 0 || !batches_[static_cast<size_t>(instance.batch)].intact) add(instance);
  for (const StaticBatch& batch : batches_)
    if (batch.intact) add(batch.drawn);
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<const InstanceGpu*> order;
  order.reserve(keyed.size());
  for (const auto& entry : keyed) order.push_back(entry.second);
  return order;
}

void GpuScene::draw(const glm::mat4& view, const ProgramChoice& choose, const DrawOptions& options) const {
  counts_ = {};
  DrawState state(choose);
  glActiveTexture(GL_TEXTURE0);
  for (const InstanceGpu* instance : drawOrder(view, options)) {
    const MaterialGpu& material = materials_[static_cast<size_t>(instance->material)];
    const int culling = material.doubleSided || options.bothFaces ? 0 : 1;
    if (culling != state.culling) {
      if (culling) glEnable(GL_CULL_FACE);
      else glDisable(GL_CULL_FACE);
      state.culling = culling;
    }
    drawInstance(*instance, view, state);
  }
  restoreAfterDraw(state);
}

void GpuScene::drawInstance(const InstanceGpu& instance, const glm::mat4& view, DrawState& state) const {
  const MaterialGpu& material = materials_[static_cast<size_t>(instance.material)];
  if (state.texturesOf != instance.material) {
    bindMaterialTextures(material, state);
    state.texturesOf = instance.material;
  }
  const glm::mat4 modelView = view * instance.world;
  // A mirroring transform flips the winding; keep "front" meaning the outside. A skinned vertex's transform is its
  // joints' (the instance's is the view alone): a skin whose joints mostly mirror flips it. (One that mirrors some
  // joints and not others shows the other part's faces from inside: glTF leaves that winding undefined.)
  const bool mirrored = glm::determinant(glm::mat3(modelView)) < 0.0f;
  const bool skinMirrored = instance.skin >= 0 && skins_[static_cast<size_t>(instance.skin)].mirrored;
  const GLenum frontFace = mirrored != skinMirrored ? GL_CW : GL_CCW;
  if (frontFace != state.frontFace) {
    glFrontFace(frontFace);
    state.frontFace = frontFace;
  }
  for (int p = instance.firstPiece; p < instance.firstPiece + instance.pieceCount; ++p)
    drawPiece(instance, p, material, modelView, state);
}

// The pixels an instance covers at most: its mesh's bounds projected (a skinned or morphed instance, whose pose may
// leave its rest bounds, and one reaching behind the eye cover the frame), widened by a pixel for rasterisation.
glm::ivec4 GpuScene::screenRect(const InstanceGpu& instance, const glm::mat4& viewProjection, glm::ivec2 size) const {
  const glm::ivec4 frame(0, 0, size.x, size.y);
  if (!withinRestBounds(instance)) return frame;
  const Bounds bounds{instance.localMin, instance.localMax};
  glm::vec2 low(1e30f), high(-1e30f);
  for (const glm::vec4& clip : bounds.clipCorners(viewProjection * instance.world)) {
    if (clip.w <= 1e-6f) return frame;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    low = glm::min(low, ndc);
    high = glm::max(high, ndc);
  }
  const glm::vec2 half = glm::vec2(size) * 0.5f;
  const glm::ivec2 from = glm::clamp(glm::ivec2(glm::floor((low + 1.0f) * half)) - 1, glm::ivec2(0), size);
  const glm::ivec2 to = glm::clamp(glm::ivec2(glm::ceil((high + 1.0f) * half)) + 1, glm::ivec2(0), size);
  return {from.x, from.y, std::max(0, to.x - from.x), std::max(0, to.y - from.y)};
}

glm::ivec4 GpuScene::coveredRect(const glm::mat4& viewProjection, glm::ivec2 size) const {
  glm::ivec2 from(size), to(0);
  for (const InstanceGpu& instance : instances_) {
    const glm::ivec4 rect = screenRect(instance, viewProjection, size);
    if (rect.z <= 0 || rect.w <= 0) continue;
    from = glm::min(from, glm::ivec2(rect.x, rect.y));
    to = glm::max(to, glm::ivec2(rect.x + rect.z, rect.y + rect.w));
  }
  if (to.x <= from.x || to.y <= from.y) return glm::ivec4(0);
  return {from.x, from.y, to.x - from.x, to.y - from.y};
}

std::vector<GpuScene::TransparentBatch> GpuScene::transparentBatches(const glm::mat4& view,
                                                                     const glm::mat4& projection,
                                                                     glm::ivec2 size) const {
  // Back to front: the view-space z of the bounds' centre, farthest (most negative) first.
  std::vector<std::pair<float, int>> order;
  for (size_t i = 0; i < instances_.size(); ++i)
    if (instances_[i].transparent && instances_[i].inView)
      order.emplace_back((view * glm::vec4(instances_[i].centre, 1.0f)).z, static_cast<int>(i));
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const glm::mat4 viewProjection = projection * view;
  auto overlap = [](const glm::ivec4& a, const glm::ivec4& b) {
    return a.x < b.x + b.z && b.x < a.x + a.z && a.y < b.y + b.w && b.y < a.y + a.w;
  };
  std::vector<TransparentBatch> batches;
  std::vector<glm::ivec4> batchRects;  // the rectangles of the last batch's draws
  auto add = [&](const TransparentDraw& draw, const glm::ivec4& rect) {
    const bool fits = !batches.empty() && std::none_of(batchRects.begin(), batchRects.end(),
                                                       [&](const glm::ivec4& r) { return overlap(r, rect); });
    if (!fits) {
      batches.emplace_back();
      batchRects.clear();
      batches.back().rect = rect;
    } else {
      glm::ivec4& u = batches.back().rect;
      const glm::ivec2 from = glm::min(glm::ivec2(u.x, u.y), glm::ivec2(rect.x, rect.y));
      const glm::ivec2 to = glm::max(glm::ivec2(u.x + u.z, u.y + u.w), glm::ivec2(rect.x + rect.z, rect.y + rect.w));
      u = glm::ivec4(from, to - from);
    }
    batchRects.push_back(rect);
    batches.back().draws.push_back(draw);
  };
  for (const auto& [z, index] : order) {
    const InstanceGpu& instance = instances_[static_cast<size_t>(index)];
    const glm::ivec4 rect = screenRect(instance, viewProjection, size);
    if (rect.z <= 0 || rect.w <= 0) continue;
    // A double-sided material's back faces first: they lie behind its front faces (rect overlaps itself, so the
    // front faces go to the next batch and see the back faces behind them).
    if (materials_[static_cast<size_t>(instance.material)].doubleSided) add({index, GL_FRONT}, rect);
    add({index, GL_BACK}, rect);
  }
  return batches;
}

void GpuScene::drawTransparent(const glm::mat4& view, const ProgramChoice& choose,
                               const TransparentBatch& batch) const {
  counts_ = {};
  DrawState state(choose);
  glActiveTexture(GL_TEXTURE0);
  glEnable(GL_CULL_FACE);
  for (const TransparentDraw& draw : batch.draws) {
    glCullFace(draw.cullFace);
    drawInstance(instances_[static_cast<size_t>(draw.instance)], view, state);
  }
  glCullFace(GL_BACK);
  restoreAfterDraw(state);
}

void GpuScene::bindMaterialTextures(const MaterialGpu& material, DrawState& state) const {
  if (material.texture >= 0) glBindTexture(GL_TEXTURE_2D, textures_[static_cast<size_t>(material.texture)].id());
  if (!material.pbr) return;
  for (size_t slot = 0; slot < material.pbrTextures.size(); ++slot) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + TextureUnits::kPbr[slot]));
    const int texture = material.pbrTextures[slot];
    glBindTexture(GL_TEXTURE_2D, texture >= 0  ? textures_[static_cast<size_t>(texture)].id()
                                 : slot == 1 ? neutralNormal_.id()
                                             : neutralWhite_.id());
  }
  glActiveTexture(GL_TEXTURE0);
  state.pbrTexturesBound = true;
}

void GpuScene::drawIndices(const Piece& piece, int detail) const {
  if (!piece.members.empty()) {
    drawBatchMembers(piece);
    return;
  }
  const Piece::Level full{piece.indexCount, 0, 0.0f};
  const Piece::Level& level = detail > 0 ? piece.levels[static_cast<size_t>(detail - 1)] : full;
  glDrawElements(GL_TRIANGLES, level.indexCount, piece.indexType, reinterpret_cast<const void*>(level.offset));
  ++counts_.drawCalls;
  counts_.triangles += level.indexCount / 3;
  if (detail > 0) ++counts_.coarser;
}

void GpuScene::drawPiece(const InstanceGpu& instance, int p, const MaterialGpu& material, const glm::mat4& modelView,
                         DrawState& state) const {
  using gl::Program;
  const Piece& piece = pieces_[static_cast<size_t>(p)];
  const MaterialKind materialKind = material.kind();
  const VertexKind vertexKind = this->vertexKind(instance, piece);
  const bool newProgram =
      !state.uniforms || !(materialKind == state.programMaterial) || !(vertexKind == state.programVertex);
  if (newProgram) {
    // The program's per-draw uniforms, resolved on its first draw (programs outlive the scene's draws: they belong
    // to the Renderer).
    const gl::Program& program = state.choose(materialKind, vertexKind);
    if (withheld_) {
      state.uniforms = &state.withheldUniforms.emplace(program);
    } else {
      auto found = geometryUniforms_.find(&program);
      if (found == geometryUniforms_.end())
        found = geometryUniforms_.emplace(&program, GeometryUniforms(program)).first;
      state.uniforms = &found->second;
    }
    state.programMaterial = materialKind;
    state.programVertex = vertexKind;
    state.texturesOf = state.uniformsOf = -1;
    Program::set(state.uniforms->baseColorTexture, TextureUnits::kBaseColor);
    Program::set(state.uniforms->jointTexture, TextureUnits::kJoints);
    for (size_t slot = 0; slot < 4; ++slot) Program::set(state.uniforms->pbrTextures[slot], TextureUnits::kPbr[slot]);
  }
  if (newProgram || p == instance.firstPiece) setInstanceUniforms(instance, material, modelView, vertexKind, state);
  ++counts_.draws;
  for (const Piece::Member& member : piece.members)
    counts_.batchedInstances += instances_[static_cast<size_t>(member.instance)].inView ? 1 : 0;
  if (vertexKind.cpuDeformed) ++counts_.cpuDeformed;
  if (vertexKind.morphTargets > 0) ++counts_.gpuMorphed;
  if (vertexKind.skinning != VertexKind::None) ++counts_.skinned;
  bindSkin(instance, piece, vertexKind, state);
  if (const GLuint vertexArray = pieceVertexArray(instance, p, vertexKind, state)) {
    bindVertexArray(vertexArray, state);
    ++counts_.vertexArrays;
    drawIndices(piece, instance.detail);
    return;
  }
  bindVertexArray(0, state);
  if (!state.defaultStreams) {
    for (GLuint slot : {gl::kAttribPosition, gl::kAttribNormal, gl::kAttribTexcoord}) glEnableVertexAttribArray(slot);
    state.defaultStreams = true;
  }
  bindVertices(instance, p, vertexKind, state);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, piece.indices.id());
  if (!withheld_) drawIndices(piece, instance.detail);
  for (GLuint slot : state.extraAttributes) glDisableVertexAttribArray(slot);
  state.extraAttributes.clear();
}

namespace {
// The attribute locations a piece's object depends on beyond slots 0..2 (fixed by gl::Program), each + 1 in a byte
// (0: not bound): tangents, colours, joints, weights.
std::uint32_t vertexArrayKey(GLint tangent, GLint color, GLint joints, GLint weights) {
  auto byte = [](GLint location) { return static_cast<std::uint32_t>(location + 1) & 0xFFu; };
  return byte(tangent) | byte(color) << 8 | byte(joints) << 16 | byte(weights) << 24;
}
}  // namespace

GLuint GpuScene::pieceVertexArray(const InstanceGpu& instance, int p, const VertexKind& vertexKind,
                                  DrawState& state) const {
  // A withheld draw's program may be a stand-in with other attribute locations, and GPU-morphed or CPU-deformed
  // streams change per frame: those set their streams per draw.
  if (!vertexArrays_ || withheld_ || vertexKind.cpuDeformed || vertexKind.morphTargets > 0) return 0;
  const Piece& piece = pieces_[static_cast<size_t>(p)];
  const GeometryUniforms& uniforms = *state.uniforms;
  const bool skinned = vertexKind.skinning != VertexKind::None;
  const GLint tangent = piece.tangents ? uniforms.tangentAttribute : -1;
  const GLint color = piece.colors ? uniforms.colorAttribute : -1;
  const GLint joints = skinned ? uniforms.jointsAttribute : -1, weights = skinned ? uniforms.weightsAttribute : -1;
  // Locations past a byte do not occur (GL_MAX_VERTEX_ATTRIBS is 16 on the devices seen); such a draw sets its
  // streams itself.
  for (GLint location : {tangent, color, joints, weights})
    if (location > 254) return 0;
  const std::uint32_t key = vertexArrayKey(tangent, color, joints, weights);
  if (pieceVertexArrays_.size() != pieces_.size()) pieceVertexArrays_.resize(pieces_.size());
  auto& made = pieceVertexArrays_[static_cast<size_t>(p)];
  for (const auto& [k, vertexArray] : made)
    if (k == key) return vertexArray.id();
  // The object records what bindVertices and the element buffer's binding set for this draw (the attribute arrays
  // enabled, their pointers into the piece's buffers, the element buffer); the context's default object is left as
  // it was, and the arrays bindVertices enabled are the object's to keep, not the default object's to disable.
  gl::VertexArrayHandle vertexArray = gl::VertexArrayHandle::create();
  glBindVertexArrayOES(vertexArray.id());
  for (GLuint slot : {gl::kAttribPosition, gl::kAttribNormal, gl::kAttribTexcoord}) glEnableVertexAttribArray(slot);
  bindVertices(instance, p, vertexKind, state);
  state.extraAttributes.clear();
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, piece.indices.id());
  glBindVertexArrayOES(state.vertexArray);
  made.emplace_back(key, std::move(vertexArray));
  return made.back().second.id();
}

void GpuScene::bindVertexArray(GLuint vertexArray, DrawState& state) const {
  if (vertexArray == state.vertexArray) return;
  glBindVertexArrayOES(vertexArray);
  state.vertexArray = vertexArray;
}

void GpuScene::setInstanceUniforms(const InstanceGpu& instance, const MaterialGpu& material,
                                   const glm::mat4& modelView, const VertexKind& vertexKind,
                                   DrawState& state) const {
  using gl::Program;
  const GeometryUniforms& uniforms = *state.uniforms;
  // One call for both (geometry.vert): a program whose fragment stage reads no normal has a shorter active array,
  // and GL ignores the values past its end.
  const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(modelView));
  const glm::vec4 transforms[7] = {modelView[0],
                                   modelView[1],
                                   modelView[2],
                                   modelView[3],
                                   glm::vec4(normalMatrix[0], 0.0f),
                                   glm::vec4(normalMatrix[1], 0.0f),
                                   glm::vec4(normalMatrix[2], 0.0f)};
  glUniform4fv(uniforms.instanceTransforms, 7, &transforms[0].x);
  Program::set(uniforms.previousModel, instance.previousWorld);
  if (vertexKind.morphTargets > 0) {
    glm::vec4 now(0.0f), before(0.0f);
    for (size_t k = 0; k < instance.gpuTargets.size(); ++k) {
      const auto t = static_cast<size_t>(instance.gpuTargets[k]);
      now[static_cast<glm::length_t>(k)] = instance.weights[t];
      before[static_cast<glm::length_t>(k)] = instance.previousWeights[t];
    }
    Program::set(uniforms.morphWeights, now);
    Program::set(uniforms.previousMorphWeights, before);
  }
  if (state.uniformsOf == instance.material) return;  // the program holds this material's values already
  state.uniformsOf = instance.material;
  Program::set(uniforms.baseColorFactor, material.baseColorFactor);
  Program::set(uniforms.baseColorSrgb, material.baseColorSrgb);
  Program::set(uniforms.alphaCutoff, material.alphaCutoff);
  Program::set(uniforms.metallicRoughness, material.metallicRoughness);
  Program::set(uniforms.emissive, material.emissive);
  if (uniforms.uvTransforms >= 0) glUniform3fv(uniforms.uvTransforms, 2 * kTextureSlots, &material.uvRows[0].x);
  Program::set(uniforms.uvSets, material.uvSets);
  Program::set(uniforms.specular, material.specular);
  Program::set(uniforms.clearcoat, material.clearcoat);
  Program::set(uniforms.clearcoatRoughness, material.clearcoatRoughness);
  Program::set(uniforms.transmission, material.transmissionFactor);
  Program::set(uniforms.transmissionIor, material.transmissionIor);
}

// The piece's vertex streams: its own buffers, or the CPU-deformed ones (with the previous positions beside them);
// tangents, skin attributes and the morph targets chosen this frame.
void GpuScene::bindVertices(const InstanceGpu& instance, int p, const VertexKind& vertexKind,
                            DrawState& state) const {
  const Piece& piece = pieces_[static_cast<size_t>(p)];
  const GeometryUniforms& uniforms = *state.uniforms;
  const bool deformed = vertexKind.cpuDeformed;
  const GLsizei stride = GpuScene::kVertexFloats * static_cast<GLsizei>(sizeof(float));
  glBindBuffer(GL_ARRAY_BUFFER, piece.vertices.id());
  glVertexAttribPointer(gl::kAttribTexcoord, 4, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(6 * sizeof(float)));
  if (deformed) {
    // Position, normal, previous position and tangent as the CPU deformed them this frame.
    const GLuint stream = instance.deformed[static_cast<size_t>(p - instance.firstPiece)].id();
    const GLsizei deformedStride = kDeformedFloats * static_cast<GLsizei>(sizeof(float));
    glBindBuffer(GL_ARRAY_BUFFER, stream);
    glVertexAttribPointer(gl::kAttribPosition, 3, GL_FLOAT, GL_FALSE, deformedStride, nullptr);
    glVertexAttribPointer(gl::kAttribNormal, 3, GL_FLOAT, GL_FALSE, deformedStride,
                          reinterpret_cast<const void*>(3 * sizeof(float)));
    state.attribute(uniforms.previousPositionAttribute, stream, 3, deformedStride, 6 * sizeof(float));
    if (piece.tangents) state.attribute(uniforms.tangentAttribute, stream, 4, deformedStride, 9 * sizeof(float));
  } else {
    glVertexAttribPointer(gl::kAttribPosition, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    glVertexAttribPointer(gl::kAttribNormal, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(3 * sizeof(float)));
    if (piece.tangents) state.attribute(uniforms.tangentAttribute, piece.tangents.id(), 4, 0, 0);
  }
  if (piece.colors) state.attribute(uniforms.colorAttribute, piece.colors.id(), 4, 0, 0);
  if (vertexKind.skinning != VertexKind::None) {
    const GLsizei skinStride = 8 * sizeof(float);
    state.attribute(uniforms.jointsAttribute, piece.skinAttributes.id(), 4, skinStride, 0);
    state.attribute(uniforms.weightsAttribute, piece.skinAttributes.id(), 4, skinStride, 4 * sizeof(float));
  }
  // A target without normal or tangent deltas beside one with: its attribute holds zero (no delta).
  auto delta = [&](GLint location, const gl::BufferHandle& buffer) {
    if (buffer) state.attribute(location, buffer.id(), 3, 0, 0);
    else if (location >= 0) glVertexAttrib3f(static_cast<GLuint>(location), 0.0f, 0.0f, 0.0f);
  };
  for (size_t k = 0; k < static_cast<size_t>(vertexKind.morphTargets); ++k) {
    const auto t = static_cast<size_t>(instance.gpuTargets[k]);
    state.attribute(uniforms.morphPositionAttribute[k], piece.morphPositions[t].id(), 3, 0, 0);
    delta(uniforms.morphNormalAttribute[k], piece.morphNormals[t]);
    delta(uniforms.morphTangentAttribute[k], piece.morphTangents[t]);
  }
}

void GpuScene::restoreAfterDraw(const DrawState& state) const {
  // The default object again before the default streams' state is reset: a bound object must not leak into the
  // next pass (the fullscreen triangle and the lines set their streams on the default object).
  if (state.vertexArray != 0) glBindVertexArrayOES(0);
  if (state.defaultStreams)
    for (GLuint slot : {gl::kAttribPosition, gl::kAttribNormal, gl::kAttribTexcoord}) glDisableVertexAttribArray(slot);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  if (state.jointTextureBound) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + TextureUnits::kJoints));
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
  }
  if (state.pbrTexturesBound) {
    for (int unit : TextureUnits::kPbr) {
      glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
      glBindTexture(GL_TEXTURE_2D, 0);
    }
    glActiveTexture(GL_TEXTURE0);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
}

}  // namespace obscura
