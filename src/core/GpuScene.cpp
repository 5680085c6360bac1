#include "core/GpuScene.h"

#include <algorithm>

#include <glm/gtc/matrix_inverse.hpp>

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

}  // namespace

GpuScene::GpuScene(const Scene& scene, const gl::GlCaps& caps, const Options& options) {
  const bool uint32 = caps.elementIndexUint && options.allowUint32Indices;

  for (size_t t = 0; t < scene.textures.size(); ++t) {
    const Texture& texture = scene.textures[t];
    if (texture.image >= 0 && scene.images[static_cast<size_t>(texture.image)].width > 0)
      textures_.push_back(uploadTexture(scene.images[static_cast<size_t>(texture.image)], texture.sampler, caps));
    else
      textures_.emplace_back();
  }
  for (const Material& m : scene.materials) {
    MaterialGpu gpu;
    gpu.baseColorFactor = m.baseColorFactor;
    gpu.texture = m.baseColorTexture >= 0 && textures_[static_cast<size_t>(m.baseColorTexture)] ? m.baseColorTexture
                                                                                                 : -1;
    gpu.alphaCutoff = m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : -1.0f;
    gpu.doubleSided = m.doubleSided;
    materials_.push_back(gpu);
  }
  materials_.push_back(MaterialGpu{});  // the glTF default material

  // Upload each mesh once (as one or more pieces), then point instances at the pieces.
  std::vector<std::pair<int, int>> meshPieces;  // first piece, count
  for (const Mesh& mesh : scene.meshes) {
    const int first = static_cast<int>(pieces_.size());
    for (const Mesh& part : uint32 ? std::vector<Mesh>{mesh} : splitForShortIndices(mesh)) {
      std::vector<float> interleaved;
      interleaved.reserve(part.positions.size() * 8);
      for (size_t v = 0; v < part.positions.size(); ++v) {
        const glm::vec2 uv = part.texcoords.empty() ? glm::vec2(0.0f) : part.texcoords[v];
        interleaved.insert(interleaved.end(), {part.positions[v].x, part.positions[v].y, part.positions[v].z,
                                               part.normals[v].x, part.normals[v].y, part.normals[v].z, uv.x, uv.y});
      }
      Piece piece;
      piece.vertices = gl::BufferHandle::create();
      glBindBuffer(GL_ARRAY_BUFFER, piece.vertices.id());
      glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)), interleaved.data(),
                   GL_STATIC_DRAW);
      piece.indices = gl::BufferHandle::create();
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, piece.indices.id());
      if (part.positions.size() <= 65536) {
        const std::vector<std::uint16_t> shorts(part.indices.begin(), part.indices.end());
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(shorts.size() * 2), shorts.data(),
                     GL_STATIC_DRAW);
        piece.indexType = GL_UNSIGNED_SHORT;
      } else {
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(part.indices.size() * 4), part.indices.data(),
                     GL_STATIC_DRAW);
        piece.indexType = GL_UNSIGNED_INT;
      }
      piece.indexCount = static_cast<GLsizei>(part.indices.size());
      pieces_.push_back(std::move(piece));
    }
    meshPieces.emplace_back(first, static_cast<int>(pieces_.size()) - first);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);

  for (const Instance& instance : scene.instances) {
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    InstanceGpu gpu;
    gpu.world = instance.world;
    Bounds bounds;
    for (const glm::vec3& p : mesh.positions) bounds.add(glm::vec3(instance.world * glm::vec4(p, 1.0f)));
    gpu.centre = bounds.empty() ? glm::vec3(instance.world[3]) : 0.5f * (bounds.min + bounds.max);
    gpu.material = mesh.material >= 0 ? mesh.material : static_cast<int>(materials_.size()) - 1;
    gpu.firstPiece = meshPieces[static_cast<size_t>(instance.mesh)].first;
    gpu.pieceCount = meshPieces[static_cast<size_t>(instance.mesh)].second;
    instances_.push_back(gpu);
  }
}

bool GpuScene::usesUint32Indices() const {
  return std::any_of(pieces_.begin(), pieces_.end(), [](const Piece& p) { return p.indexType == GL_UNSIGNED_INT; });
}

GeometryUniforms::GeometryUniforms(const gl::Program& program)
    : modelView(program.uniform("u_modelView")),
      normalMatrix(program.optionalUniform("u_normalMatrix")),
      baseColorFactor(program.optionalUniform("u_baseColorFactor")),
      baseColorTexture(program.optionalUniform("u_baseColorTexture")),
      alphaCutoff(program.optionalUniform("u_alphaCutoff")) {}

std::vector<glm::mat4> GpuScene::worldMatrices() const {
  std::vector<glm::mat4> out;
  out.reserve(instances_.size());
  for (const InstanceGpu& instance : instances_) out.push_back(instance.world);
  return out;
}

void GpuScene::draw(const glm::mat4& view, const ProgramChoice& choose) const {
  using gl::Program;
  // Opaque before masked, each front to back: the view-space z of the bounds' centre, nearest (largest) first.
  std::vector<std::pair<float, const InstanceGpu*>> order;
  order.reserve(instances_.size());
  for (const InstanceGpu& instance : instances_) {
    const bool masked = materials_[static_cast<size_t>(instance.material)].alphaCutoff >= 0.0f;
    order.emplace_back((masked ? 1e30f : 0.0f) - (view * glm::vec4(instance.centre, 1.0f)).z, &instance);
  }
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });

  const GLsizei stride = 8 * sizeof(float);
  for (GLuint slot : {gl::kAttribPosition, gl::kAttribNormal, gl::kAttribTexcoord}) glEnableVertexAttribArray(slot);
  const GeometryUniforms* uniforms = nullptr;
  MaterialKind programKind;
  glActiveTexture(GL_TEXTURE0);
  for (const auto& [key, instancePointer] : order) {
    const InstanceGpu& instance = *instancePointer;
    const MaterialGpu& material = materials_[static_cast<size_t>(instance.material)];
    const MaterialKind kind{material.alphaCutoff >= 0.0f, material.texture >= 0};
    if (!uniforms || !(kind == programKind)) {
      uniforms = &choose(kind);
      programKind = kind;
      Program::set(uniforms->baseColorTexture, 0);
    }
    const glm::mat4 modelView = view * instance.world;
    const glm::mat3 linear(modelView);
    Program::set(uniforms->modelView, modelView);
    Program::set(uniforms->normalMatrix, glm::inverseTranspose(linear));
    // A mirroring transform flips the winding; keep "front" meaning the outside.
    glFrontFace(glm::determinant(linear) < 0.0f ? GL_CW : GL_CCW);

    Program::set(uniforms->baseColorFactor, material.baseColorFactor);
    Program::set(uniforms->alphaCutoff, material.alphaCutoff);
    if (material.texture >= 0) glBindTexture(GL_TEXTURE_2D, textures_[static_cast<size_t>(material.texture)].id());
    if (material.doubleSided) glDisable(GL_CULL_FACE);
    else glEnable(GL_CULL_FACE);

    for (int p = instance.firstPiece; p < instance.firstPiece + instance.pieceCount; ++p) {
      const Piece& piece = pieces_[static_cast<size_t>(p)];
      glBindBuffer(GL_ARRAY_BUFFER, piece.vertices.id());
      glVertexAttribPointer(gl::kAttribPosition, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
      glVertexAttribPointer(gl::kAttribNormal, 3, GL_FLOAT, GL_FALSE, stride,
                            reinterpret_cast<const void*>(3 * sizeof(float)));
      glVertexAttribPointer(gl::kAttribTexcoord, 2, GL_FLOAT, GL_FALSE, stride,
                            reinterpret_cast<const void*>(6 * sizeof(float)));
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, piece.indices.id());
      glDrawElements(GL_TRIANGLES, piece.indexCount, piece.indexType, nullptr);
    }
  }
  for (GLuint slot : {gl::kAttribPosition, gl::kAttribNormal, gl::kAttribTexcoord}) glDisableVertexAttribArray(slot);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
}

}  // namespace obscura
