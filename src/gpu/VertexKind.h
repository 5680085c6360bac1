#pragma once
// What a draw asks of geometry.vert: how its vertices are deformed (skinning from a uniform palette or a joint
// texture, morph targets in attributes, or already deformed on the CPU). Like MaterialKind, a program per kind rather
// than a branch per vertex; gpu/GpuScene.h picks the kind per draw from what the context allows.
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace obscura {

enum class SkinningPath {
  Uniforms,  // a uniform palette; skeletons larger than it are drawn in pieces (any GLES 2 context)
  Texture,   // the joint matrices in a float texture read by the vertex stage (vertex textures + float textures)
  Cpu,       // skinned and morphed on the CPU, uploaded each frame (the fallback)
};
const char* skinningPathName(SkinningPath path);  // "uniforms", "texture", "cpu"

struct VertexKind {
  enum Skinning { None = 0, Palette = 1, JointTexture = 2 };
  int skinning = None;
  int palette = 0;            // Palette: joints in the uniform palette (SKIN_PALETTE)
  int morphTargets = 0;       // 0..kMaxMorphTargets targets in attributes
  bool morphNormals = false;  // their NORMAL deltas too
  bool cpuDeformed = false;   // positions and normals deformed on the CPU; a_previousPosition for the velocity
  bool morphTangents = false;  // the morph targets' TANGENT deltas too (a tangent-framed material only)
  bool vertexColors = false;   // COLOR_0 in a_color (lib/material.glsl multiplies the base colour)

  static constexpr int kMaxMorphTargets = 4;  // geometry.vert's attribute names

  auto key() const {
    return std::tie(skinning, palette, morphTargets, morphNormals, cpuDeformed, morphTangents, vertexColors);
  }
  bool operator<(const VertexKind& o) const { return key() < o.key(); }
  bool operator==(const VertexKind& o) const { return key() == o.key(); }

  // The kind as a pass that draws only the current frame sees it: CPU-deformed vertices are plain ones there.
  VertexKind forCurrentFrame() const {
    VertexKind k = *this;
    k.cpuDeformed = false;
    return k;
  }
  // "" for plain vertices, else e.g. ",skin-palette16,morph2n" (program names).
  std::string nameSuffix() const {
    std::string s;
    if (skinning == Palette) s += ",skin-palette" + std::to_string(palette);
    if (skinning == JointTexture) s += ",skin-texture";
    if (morphTargets > 0)
      s += ",morph" + std::to_string(morphTargets) + (morphNormals ? "n" : "") + (morphTangents ? "t" : "");
    if (cpuDeformed) s += ",cpu-deformed";
    if (vertexColors) s += ",colors";
    return s;
  }
  // Kinds the shader validation checks (renderer/Renderer.h: allProgramSpecs) besides plain vertices, at GLES 2's
  // minimums: the 16-joint palette, the joint texture, and as many morph targets as 8 attributes hold.
  static std::vector<VertexKind> validated() {
    return {{Palette, 16, 0, false, false},       {JointTexture, 0, 0, false, false},
            {None, 0, 2, true, false},            {Palette, 16, 1, true, false},
            {None, 0, 4, false, false},           {None, 0, 0, false, true},
            {None, 0, 1, true, false, true},      {None, 0, 0, false, false, false, true},
            {Palette, 16, 0, false, false, false, true}};
  }
  std::vector<std::pair<std::string, std::string>> defines() const {
    std::vector<std::pair<std::string, std::string>> d = {{"SKINNING", std::to_string(skinning)},
                                                          {"MORPH_TARGETS", std::to_string(morphTargets)},
                                                          {"MORPH_NORMALS", morphNormals ? "1" : "0"},
                                                          {"CPU_DEFORMED", cpuDeformed ? "1" : "0"},
                                                          {"MORPH_TANGENTS", morphTangents ? "1" : "0"},
                                                          {"VERTEX_COLORS", vertexColors ? "1" : "0"}};
    if (skinning == Palette) d.emplace_back("SKIN_PALETTE", std::to_string(palette));
    return d;
  }
};

}  // namespace obscura
