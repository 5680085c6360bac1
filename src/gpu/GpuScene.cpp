#include "gpu/GpuScene.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>

#include "base/Error.h"
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

// Vertex uniform vectors the palette cannot have: the matrices of geometry.vert (model-view, projection, normal
// matrix, the velocity's unjittered projection, previous model and previous view-projection: 22 vectors), the morph
// weights (2), and room for the driver's packing and the uniforms a compiler adds.
constexpr int kReservedUniformVectors = 32;
// Joints per palette where uniforms are plenty: beyond it, uploading the palette per draw costs more than it saves.
constexpr int kMaxPaletteJoints = 128;
// GL_RGBA32F: a desktop context needs the sized format to keep floats; GLES 2 / WebGL 1 with OES_texture_float take
// GL_RGBA with type GL_FLOAT.
constexpr GLenum kRgba32f = 0x8814;

constexpr int kDeformedFloats = 11;  // CPU-deformed vertices: position, normal, texcoord, previous position

std::vector<float> interleave(const Mesh& part) {
  std::vector<float> interleaved;
  interleaved.reserve(part.positions.size() * 8);
  for (size_t v = 0; v < part.positions.size(); ++v) {
    const glm::vec2 uv = part.texcoords.empty() ? glm::vec2(0.0f) : part.texcoords[v];
    interleaved.insert(interleaved.end(), {part.positions[v].x, part.positions[v].y, part.positions[v].z,
                                           part.normals[v].x, part.normals[v].y, part.normals[v].z, uv.x, uv.y});
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

// Three rows of an affine matrix (glm is column-major: m[column][row]): the layout of the palette and the texture.
void appendRows(std::vector<float>& out, const glm::mat4& m) {
  for (int row = 0; row < 3; ++row) out.insert(out.end(), {m[0][row], m[1][row], m[2][row], m[3][row]});
}

}  // namespace

const char* skinningPathName(SkinningPath path) {
  switch (path) {
    case SkinningPath::Uniforms: return "uniforms";
    case SkinningPath::Texture: return "texture";
    case SkinningPath::Cpu: return "cpu";
  }
  return "?";
}

GpuScene::GpuScene(const Scene& scene, const gl::GlCaps& caps, const Options& options) {
  const bool uint32 = caps.elementIndexUint && options.allowUint32Indices;
  desktopGl_ = caps.desktopGl;
  // The caps carry the limits a test simulates (RendererOptions::simulateVertexLimits, applied by the Renderer).
  limits_ = {caps.maxVertexUniformVectors, caps.maxVertexAttribs, caps.maxVertexTextureImageUnits};

  // The skinning path: the one asked for where the context can take it, else the best it can.
  // The joint texture needs a ninth texture unit (gpu/TextureUnits.h): the lighting's fragment stage may use eight.
  const bool textureOk = limits_.textureUnits > 0 && caps.textureFloat && TextureUnits::jointTextureFits(caps);
  const int palette = std::min(kMaxPaletteJoints, (limits_.uniformVectors - kReservedUniformVectors) / 6);
  const bool uniformsOk = palette >= 12;  // a triangle may need 3 vertices x 4 joints
  const SkinningPath wanted = options.skinning.value_or(SkinningPath::Texture);
  if (wanted == SkinningPath::Cpu) skinningPath_ = SkinningPath::Cpu;
  else if (wanted == SkinningPath::Texture && textureOk) skinningPath_ = SkinningPath::Texture;
  else skinningPath_ = uniformsOk ? SkinningPath::Uniforms : SkinningPath::Cpu;
  paletteSize_ = skinningPath_ == SkinningPath::Uniforms ? palette : 0;

  for (size_t t = 0; t < scene.textures.size(); ++t) {
    const Texture& texture = scene.textures[t];
    if (texture.image >= 0 && scene.images[static_cast<size_t>(texture.image)].width > 0)
      textures_.push_back(uploadTexture(scene.images[static_cast<size_t>(texture.image)], texture.sampler, caps));
    else
      textures_.emplace_back();
  }
  auto usable = [&](int texture) { return texture >= 0 && textures_[static_cast<size_t>(texture)] ? texture : -1; };
  for (const Material& m : scene.materials) {
    MaterialGpu gpu;
    gpu.baseColorFactor = m.baseColorFactor;
    gpu.texture = usable(m.baseColorTexture);
    gpu.alphaCutoff = m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : -1.0f;
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
    }
    materials_.push_back(gpu);
  }
  materials_.push_back(MaterialGpu{});  // the default material (Material{}: a white rough dielectric)
  // Neutral texels for the slots a PBR_TEXTURES material lacks: white (the factor alone) and the flat normal.
  const std::uint8_t white[4] = {255, 255, 255, 255}, flat[4] = {128, 128, 255, 255};
  neutralWhite_ = gl::Texture2D(1, 1, GL_NEAREST, white);
  neutralNormal_ = gl::Texture2D(1, 1, GL_NEAREST, flat);

  // Upload each mesh once (as one or more pieces), then point instances at the pieces.
  struct MeshPieces {
    int first = 0, count = 0;
    bool cpuSkinned = false;
  };
  std::vector<MeshPieces> meshPieces;
  for (const Mesh& source : scene.meshes) {
    // A mesh drawn with PBR textures needs tangents (the vertex stage's a_tangent): the file's, else generated.
    const bool pbr = source.material >= 0 && materials_[static_cast<size_t>(source.material)].pbr;
    Mesh withTangents;
    if (pbr && source.tangents.size() != source.positions.size()) {
      withTangents = source;
      generateTangents(withTangents);
    }
    const Mesh& mesh = withTangents.positions.empty() ? source : withTangents;
    MeshPieces placed;
    placed.first = static_cast<int>(pieces_.size());
    std::vector<PalettePiece> parts;
    if (mesh.skinned() && skinningPath_ == SkinningPath::Uniforms) parts = splitForJointPalette(mesh, paletteSize_);
    if (parts.empty()) parts.push_back({mesh, {}});
    placed.cpuSkinned = mesh.skinned() && skinningPath_ == SkinningPath::Cpu;
    for (const PalettePiece& part : parts) {
      for (Mesh& piece16 : uint32 ? std::vector<Mesh>{part.mesh} : splitForShortIndices(part.mesh)) {
        Piece piece;
        const std::vector<float> interleaved = interleave(piece16);
        piece.vertices = arrayBuffer(interleaved.data(), interleaved.size() * sizeof(float));
        piece.indices = gl::BufferHandle::create();
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, piece.indices.id());
        if (piece16.positions.size() <= 65536) {
          const std::vector<std::uint16_t> shorts(piece16.indices.begin(), piece16.indices.end());
          glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(shorts.size() * 2), shorts.data(),
                       GL_STATIC_DRAW);
          piece.indexType = GL_UNSIGNED_SHORT;
        } else {
          glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(piece16.indices.size() * 4),
                       piece16.indices.data(), GL_STATIC_DRAW);
          piece.indexType = GL_UNSIGNED_INT;
        }
        piece.indexCount = static_cast<GLsizei>(piece16.indices.size());
        if (piece16.skinned()) {
          std::vector<float> skin;
          skin.reserve(piece16.joints.size() * 8);
          for (size_t v = 0; v < piece16.joints.size(); ++v) {
            const glm::vec4 j(piece16.joints[v]);
            const glm::vec4& w = piece16.weights[v];
            skin.insert(skin.end(), {j.x, j.y, j.z, j.w, w.x, w.y, w.z, w.w});
          }
          piece.skinAttributes = arrayBuffer(skin.data(), skin.size() * sizeof(float));
        }
        for (const MorphTarget& target : piece16.morphTargets) {
          piece.morphPositions.push_back(vec3Buffer(target.positions));
          piece.morphNormals.push_back(target.normals.empty() ? gl::BufferHandle() : vec3Buffer(target.normals));
        }
        if (pbr) piece.tangents = arrayBuffer(piece16.tangents.data(), piece16.tangents.size() * sizeof(glm::vec4));
        piece.palette = part.palette;
        if (piece16.skinned() || !piece16.morphTargets.empty()) piece.source = std::move(piece16);
        pieces_.push_back(std::move(piece));
      }
    }
    placed.count = static_cast<int>(pieces_.size()) - placed.first;
    meshPieces.push_back(placed);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  lines_ = GpuLines(scene);

  skins_.resize(scene.skins.size());
  for (size_t s = 0; s < scene.skins.size(); ++s) {
    SkinGpu& skin = skins_[s];
    const size_t joints = std::max<size_t>(1, scene.skins[s].joints.size());
    skin.joints.assign(joints, glm::mat4(1.0f));
    skin.previousJoints = skin.joints;
    if (skinningPath_ != SkinningPath::Texture) continue;
    // Rows of this frame's palette, then the previous frame's, wrapped at the widest texture the context allows.
    const int texels = static_cast<int>(3 * joints);
    const int width = std::min(2 * texels, std::max(1, caps.maxTextureSize));
    const int height = (2 * texels + width - 1) / width;
    if (height > caps.maxTextureSize) throw InputError("a skin has too many joints for this context's textures");
    skin.textureSize = glm::vec3(width, height, texels);
    skin.texture = gl::TextureHandle::create();
    glBindTexture(GL_TEXTURE_2D, skin.texture.id());
    glTexImage2D(GL_TEXTURE_2D, 0, desktopGl_ ? kRgba32f : GL_RGBA, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
  }

  for (const Instance& instance : scene.instances) {
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    const MeshPieces& placed = meshPieces[static_cast<size_t>(instance.mesh)];
    InstanceGpu gpu;
    gpu.world = gpu.previousWorld = instance.world;
    Bounds local;
    for (const glm::vec3& p : mesh.positions) local.add(p);
    gpu.localCentre = local.empty() ? glm::vec3(0.0f) : local.center();
    gpu.restCentre = gpu.centre = glm::vec3(instance.world * glm::vec4(gpu.localCentre, 1.0f));
    gpu.material = mesh.material >= 0 ? mesh.material : static_cast<int>(materials_.size()) - 1;
    gpu.firstPiece = placed.first;
    gpu.pieceCount = placed.count;
    gpu.skin = instance.skin >= 0 && mesh.skinned() ? instance.skin : -1;
    gpu.cpuSkinned = gpu.skin >= 0 && placed.cpuSkinned;
    gpu.morphed = !mesh.morphTargets.empty();
    instances_.push_back(std::move(gpu));
  }
  lights_ = scene.lights;
  needsForwardLighting_ = !scene.lights.empty();
  for (const Mesh& mesh : scene.meshes)
    if (mesh.material >= 0 && scene.materials[static_cast<size_t>(mesh.material)].needsForwardLighting())
      needsForwardLighting_ = true;
  // The rest pose, until the first setPose.
  const ScenePose rest = evaluatePose(scene, 0.0, PoseOptions{AnimationChoice::none(), false});
  setPose(rest, rest);
}

bool GpuScene::usesUint32Indices() const {
  return std::any_of(pieces_.begin(), pieces_.end(), [](const Piece& p) { return p.indexType == GL_UNSIGNED_INT; });
}

bool GpuScene::anyMoving() const {
  return std::any_of(instances_.begin(), instances_.end(), [](const InstanceGpu& i) { return i.moving; });
}

int GpuScene::morphTargetSlots(bool withNormals, bool skinned) const {
  const int free = limits_.attributes - 3 - (skinned ? 2 : 0);
  return std::clamp(free / (withNormals ? 2 : 1), 0, VertexKind::kMaxMorphTargets);
}

GeometryUniforms::GeometryUniforms(const gl::Program& program)
    : modelView(program.uniform("u_modelView")),
      normalMatrix(program.optionalUniform("u_normalMatrix")),
      baseColorFactor(program.optionalUniform("u_baseColorFactor")),
      baseColorTexture(program.optionalUniform("u_baseColorTexture")),
      alphaCutoff(program.optionalUniform("u_alphaCutoff")),
      metallicRoughness(program.optionalUniform("u_metallicRoughness")),
      emissive(program.optionalUniform("u_emissive")),
      uvTransforms(program.optionalUniform("u_uvTransforms[0]")),
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
      tangentAttribute(glGetAttribLocation(program.id(), "a_tangent")) {
  for (int t = 0; t < VertexKind::kMaxMorphTargets; ++t) {
    morphPositionAttribute[t] = glGetAttribLocation(program.id(), ("a_morphPosition" + std::to_string(t)).c_str());
    morphNormalAttribute[t] = glGetAttribLocation(program.id(), ("a_morphNormal" + std::to_string(t)).c_str());
  }
}

void GpuScene::setPose(const ScenePose& current, const ScenePose& previous) {
  lines_.setPose(current);
  for (PunctualLight& light : lights_)
    if (light.node >= 0 && static_cast<size_t>(light.node) < current.nodeWorld.size())
      light.world = current.nodeWorld[static_cast<size_t>(light.node)];
  std::vector<bool> skinMoving(skins_.size(), false);
  for (size_t s = 0; s < skins_.size(); ++s) {
    SkinGpu& skin = skins_[s];
    if (current.skinJoints[s].empty()) continue;
    skin.joints = current.skinJoints[s];
    skin.previousJoints = previous.skinJoints[s];
    skinMoving[s] = skin.joints != skin.previousJoints;
    if (!skin.texture) continue;
    const auto texels = static_cast<size_t>(skin.textureSize.x * skin.textureSize.y);
    std::vector<float> data;
    data.reserve(texels * 4);
    for (const glm::mat4& m : skin.joints) appendRows(data, m);
    for (const glm::mat4& m : skin.previousJoints) appendRows(data, m);
    data.resize(texels * 4, 0.0f);
    glBindTexture(GL_TEXTURE_2D, skin.texture.id());
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, static_cast<GLsizei>(skin.textureSize.x),
                    static_cast<GLsizei>(skin.textureSize.y), GL_RGBA, GL_FLOAT, data.data());
    glBindTexture(GL_TEXTURE_2D, 0);
  }

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

    // Morph targets on the GPU: those with a weight now or in the previous frame, heaviest first, if they fit.
    instance.gpuTargets.clear();
    bool cpu = instance.cpuSkinned;
    if (instance.morphed) {
      const Piece& first = pieces_[static_cast<size_t>(instance.firstPiece)];
      std::vector<int> needed;
      bool normals = false;
      for (size_t t = 0; t < instance.weights.size(); ++t)
        if (instance.weights[t] != 0.0f || instance.previousWeights[t] != 0.0f) {
          needed.push_back(static_cast<int>(t));
          normals = normals || first.morphNormals[t].id() != 0;
        }
      const auto heaviness = [&](int t) {
        return std::max(std::abs(instance.weights[static_cast<size_t>(t)]),
                        std::abs(instance.previousWeights[static_cast<size_t>(t)]));
      };
      std::stable_sort(needed.begin(), needed.end(), [&](int a, int b) { return heaviness(a) > heaviness(b); });
      if (static_cast<int>(needed.size()) <= morphTargetSlots(normals, instance.skin >= 0 && !cpu))
        instance.gpuTargets = needed;
      else
        cpu = true;
    }
    instance.cpuDeformed = cpu;
    if (cpu) uploadCpuDeformed(instance, current, previous, i);
    else instance.deformed.clear();
  }
}

void GpuScene::uploadCpuDeformed(InstanceGpu& instance, const ScenePose& current, const ScenePose& previous,
                                 size_t index) {
  instance.deformed.resize(static_cast<size_t>(instance.pieceCount));
  for (int p = 0; p < instance.pieceCount; ++p) {
    const Piece& piece = pieces_[static_cast<size_t>(instance.firstPiece + p)];
    // A palette piece's joint indices are palette entries: hand posedMesh the palette's matrices.
    auto jointsOf = [&](const ScenePose& pose) {
      if (instance.skin < 0) return std::vector<glm::mat4>{};
      const std::vector<glm::mat4>& all = pose.skinJoints[static_cast<size_t>(instance.skin)];
      if (piece.palette.empty()) return all;
      std::vector<glm::mat4> local;
      for (int joint : piece.palette) local.push_back(all[static_cast<size_t>(joint)]);
      return local;
    };
    const PosedVertices now = posedMesh(piece.source, jointsOf(current), current.instanceWeights[index]);
    const PosedVertices before = posedMesh(piece.source, jointsOf(previous), previous.instanceWeights[index]);
    std::vector<float> data;
    data.reserve(now.positions.size() * kDeformedFloats);
    for (size_t v = 0; v < now.positions.size(); ++v) {
      const glm::vec2 uv = piece.source.texcoords.empty() ? glm::vec2(0.0f) : piece.source.texcoords[v];
      const glm::vec3 &p3 = now.positions[v], &n = now.normals[v], &q = before.positions[v];
      data.insert(data.end(), {p3.x, p3.y, p3.z, n.x, n.y, n.z, uv.x, uv.y, q.x, q.y, q.z});
    }
    gl::BufferHandle& buffer = instance.deformed[static_cast<size_t>(p)];
    if (!buffer) buffer = gl::BufferHandle::create();
    glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data(), GL_STREAM_DRAW);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

VertexKind GpuScene::vertexKind(const InstanceGpu& instance, const Piece& piece) const {
  VertexKind kind;
  if (instance.cpuDeformed) {
    kind.cpuDeformed = true;
    return kind;
  }
  if (instance.skin >= 0) {
    kind.skinning = skinningPath_ == SkinningPath::Texture ? VertexKind::JointTexture : VertexKind::Palette;
    if (kind.skinning == VertexKind::Palette) kind.palette = paletteSize_;
  }
  kind.morphTargets = static_cast<int>(instance.gpuTargets.size());
  for (int t : instance.gpuTargets)
    kind.morphNormals = kind.morphNormals || piece.morphNormals[static_cast<size_t>(t)].id() != 0;
  return kind;
}

void GpuScene::draw(const glm::mat4& view, const ProgramChoice& choose, const DrawOptions& options) const {
  using gl::Program;
  counts_ = {};
  // Opaque before masked, each front to back: the view-space z of the bounds' centre, nearest (largest) first.
  std::vector<std::pair<float, const InstanceGpu*>> order;
  order.reserve(instances_.size());
  for (const InstanceGpu& instance : instances_) {
    if (options.onlyMoving && !instance.moving) continue;
    const bool masked = materials_[static_cast<size_t>(instance.material)].alphaCutoff >= 0.0f;
    order.emplace_back((masked ? 1e30f : 0.0f) - (view * glm::vec4(instance.centre, 1.0f)).z, &instance);
  }
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });

  for (GLuint slot : {gl::kAttribPosition, gl::kAttribNormal, gl::kAttribTexcoord}) glEnableVertexAttribArray(slot);
  const GeometryUniforms* uniforms = nullptr;
  MaterialKind programMaterial;
  VertexKind programVertex;
  std::vector<GLuint> extraAttributes;  // enabled for the current piece
  auto attribute = [&](GLint location, GLuint buffer, GLint size, GLsizei stride, size_t offset) {
    if (location < 0) return;
    const auto slot = static_cast<GLuint>(location);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glEnableVertexAttribArray(slot);
    glVertexAttribPointer(slot, size, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset));
    extraAttributes.push_back(slot);
  };
  glActiveTexture(GL_TEXTURE0);
  bool jointTextureBound = false;
  bool pbrTexturesBound = false;
  for (const auto& [key, instancePointer] : order) {
    const InstanceGpu& instance = *instancePointer;
    const MaterialGpu& material = materials_[static_cast<size_t>(instance.material)];
    const MaterialKind materialKind{material.alphaCutoff >= 0.0f, material.texture >= 0, material.pbr};
    if (material.texture >= 0) glBindTexture(GL_TEXTURE_2D, textures_[static_cast<size_t>(material.texture)].id());
    if (material.pbr) {
      for (size_t slot = 0; slot < material.pbrTextures.size(); ++slot) {
        glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + TextureUnits::kPbr[slot]));
        const int texture = material.pbrTextures[slot];
        glBindTexture(GL_TEXTURE_2D, texture >= 0  ? textures_[static_cast<size_t>(texture)].id()
                                     : slot == 1 ? neutralNormal_.id()
                                                 : neutralWhite_.id());
      }
      glActiveTexture(GL_TEXTURE0);
      pbrTexturesBound = true;
    }
    if (material.doubleSided || options.bothFaces) glDisable(GL_CULL_FACE);
    else glEnable(GL_CULL_FACE);
    const glm::mat4 modelView = view * instance.world;
    const glm::mat3 linear(modelView);
    // A mirroring transform flips the winding; keep "front" meaning the outside.
    glFrontFace(glm::determinant(linear) < 0.0f ? GL_CW : GL_CCW);

    for (int p = instance.firstPiece; p < instance.firstPiece + instance.pieceCount; ++p) {
      const Piece& piece = pieces_[static_cast<size_t>(p)];
      const VertexKind vertexKind = this->vertexKind(instance, piece);
      const bool newProgram = !uniforms || !(materialKind == programMaterial) || !(vertexKind == programVertex);
      if (newProgram) {
        uniforms = &choose(materialKind, vertexKind);
        programMaterial = materialKind;
        programVertex = vertexKind;
        Program::set(uniforms->baseColorTexture, TextureUnits::kBaseColor);
        Program::set(uniforms->jointTexture, TextureUnits::kJoints);
        for (size_t slot = 0; slot < 4; ++slot) Program::set(uniforms->pbrTextures[slot], TextureUnits::kPbr[slot]);
      }
      if (newProgram || p == instance.firstPiece) {
        Program::set(uniforms->modelView, modelView);
        Program::set(uniforms->normalMatrix, glm::inverseTranspose(linear));
        Program::set(uniforms->previousModel, instance.previousWorld);
        Program::set(uniforms->baseColorFactor, material.baseColorFactor);
        Program::set(uniforms->alphaCutoff, material.alphaCutoff);
        Program::set(uniforms->metallicRoughness, material.metallicRoughness);
        Program::set(uniforms->emissive, material.emissive);
        if (uniforms->uvTransforms >= 0)
          glUniform3fv(uniforms->uvTransforms, 2 * kTextureSlots, &material.uvRows[0].x);
        if (vertexKind.morphTargets > 0) {
          glm::vec4 now(0.0f), before(0.0f);
          for (size_t k = 0; k < instance.gpuTargets.size(); ++k) {
            const auto t = static_cast<size_t>(instance.gpuTargets[k]);
            now[static_cast<glm::length_t>(k)] = instance.weights[t];
            before[static_cast<glm::length_t>(k)] = instance.previousWeights[t];
          }
          Program::set(uniforms->morphWeights, now);
          Program::set(uniforms->previousMorphWeights, before);
        }
      }
      ++counts_.draws;
      if (vertexKind.cpuDeformed) ++counts_.cpuDeformed;
      if (vertexKind.morphTargets > 0) ++counts_.gpuMorphed;
      if (vertexKind.skinning != VertexKind::None) ++counts_.skinned;

      if (vertexKind.skinning == VertexKind::Palette) {
        const SkinGpu& skin = skins_[static_cast<size_t>(instance.skin)];
        std::vector<float> rows, previousRows;
        for (int joint : piece.palette) {
          appendRows(rows, skin.joints[static_cast<size_t>(joint)]);
          appendRows(previousRows, skin.previousJoints[static_cast<size_t>(joint)]);
        }
        const auto vectors = static_cast<GLsizei>(rows.size() / 4);
        if (uniforms->joints >= 0) glUniform4fv(uniforms->joints, vectors, rows.data());
        if (uniforms->previousJoints >= 0) glUniform4fv(uniforms->previousJoints, vectors, previousRows.data());
      } else if (vertexKind.skinning == VertexKind::JointTexture) {
        const SkinGpu& skin = skins_[static_cast<size_t>(instance.skin)];
        glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + TextureUnits::kJoints));
        glBindTexture(GL_TEXTURE_2D, skin.texture.id());
        glActiveTexture(GL_TEXTURE0);
        jointTextureBound = true;
        Program::set(uniforms->jointTextureSize, skin.textureSize);
      }

      const bool deformed = vertexKind.cpuDeformed;
      const GLuint vertices =
          deformed ? instance.deformed[static_cast<size_t>(p - instance.firstPiece)].id() : piece.vertices.id();
      const GLsizei stride = (deformed ? kDeformedFloats : 8) * static_cast<GLsizei>(sizeof(float));
      glBindBuffer(GL_ARRAY_BUFFER, vertices);
      glVertexAttribPointer(gl::kAttribPosition, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
      glVertexAttribPointer(gl::kAttribNormal, 3, GL_FLOAT, GL_FALSE, stride,
                            reinterpret_cast<const void*>(3 * sizeof(float)));
      glVertexAttribPointer(gl::kAttribTexcoord, 2, GL_FLOAT, GL_FALSE, stride,
                            reinterpret_cast<const void*>(6 * sizeof(float)));
      if (deformed) attribute(uniforms->previousPositionAttribute, vertices, 3, stride, 8 * sizeof(float));
      // CPU-deformed vertices keep their rest tangents (an approximation: only the normal map's frame is off).
      if (piece.tangents) attribute(uniforms->tangentAttribute, piece.tangents.id(), 4, 0, 0);
      if (vertexKind.skinning != VertexKind::None) {
        const GLsizei skinStride = 8 * sizeof(float);
        attribute(uniforms->jointsAttribute, piece.skinAttributes.id(), 4, skinStride, 0);
        attribute(uniforms->weightsAttribute, piece.skinAttributes.id(), 4, skinStride, 4 * sizeof(float));
      }
      for (size_t k = 0; k < static_cast<size_t>(vertexKind.morphTargets); ++k) {
        const auto t = static_cast<size_t>(instance.gpuTargets[k]);
        attribute(uniforms->morphPositionAttribute[k], piece.morphPositions[t].id(), 3, 0, 0);
        if (piece.morphNormals[t]) attribute(uniforms->morphNormalAttribute[k], piece.morphNormals[t].id(), 3, 0, 0);
        else if (uniforms->morphNormalAttribute[k] >= 0)  // a target without normals beside one with: no delta
          glVertexAttrib3f(static_cast<GLuint>(uniforms->morphNormalAttribute[k]), 0.0f, 0.0f, 0.0f);
      }
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, piece.indices.id());
      glDrawElements(GL_TRIANGLES, piece.indexCount, piece.indexType, nullptr);
      for (GLuint slot : extraAttributes) glDisableVertexAttribArray(slot);
      extraAttributes.clear();
    }
  }
  for (GLuint slot : {gl::kAttribPosition, gl::kAttribNormal, gl::kAttribTexcoord}) glDisableVertexAttribArray(slot);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  if (jointTextureBound) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + TextureUnits::kJoints));
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
  }
  if (pbrTexturesBound) {
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
