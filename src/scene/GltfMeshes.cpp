#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include "scene/GltfCompression.h"
#include "scene/GltfReading.h"
#include "scene/MeshProcessing.h"

namespace obscura::gltf {
namespace {

// Triangle-list indices for a primitive, converting strips and fans.
std::vector<std::uint32_t> triangleIndices(const LoaderContext& ctx, const tinygltf::Primitive& primitive,
                                           size_t vertexCount, const std::string& what) {
  std::vector<std::uint32_t> raw;
  if (primitive.indices >= 0) {
    const std::vector<double> values =
        readAccessor(ctx, primitive.indices, what + " indices", 1,
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
    raw.reserve(values.size());
    for (double v : values) {
      if (v >= static_cast<double>(vertexCount))
        ctx.refuse(what + " has index " + std::to_string(static_cast<std::uint64_t>(v)) + " but only " +
                   std::to_string(vertexCount) + " vertices");
      raw.push_back(static_cast<std::uint32_t>(v));
    }
  } else {
    raw.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) raw[i] = static_cast<std::uint32_t>(i);
  }
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  std::vector<std::uint32_t> triangles;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (raw.size() % 3 != 0)
      ctx.report.warnings.push_back(what + ": index count " + std::to_string(raw.size()) +
                                    " is not a multiple of 3; the last partial triangle is ignored");
    raw.resize(raw.size() / 3 * 3);
    triangles = std::move(raw);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 2; i < raw.size(); ++i) {
      // Alternate the winding so every triangle keeps the strip's orientation.
      if (i % 2 == 0) triangles.insert(triangles.end(), {raw[i - 2], raw[i - 1], raw[i]});
      else triangles.insert(triangles.end(), {raw[i - 1], raw[i - 2], raw[i]});
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (size_t i = 2; i < raw.size(); ++i) triangles.insert(triangles.end(), {raw[0], raw[i - 1], raw[i]});
  }
  return triangles;
}

// Removes triangles with repeated vertices or zero area; they cover no pixels and break normal generation. A skinned
// or morphed mesh keeps its zero-area triangles with three distinct corners: a pose can open them (three collinear
// vertices following different joints, or a morph target that inflates a collapsed face).
size_t dropDegenerateTriangles(Mesh& mesh) {
  const bool poseCanChangeShape = mesh.skinned() || !mesh.morphTargets.empty();
  std::vector<std::uint32_t> kept;
  kept.reserve(mesh.indices.size());
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    if (a == b || b == c || a == c) continue;
    const glm::vec3 cross = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    if (!poseCanChangeShape && !(glm::dot(cross, cross) > 0.0f)) continue;
    kept.insert(kept.end(), {a, b, c});
  }
  const size_t dropped = (mesh.indices.size() - kept.size()) / 3;
  mesh.indices = std::move(kept);
  return dropped;
}

// JOINTS_0 / WEIGHTS_0 (glTF 2.0 sec. 3.7.3.3): joints unsigned byte or short, not normalised; weights float or
// normalised unsigned byte or short, not negative, summing to 1. Repairs, so that the vertex stage can rely on them:
// weights are renormalised (a warning counts the vertices more than 1 % off, beyond what 8-bit quantisation
// explains); all-zero weights become weight 1 on the first joint listed; slots of weight zero point at joint 0.
void loadSkinAttributes(const LoaderContext& ctx, const tinygltf::Primitive& primitive, const std::string& what,
                        size_t vertexCount, Mesh& mesh) {
  const int jointsAccessor = attributeAccessor(primitive, "JOINTS_0");
  const int weightsAccessor = attributeAccessor(primitive, "WEIGHTS_0");
  if (weightsAccessor < 0) ctx.refuse(what + " has JOINTS_0 without WEIGHTS_0");
  const std::vector<double> joints = readAccessor(
      ctx, jointsAccessor, what + " JOINTS_0", 4,
      {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
  if (ctx.model.accessors[static_cast<size_t>(jointsAccessor)].normalized)
    ctx.refuse(what + " JOINTS_0 (accessor " + std::to_string(jointsAccessor) +
               ") is normalized, which glTF does not allow for joint indices");
  const std::vector<double> weights = readAccessor(
      ctx, weightsAccessor, what + " WEIGHTS_0", 4,
      {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
  const tinygltf::Accessor& weightsSource = ctx.model.accessors[static_cast<size_t>(weightsAccessor)];
  if (weightsSource.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !weightsSource.normalized)
    ctx.refuse(what + " WEIGHTS_0 (accessor " + std::to_string(weightsAccessor) + ") has component type " +
               componentTypeName(weightsSource.componentType) + " without normalized: true, which glTF does not allow");
  if (joints.size() / 4 != vertexCount || weights.size() / 4 != vertexCount)
    ctx.refuse(what + " has " + std::to_string(joints.size() / 4) + " JOINTS_0 and " +
               std::to_string(weights.size() / 4) + " WEIGHTS_0 for " + std::to_string(vertexCount) + " positions");
  mesh.joints.resize(vertexCount);
  mesh.weights.resize(vertexCount);
  size_t renormalised = 0, weightless = 0;
  for (size_t v = 0; v < vertexCount; ++v) {
    double sum = 0.0;
    for (int c = 0; c < 4; ++c) {
      const double w = weights[v * 4 + static_cast<size_t>(c)];
      if (!std::isfinite(w) || w < 0.0)
        ctx.refuse(what + " WEIGHTS_0 " + std::to_string(v) + " is negative or not finite");
      sum += w;
    }
    glm::dvec4 w(weights[v * 4], weights[v * 4 + 1], weights[v * 4 + 2], weights[v * 4 + 3]);
    if (!(sum > 0.0)) {
      w = glm::dvec4(1.0, 0.0, 0.0, 0.0);
      ++weightless;
    } else {
      if (std::abs(sum - 1.0) > 0.01) ++renormalised;
      w /= sum;
    }
    for (int c = 0; c < 4; ++c) {
      mesh.weights[v][c] = static_cast<float>(w[c]);
      mesh.joints[v][c] = w[c] > 0.0 ? static_cast<std::uint16_t>(joints[v * 4 + static_cast<size_t>(c)]) : 0;
    }
  }
  if (renormalised > 0)
    ctx.report.warnings.push_back(what + ": WEIGHTS_0 of " + std::to_string(renormalised) +
                                  " vertices did not sum to 1; renormalised");
  if (weightless > 0)
    ctx.report.warnings.push_back(what + ": " + std::to_string(weightless) +
                                  " vertices have all WEIGHTS_0 zero; they follow their first joint");
  if (attributeAccessor(primitive, "JOINTS_1") >= 0 || attributeAccessor(primitive, "WEIGHTS_1") >= 0)
    ctx.report.warnings.push_back(what + ": JOINTS_1 / WEIGHTS_1 ignored (only four joints per vertex are drawn); "
                                         "WEIGHTS_0 renormalised");
}

// Morph targets (glTF 2.0 sec. 3.7.2.2): per target, POSITION, NORMAL and TANGENT displacements, float VEC3 (or
// quantized), one per vertex (sparse accessors welcome: targets are mostly zeros). Other attributes are ignored. A
// target without POSITION displaces nothing.
void loadMorphTargets(const LoaderContext& ctx, const tinygltf::Primitive& primitive, const std::string& what,
                      size_t vertexCount, Mesh& mesh) {
  for (size_t t = 0; t < primitive.targets.size(); ++t) {
    const std::string target = what + " target " + std::to_string(t);
    ctx.budget.morphTargetVertices += vertexCount;
    if (ctx.budget.morphTargetVertices > ctx.limits.maxMorphTargetVertices)
      ctx.refuse(target + ": more than " + std::to_string(ctx.limits.maxMorphTargetVertices) +
                 " morph target vertices in the scene");
    MorphTarget morph;
    const struct {
      const char* name;
      const char* use;  // for the component types KHR_mesh_quantization allows
      std::vector<glm::vec3> MorphTarget::*deltas;
    } attributes[] = {{"POSITION", "MORPH_POSITION", &MorphTarget::positions},
                      {"NORMAL", "MORPH_NORMAL", &MorphTarget::normals},
                      {"TANGENT", "MORPH_NORMAL", &MorphTarget::tangents}};
    for (const auto& a : attributes) {
      auto it = primitive.targets[t].find(a.name);
      if (it == primitive.targets[t].end()) continue;
      const std::vector<double> deltas = readVertexAttribute(ctx, it->second, target + " " + a.name, 3, a.use);
      if (deltas.size() / 3 != vertexCount)
        ctx.refuse(target + " has " + std::to_string(deltas.size() / 3) + " " + a.name + " displacements for " +
                   std::to_string(vertexCount) + " positions");
      if (!allFinite(deltas)) ctx.refuse(target + " " + a.name + " has a displacement that is not finite");
      morph.*a.deltas = toVectors<3>(deltas);
    }
    if (morph.positions.empty()) morph.positions.assign(vertexCount, glm::vec3(0.0f));
    mesh.morphTargets.push_back(std::move(morph));
  }
  // A mesh whose targets move tangents in some targets only: the others move none (zeros), so every target has
  // either all three kinds of delta or none of a kind the vertex stage reads.
  const bool anyTangents = std::any_of(mesh.morphTargets.begin(), mesh.morphTargets.end(),
                                       [](const MorphTarget& m) { return !m.tangents.empty(); });
  if (anyTangents)
    for (MorphTarget& m : mesh.morphTargets)
      if (m.tangents.empty()) m.tangents.assign(vertexCount, glm::vec3(0.0f));
}

// TEXCOORD_0 or TEXCOORD_1, one per vertex (empty where the primitive has none); coordinates that are not finite
// become 0.
std::vector<glm::vec2> readTexcoords(const LoaderContext& ctx, const tinygltf::Primitive& primitive,
                                     const std::string& what, const char* name, size_t vertexCount) {
  const int accessor = attributeAccessor(primitive, name);
  if (accessor < 0) return {};
  std::vector<glm::vec2> uvs =
      toVectors<2>(readVertexAttribute(ctx, accessor, what + " " + name, 2, "TEXCOORD"));
  if (uvs.size() != vertexCount)
    ctx.refuse(what + " has " + std::to_string(uvs.size()) + " " + name + " coordinates for " +
               std::to_string(vertexCount) + " positions");
  for (glm::vec2& uv : uvs)
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
  return uvs;
}

}  // namespace

// COLOR_0 (glTF 2.0 3.7.2.1: float, or normalised unsigned byte or short; RGB or RGBA), one per vertex, clamped to
// [0, 1]; alpha 1 for RGB; empty where the primitive has none.
std::vector<glm::vec4> readColors(const LoaderContext& ctx, const tinygltf::Primitive& primitive,
                                  const std::string& what, size_t vertexCount) {
  std::vector<glm::vec4> colors;
  const int colorAccessor = attributeAccessor(primitive, "COLOR_0");
  if (colorAccessor < 0) return colors;
  const tinygltf::Accessor& accessor = ctx.model.accessors.at(static_cast<size_t>(colorAccessor));
  const int components = accessor.type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
  const std::vector<double> values = readAccessor(ctx, colorAccessor, what + " COLOR_0", components,
                                                  {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
  if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !accessor.normalized)
    ctx.refuse(what + " COLOR_0 (accessor " + std::to_string(colorAccessor) + ") has component type " +
               componentTypeName(accessor.componentType) + " without normalized: true, which glTF does not allow");
  if (values.size() / static_cast<size_t>(components) != vertexCount)
    ctx.refuse(what + " has " + std::to_string(values.size() / static_cast<size_t>(components)) + " colours for " +
               std::to_string(vertexCount) + " positions");
  colors.reserve(vertexCount);
  for (size_t i = 0; i < vertexCount; ++i) {
    glm::vec4 c(1.0f);
    for (int k = 0; k < components; ++k) {
      const double v = values[i * static_cast<size_t>(components) + static_cast<size_t>(k)];
      c[k] = std::isfinite(v) ? static_cast<float>(std::clamp(v, 0.0, 1.0)) : 0.0f;
    }
    colors.push_back(c);
  }
  return colors;
}

Mesh loadPrimitive(const LoaderContext& ctx, const tinygltf::Primitive& primitive, const std::string& what,
                   bool readSkin, bool* skipped) {
  Mesh mesh;
  *skipped = false;
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    if (mode < 0 || mode > 6) ctx.refuse(what + " has primitive mode " + std::to_string(mode) + ", not a glTF mode");
    *skipped = true;  // points and lines have no surface to occlude: loadLinePrimitive reads them
    return mesh;
  }
  auto attribute = [&](const char* name) { return attributeAccessor(primitive, name); };
  const int positionAccessor = attribute("POSITION");
  if (positionAccessor < 0) ctx.refuse(what + " has no POSITION attribute");
  mesh.positions = toVectors<3>(readVertexAttribute(ctx, positionAccessor, what + " POSITION", 3, "POSITION"));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      ctx.refuse(what + " POSITION " + std::to_string(i) + " is not finite (NaN or Inf)");
  }
  const size_t vertexCount = mesh.positions.size();

  const int normalAccessor = attribute("NORMAL");
  bool normalsUsable = false;
  if (normalAccessor >= 0) {
    mesh.normals = toVectors<3>(readVertexAttribute(ctx, normalAccessor, what + " NORMAL", 3, "NORMAL"));
    if (mesh.normals.size() != vertexCount)
      ctx.refuse(what + " has " + std::to_string(mesh.normals.size()) + " normals for " +
                 std::to_string(vertexCount) + " positions");
    normalsUsable = true;
    for (glm::vec3& n : mesh.normals) {
      const float length = glm::length(n);
      if (!std::isfinite(length) || length < 1e-6f) {
        normalsUsable = false;
        break;
      }
      n /= length;  // the spec requires unit normals; tolerate slightly off ones
    }
    if (!normalsUsable)
      ctx.report.warnings.push_back(what + ": NORMAL has zero-length or non-finite vectors; flat normals generated");
  }

  // glTF 2.0 (3.7.2.1) allows integer texture coordinates only normalised (raw integers would be coordinates
  // hundreds of textures wide); KHR_mesh_quantization allows them raw, scaled by KHR_texture_transform.
  mesh.texcoords = readTexcoords(ctx, primitive, what, "TEXCOORD_0", vertexCount);
  mesh.texcoords1 = readTexcoords(ctx, primitive, what, "TEXCOORD_1", vertexCount);
  if (attribute("TEXCOORD_2") >= 0)
    ctx.report.warnings.push_back(what + ": TEXCOORD_2 and beyond are not read (only TEXCOORD_0 and TEXCOORD_1)");
  if (mesh.texcoords.empty() && !mesh.texcoords1.empty())
    ctx.report.warnings.push_back(what + " has TEXCOORD_1 without TEXCOORD_0 (glTF numbers sets without gaps)");
  const int setsNeeded = texCoordSetsSampled(ctx, primitive.material);
  const int setsPresent = mesh.texcoords1.empty() ? (mesh.texcoords.empty() ? 0 : 1) : 2;
  if (setsNeeded > setsPresent)
    ctx.report.warnings.push_back(what + ": its material samples TEXCOORD_" + std::to_string(setsNeeded - 1) +
                                  ", which it lacks; sampled at (0, 0)");
  // Each glTF primitive becomes its own Mesh with its own copy of the coordinates, so baking the material's base
  // colour coordinates here is right even when primitives with different materials share one accessor.
  const BakedBaseColorUv baked = baseColorUvToBake(ctx, primitive.material, what);
  const std::vector<glm::vec2>& bakedFrom = baked.texCoord == 1 ? mesh.texcoords1 : mesh.texcoords;
  if (!bakedFrom.empty() && (baked.texCoord == 1 || baked.transform != glm::mat3(1.0f))) {
    std::vector<glm::vec2> uvs(bakedFrom.size());
    for (size_t v = 0; v < uvs.size(); ++v) uvs[v] = glm::vec2(baked.transform * glm::vec3(bakedFrom[v], 1.0f));
    mesh.texcoords = std::move(uvs);
  }
  mesh.colors = readColors(ctx, primitive, what, vertexCount);

  const int tangentAccessor = attribute("TANGENT");
  const tinygltf::Material* material = materialOf(ctx, primitive.material);
  const bool normalMapped = material && material->normalTexture.index >= 0;
  if (tangentAccessor >= 0 && normalMapped && normalsUsable) {
    const std::vector<double> tangents = readVertexAttribute(ctx, tangentAccessor, what + " TANGENT", 4, "NORMAL");
    if (tangents.size() / 4 != vertexCount)
      ctx.refuse(what + " has " + std::to_string(tangents.size() / 4) + " tangents for " +
                 std::to_string(vertexCount) + " positions");
    mesh.tangents = toVectors<4>(tangents);
    for (size_t v = 0; v < vertexCount; ++v) {
      glm::vec4& t = mesh.tangents[v];
      const float length = glm::length(glm::vec3(t));
      // glTF: XYZ unit, W +-1. Tolerate slightly off ones; a broken one takes a perpendicular of the normal.
      const glm::vec3 xyz = std::isfinite(length) && length > 1e-6f ? glm::vec3(t) / length
                                                                     : anyPerpendicular(mesh.normals[v]);
      t = glm::vec4(xyz, t.w < 0.0f ? -1.0f : 1.0f);
    }
  }

  if (readSkin) loadSkinAttributes(ctx, primitive, what, vertexCount, mesh);
  loadMorphTargets(ctx, primitive, what, vertexCount, mesh);
  // Normal displacements are relative to the file's normals; where those are replaced by flat ones,
  // generateFlatNormals derives each target's from its displaced faces instead.
  if (!normalsUsable)
    for (MorphTarget& target : mesh.morphTargets) target.normals.clear();
  // Tangent displacements are relative to the file's tangents; generated ones have none.
  if (mesh.tangents.empty())
    for (MorphTarget& target : mesh.morphTargets) target.tangents.clear();

  mesh.indices = triangleIndices(ctx, primitive, vertexCount, what);
  const size_t dropped = dropDegenerateTriangles(mesh);
  if (dropped > 0)
    ctx.report.warnings.push_back(what + ": dropped " + std::to_string(dropped) + " degenerate triangles");
  if (primitive.material >= 0 && static_cast<size_t>(primitive.material) >= ctx.model.materials.size())
    ctx.refuse(what + " refers to material " + std::to_string(primitive.material) + ", which does not exist");
  mesh.material = primitive.material;
  if (!normalsUsable) generateFlatNormals(mesh);
  // glTF 2.0 (3.7.2.1): without TANGENT, tangents are computed (MikkTSpace) where a normal texture needs them.
  if (normalMapped && mesh.tangents.empty()) generateTangents(mesh, normalTextureTexCoord(*material));
  // TEXCOORD_1 serves only slots that sample it; a material whose base colour was baked needs no second set.
  if (!material || !usesTexCoord1(*material)) mesh.texcoords1.clear();
  return mesh;
}

// A POINTS, LINES, LINE_LOOP or LINE_STRIP primitive as a LineMesh: POSITION (float, or quantized under
// KHR_mesh_quantization), COLOR_0 (float or normalised u8/u16, RGB or RGBA), indices as for triangles. Strips and
// loops become segment lists; a zero-length segment is kept (it covers a pixel, as a point would).
LineMesh loadLinePrimitive(const LoaderContext& ctx, const tinygltf::Primitive& primitive, const std::string& what) {
  const int mode = primitive.mode;
  LineMesh lines;
  lines.points = mode == TINYGLTF_MODE_POINTS;
  const int positionAccessor = attributeAccessor(primitive, "POSITION");
  if (positionAccessor < 0) ctx.refuse(what + " has no POSITION attribute");
  const std::vector<glm::vec3> positions =
      toVectors<3>(readVertexAttribute(ctx, positionAccessor, what + " POSITION", 3, "POSITION"));
  for (size_t i = 0; i < positions.size(); ++i)
    if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z))
      ctx.refuse(what + " POSITION " + std::to_string(i) + " is not finite (NaN or Inf)");
  const std::vector<glm::vec4> colors = readColors(ctx, primitive, what, positions.size());
  std::vector<std::uint32_t> order;
  if (primitive.indices >= 0) {
    const std::vector<double> values =
        readAccessor(ctx, primitive.indices, what + " indices", 1,
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
    for (double v : values) {
      if (v >= static_cast<double>(positions.size()))
        ctx.refuse(what + " has index " + std::to_string(static_cast<std::uint64_t>(v)) + " but only " +
                   std::to_string(positions.size()) + " vertices");
      order.push_back(static_cast<std::uint32_t>(v));
    }
  } else {
    for (size_t i = 0; i < positions.size(); ++i) order.push_back(static_cast<std::uint32_t>(i));
  }
  std::vector<std::uint32_t> corners;  // points, or segment ends in pairs
  if (mode == TINYGLTF_MODE_POINTS) {
    corners = order;
  } else if (mode == TINYGLTF_MODE_LINE) {
    if (order.size() % 2 != 0)
      ctx.report.warnings.push_back(what + ": index count " + std::to_string(order.size()) +
                                    " is odd; the last partial line is ignored");
    corners.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(order.size() / 2 * 2));
  } else {
    for (size_t i = 1; i < order.size(); ++i) corners.insert(corners.end(), {order[i - 1], order[i]});
    if (mode == TINYGLTF_MODE_LINE_LOOP && order.size() > 2) corners.insert(corners.end(), {order.back(), order[0]});
  }
  if (corners.size() > ctx.limits.maxAccessorElements)
    ctx.refuse(what + " expands to " + std::to_string(corners.size()) + " vertices, over the limit");
  for (std::uint32_t c : corners) {
    lines.positions.push_back(positions[c]);
    if (!colors.empty()) lines.colors.push_back(colors[c]);
  }
  if (primitive.material >= 0 && static_cast<size_t>(primitive.material) >= ctx.model.materials.size())
    ctx.refuse(what + " refers to material " + std::to_string(primitive.material) + ", which does not exist");
  lines.material = primitive.material;
  return lines;
}

}  // namespace obscura::gltf
