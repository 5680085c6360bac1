#pragma once
// A scene's points and lines (Scene::lineMeshes, lineInstances) uploaded to GL: per mesh one vertex buffer of
// position and colour (the material's base colour factor times COLOR_0, linear RGBA), drawn with glDrawArrays, so
// no index type limits them (WebGL 1 without OES_element_index_uint). Each instance follows its node's pose
// (setPose); skins and morph targets do not apply to them. effects/lines/LinesEffect.h draws them.
#include <vector>

#include <glm/mat4x4.hpp>

#include "gl/GlObjects.h"
#include "scene/Animation.h"
#include "scene/Scene.h"

namespace obscura {

class GpuLines {
 public:
  GpuLines() = default;
  explicit GpuLines(const Scene& scene);

  bool empty() const { return instances_.empty(); }
  // Places each instance at its node's world matrix in `pose` (the rest matrix where it has no node).
  void setPose(const ScenePose& pose);
  // Draws every instance, points or lines as `points` asks, with the program in use: `modelViewProjection` gets
  // viewProjection x world, the vertex attributes `position` (vec3) and `color` (vec4). Leaves the arrays disabled
  // and no buffer bound.
  void draw(const glm::mat4& viewProjection, bool points, GLint modelViewProjection, GLint position,
            GLint color) const;
  // While withheld, draw() draws nothing (GpuScene::withholdDraws).
  void withholdDraws(bool withheld) { withheld_ = withheld; }

 private:
  struct MeshGpu {
    gl::BufferHandle vertices;  // per vertex: x, y, z, r, g, b, a
    GLsizei count = 0;
    bool points = false;
  };
  struct InstanceGpu {
    int mesh = 0;
    int node = -1;
    glm::mat4 rest{1.0f}, world{1.0f};
  };
  std::vector<MeshGpu> meshes_;
  std::vector<InstanceGpu> instances_;
  bool withheld_ = false;
};

}  // namespace obscura
