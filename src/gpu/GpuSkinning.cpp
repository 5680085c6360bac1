// GpuScene's skinning paths (gpu/GpuScene.h): which one a context takes, the joint textures, the uniform palette
// bound per draw, and the vertices deformed on the CPU where neither fits.
#include <algorithm>

#include "base/Error.h"
#include "gpu/GpuScene.h"
#include "gpu/TextureUnits.h"
#include "scene/MeshProcessing.h"

namespace obscura {
namespace {

// Vertex uniform vectors the palette cannot have: the matrices of geometry.vert (model-view, projection, normal
// matrix, the velocity's unjittered projection, previous model and previous view-projection: 22 vectors), the morph
// weights (2), and room for the driver's packing and the uniforms a compiler adds.
constexpr int kReservedUniformVectors = 32;
// Joints per palette where uniforms are plenty: beyond it, uploading the palette per draw costs more than it saves.
constexpr int kMaxPaletteJoints = 128;
// GL_RGBA32F: a desktop context needs the sized format to keep floats; GLES 2 / WebGL 1 with OES_texture_float take
// GL_RGBA with type GL_FLOAT.
constexpr GLenum kRgba32f = 0x8814;

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

// The skinning path: the one asked for where the context can take it, else the best it can.
void GpuScene::chooseSkinningPath(const gl::GlCaps& caps, const Options& options) {
  // The joint texture needs a ninth texture unit (gpu/TextureUnits.h): the lighting's fragment stage may use eight.
  const bool textureOk = limits_.textureUnits > 0 && caps.textureFloat && TextureUnits::jointTextureFits(caps);
  const int palette = std::min(kMaxPaletteJoints, (limits_.uniformVectors - kReservedUniformVectors) / 6);
  const bool uniformsOk = palette >= 12;  // a triangle may need 3 vertices x 4 joints
  const SkinningPath wanted = options.skinning.value_or(SkinningPath::Texture);
  if (wanted == SkinningPath::Cpu) skinningPath_ = SkinningPath::Cpu;
  else if (wanted == SkinningPath::Texture && textureOk) skinningPath_ = SkinningPath::Texture;
  else skinningPath_ = uniformsOk ? SkinningPath::Uniforms : SkinningPath::Cpu;
  paletteSize_ = skinningPath_ == SkinningPath::Uniforms ? palette : 0;
}

// Every skin's matrices at rest, and on the texture path its float texture.
void GpuScene::createSkins(const Scene& scene, const gl::GlCaps& caps) {
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
}

// This frame's and the previous frame's joint matrices, uploaded to the joint textures. Returns, per skin, whether
// its joints moved.
std::vector<bool> GpuScene::poseSkins(const ScenePose& current, const ScenePose& previous) {
  std::vector<bool> skinMoving(skins_.size(), false);
  for (size_t s = 0; s < skins_.size(); ++s) {
    SkinGpu& skin = skins_[s];
    if (current.skinJoints[s].empty()) continue;
    // A pose that stands still (a paused or unanimated skin) leaves the texture as it is: each upload costs a browser
    // the conversion of every texel.
    const bool same = skin.joints == current.skinJoints[s] && skin.previousJoints == previous.skinJoints[s];
    skin.joints = current.skinJoints[s];
    skin.previousJoints = previous.skinJoints[s];
    skinMoving[s] = skin.joints != skin.previousJoints;
    int mirroring = 0;
    for (const glm::mat4& m : skin.joints) mirroring += glm::determinant(glm::mat3(m)) < 0.0f ? 1 : -1;
    skin.mirrored = mirroring > 0;
    if (!skin.texture || (skin.uploaded && same)) continue;
    skin.uploaded = true;
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
  return skinMoving;
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
    // Tangents are deformed as the vertex stage would (their w turned by a mirroring joint): a normal texture on a
    // CPU-deformed mesh keeps its frame.
    for (size_t v = 0; v < now.positions.size(); ++v) {
      const glm::vec3 &p3 = now.positions[v], &n = now.normals[v], &q = before.positions[v];
      const glm::vec4 t = now.tangents.empty() ? glm::vec4(1.0f, 0.0f, 0.0f, 1.0f) : now.tangents[v];
      data.insert(data.end(), {p3.x, p3.y, p3.z, n.x, n.y, n.z, q.x, q.y, q.z, t.x, t.y, t.z, t.w});
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
  kind.vertexColors = static_cast<bool>(piece.colors);
  if (instance.cpuDeformed) {
    kind.cpuDeformed = true;
    return kind;
  }
  if (instance.skin >= 0) {
    kind.skinning = skinningPath_ == SkinningPath::Texture ? VertexKind::JointTexture : VertexKind::Palette;
    if (kind.skinning == VertexKind::Palette) kind.palette = paletteSize_;
  }
  kind.morphTargets = static_cast<int>(instance.gpuTargets.size());
  for (int t : instance.gpuTargets) {
    kind.morphNormals = kind.morphNormals || piece.morphNormals[static_cast<size_t>(t)].id() != 0;
    kind.morphTangents = kind.morphTangents || piece.morphTangents[static_cast<size_t>(t)].id() != 0;
  }
  return kind;
}

// The draw's skin: the palette piece's joints as uniforms, or the skin's joint texture on its unit.
void GpuScene::bindSkin(const InstanceGpu& instance, const Piece& piece, const VertexKind& vertexKind,
                        DrawState& state) const {
  const GeometryUniforms& uniforms = *state.uniforms;
  if (vertexKind.skinning == VertexKind::Palette) {
    const SkinGpu& skin = skins_[static_cast<size_t>(instance.skin)];
    std::vector<float> rows, previousRows;
    for (int joint : piece.palette) {
      appendRows(rows, skin.joints[static_cast<size_t>(joint)]);
      appendRows(previousRows, skin.previousJoints[static_cast<size_t>(joint)]);
    }
    const auto vectors = static_cast<GLsizei>(rows.size() / 4);
    if (uniforms.joints >= 0) glUniform4fv(uniforms.joints, vectors, rows.data());
    if (uniforms.previousJoints >= 0) glUniform4fv(uniforms.previousJoints, vectors, previousRows.data());
  } else if (vertexKind.skinning == VertexKind::JointTexture) {
    const SkinGpu& skin = skins_[static_cast<size_t>(instance.skin)];
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + TextureUnits::kJoints));
    glBindTexture(GL_TEXTURE_2D, skin.texture.id());
    glActiveTexture(GL_TEXTURE0);
    state.jointTextureBound = true;
    gl::Program::set(uniforms.jointTextureSize, skin.textureSize);
  }
}

}  // namespace obscura
