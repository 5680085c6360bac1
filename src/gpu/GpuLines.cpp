#include "gpu/GpuLines.h"

#include "gl/Program.h"

namespace obscura {

GpuLines::GpuLines(const Scene& scene) {
  for (const LineMesh& mesh : scene.lineMeshes) {
    glm::vec4 tint(1.0f);
    if (mesh.material >= 0 && static_cast<size_t>(mesh.material) < scene.materials.size())
      tint = scene.materials[static_cast<size_t>(mesh.material)].baseColorFactor;
    std::vector<float> interleaved;
    interleaved.reserve(mesh.positions.size() * 7);
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const glm::vec4 c = tint * (mesh.colors.empty() ? glm::vec4(1.0f) : mesh.colors[v]);
      interleaved.insert(interleaved.end(), {mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z, c.r, c.g,
                                             c.b, c.a});
    }
    MeshGpu gpu;
    gpu.vertices = gl::BufferHandle::create();
    glBindBuffer(GL_ARRAY_BUFFER, gpu.vertices.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)), interleaved.data(),
                 GL_STATIC_DRAW);
    gpu.count = static_cast<GLsizei>(mesh.positions.size());
    gpu.points = mesh.points;
    meshes_.push_back(std::move(gpu));
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  for (const LineInstance& instance : scene.lineInstances)
    instances_.push_back({instance.mesh, instance.node, instance.world, instance.world});
}

void GpuLines::setPose(const ScenePose& pose) {
  for (InstanceGpu& instance : instances_)
    instance.world = instance.node >= 0 && static_cast<size_t>(instance.node) < pose.nodeWorld.size()
                         ? pose.nodeWorld[static_cast<size_t>(instance.node)]
                         : instance.rest;
}

void GpuLines::draw(const glm::mat4& viewProjection, bool points, GLint modelViewProjection, GLint position,
                    GLint color) const {
  if (withheld_) return;
  const GLsizei stride = 7 * sizeof(float);
  for (const InstanceGpu& instance : instances_) {
    const MeshGpu& mesh = meshes_[static_cast<size_t>(instance.mesh)];
    if (mesh.points != points) continue;
    gl::Program::set(modelViewProjection, viewProjection * instance.world);
    glBindBuffer(GL_ARRAY_BUFFER, mesh.vertices.id());
    glEnableVertexAttribArray(static_cast<GLuint>(position));
    glVertexAttribPointer(static_cast<GLuint>(position), 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(static_cast<GLuint>(color));
    glVertexAttribPointer(static_cast<GLuint>(color), 4, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(3 * sizeof(float)));
    glDrawArrays(points ? GL_POINTS : GL_LINES, 0, mesh.count);
  }
  if (!instances_.empty()) {
    glDisableVertexAttribArray(static_cast<GLuint>(position));
    glDisableVertexAttribArray(static_cast<GLuint>(color));
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

}  // namespace obscura
