// Compressed and quantized glTF geometry (scene/GltfCompression.h): the Draco copy of 2CylinderEngine against the
// uncompressed one, files compressed in the test with meshoptimizer's encoders (every mode, the octahedral filter,
// .gltf and .glb, fallback buffers without data), KHR_mesh_quantization's integer attributes, and the refusals.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "base/Error.h"
#include "scene/GltfLoader.h"

using namespace obscura;
using nlohmann::json;

namespace {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;

// A buffer whose data exists only meshopt-compressed (no uri).
const json kFallbackBuffer = {{"byteLength", 1 << 20},
                              {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}};

std::string refusal(const std::function<void()>& load) {
  try {
    load();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A glTF document with two buffers: buffer 0 holds plain data, buffer 1 the meshopt streams (or nothing).
struct Document {
  json doc = {{"asset", {{"version", "2.0"}}}, {"bufferViews", json::array()}, {"accessors", json::array()}};
  std::vector<std::uint8_t> bin;

  size_t append(const void* data, size_t bytes) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    bin.resize(offset + bytes);
    if (bytes) std::memcpy(bin.data() + offset, data, bytes);
    return offset;
  }
  int view(json v) {
    doc["bufferViews"].push_back(std::move(v));
    return static_cast<int>(doc["bufferViews"].size()) - 1;
  }
  int plainView(const void* data, size_t bytes, int stride = 0) {
    json v = {{"buffer", 0}, {"byteOffset", append(data, bytes)}, {"byteLength", bytes}};
    if (stride) v["byteStride"] = stride;
    return view(v);
  }
  // A view of `count` elements of `stride` bytes whose data lives only meshopt-compressed, in the fallback buffer 1.
  int meshoptView(const std::vector<unsigned char>& encoded, size_t count, size_t stride, const char* mode,
                  const char* filter = "NONE", bool attributes = true) {
    const size_t offset = append(encoded.data(), encoded.size());
    json ext = {{"buffer", 0},       {"byteOffset", offset}, {"byteLength", encoded.size()},
                {"byteStride", stride}, {"count", count},       {"mode", mode}};
    if (std::strcmp(filter, "NONE") != 0) ext["filter"] = filter;
    json v = {{"buffer", 1}, {"byteLength", count * stride}, {"extensions", {{"EXT_meshopt_compression", ext}}}};
    if (attributes) v["byteStride"] = stride;
    return view(v);
  }
  int accessor(int bufferView, int componentType, size_t count, const char* type, bool normalized = false) {
    json a = {{"bufferView", bufferView}, {"componentType", componentType}, {"count", count}, {"type", type}};
    if (normalized) a["normalized"] = true;
    doc["accessors"].push_back(a);
    return static_cast<int>(doc["accessors"].size()) - 1;
  }
  void scene(json primitive, json node = json::object()) {
    doc["meshes"] = json::array({{{"primitives", json::array({std::move(primitive)})}}});
    node["mesh"] = 0;
    doc["nodes"] = json::array({node});
    doc["scenes"] = json::array({{{"nodes", {0}}}});
    doc["scene"] = 0;
  }
  void uses(const char* extension, bool required) {
    doc["extensionsUsed"].push_back(extension);
    if (required) doc["extensionsRequired"].push_back(extension);
  }
  // As a .gltf with buffer 0 a side file and buffer 1 (if any) a meshopt fallback without data.
  Scene loadGltf(bool fallbackBuffer, GltfLoadReport* report = nullptr) const {
    json d = doc;
    d["buffers"] = json::array({{{"uri", "buffer.bin"}, {"byteLength", bin.size()}}});
    if (fallbackBuffer)
      d["buffers"].push_back(kFallbackBuffer);
    const std::string text = d.dump();
    return loadGltfMemory(std::vector<std::uint8_t>(text.begin(), text.end()), "compressed.gltf", {{"buffer.bin", bin}},
                          report);
  }
  // As a .glb: buffer 0 the BIN chunk.
  Scene loadGlb(bool fallbackBuffer) const {
    json d = doc;
    std::vector<std::uint8_t> chunk = bin;
    while (chunk.size() % 4) chunk.push_back(0);
    d["buffers"] = json::array({{{"byteLength", chunk.size()}}});
    if (fallbackBuffer)
      d["buffers"].push_back(kFallbackBuffer);
    std::string text = d.dump();
    while (text.size() % 4) text.push_back(' ');
    std::vector<std::uint8_t> glb(12);
    auto put32 = [&](std::uint32_t v) {
      const size_t at = glb.size();
      glb.resize(at + 4);
      std::memcpy(glb.data() + at, &v, 4);
    };
    std::memcpy(glb.data(), "glTF", 4);
    const std::uint32_t version = 2, total = static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + chunk.size());
    std::memcpy(glb.data() + 4, &version, 4);
    std::memcpy(glb.data() + 8, &total, 4);
    put32(static_cast<std::uint32_t>(text.size()));
    put32(0x4E4F534Au);
    glb.insert(glb.end(), text.begin(), text.end());
    put32(static_cast<std::uint32_t>(chunk.size()));
    put32(0x004E4942u);
    glb.insert(glb.end(), chunk.begin(), chunk.end());
    return loadGltfMemory(glb, "compressed.glb", {}, nullptr);
  }
};

// A grid of n x n vertices on a bumpy surface (distinct normals), as triangles.
struct Grid {
  std::vector<float> positions, normals;
  std::vector<std::uint32_t> indices;
  explicit Grid(int n) {
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const float u = float(x) / float(n - 1), v = float(y) / float(n - 1);
        positions.insert(positions.end(), {u, v, 0.1f * std::sin(6.0f * u) * std::cos(5.0f * v)});
        glm::vec3 normal = glm::normalize(glm::vec3(-0.6f * std::cos(6.0f * u) * std::cos(5.0f * v),
                                                    0.5f * std::sin(6.0f * u) * std::sin(5.0f * v), 1.0f));
        normals.insert(normals.end(), {normal.x, normal.y, normal.z});
      }
    for (int y = 0; y + 1 < n; ++y)
      for (int x = 0; x + 1 < n; ++x) {
        const std::uint32_t a = std::uint32_t(y * n + x), b = a + 1, c = a + std::uint32_t(n), d = c + 1;
        indices.insert(indices.end(), {a, b, d, a, d, c});
      }
  }
  size_t vertices() const { return positions.size() / 3; }
};

std::vector<unsigned char> encodeVertices(const void* data, size_t count, size_t stride) {
  std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(count, stride));
  out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, count, stride));
  return out;
}

// A meshopt grid: positions (ATTRIBUTES, float), normals (ATTRIBUTES with the OCTAHEDRAL filter, 4 bytes: signed
// normalized bytes under KHR_mesh_quantization), indices (TRIANGLES, or INDICES for `sequence`).
Document meshoptGrid(const Grid& grid, bool sequence) {
  Document d;
  d.uses("EXT_meshopt_compression", true);
  d.uses("KHR_mesh_quantization", true);
  const size_t n = grid.vertices();
  const int positions = d.accessor(d.meshoptView(encodeVertices(grid.positions.data(), n, 12), n, 12, "ATTRIBUTES"),
                                   kFloat, n, "VEC3");
  std::vector<float> normalsWithW;  // the encoder reads 4 floats per vector
  for (size_t i = 0; i < n; ++i)
    normalsWithW.insert(normalsWithW.end(),
                        {grid.normals[3 * i], grid.normals[3 * i + 1], grid.normals[3 * i + 2], 0.0f});
  std::vector<std::int8_t> octahedral(n * 4);
  meshopt_encodeFilterOct(octahedral.data(), n, 4, 8, normalsWithW.data());
  const int normals = d.accessor(d.meshoptView(encodeVertices(octahedral.data(), n, 4), n, 4, "ATTRIBUTES",
                                               "OCTAHEDRAL"),
                                 kByte, n, "VEC3", true);
  std::vector<unsigned char> encodedIndices;
  if (sequence) {
    encodedIndices.resize(meshopt_encodeIndexSequenceBound(grid.indices.size(), n));
    encodedIndices.resize(meshopt_encodeIndexSequence(encodedIndices.data(), encodedIndices.size(),
                                                      grid.indices.data(), grid.indices.size()));
  } else {
    encodedIndices.resize(meshopt_encodeIndexBufferBound(grid.indices.size(), n));
    encodedIndices.resize(meshopt_encodeIndexBuffer(encodedIndices.data(), encodedIndices.size(), grid.indices.data(),
                                                    grid.indices.size()));
  }
  const int indices = d.accessor(d.meshoptView(encodedIndices, grid.indices.size(), 4,
                                               sequence ? "INDICES" : "TRIANGLES", "NONE", false),
                                 kUnsignedInt, grid.indices.size(), "SCALAR");
  d.scene({{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}}, {"indices", indices}});
  return d;
}

void expectGridGeometry(const Scene& scene, const Grid& grid, const char* what) {
  ASSERT_EQ(scene.meshes.size(), 1u) << what;
  const Mesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.positions.size(), grid.vertices()) << what;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 expected(grid.positions[3 * i], grid.positions[3 * i + 1], grid.positions[3 * i + 2]);
    ASSERT_EQ(mesh.positions[i], expected) << what << " vertex " << i;  // lossless
    const glm::vec3 normal(grid.normals[3 * i], grid.normals[3 * i + 1], grid.normals[3 * i + 2]);
    // 8-bit octahedral: within 2 degrees (the extension's 8-bit encoding is about 1 degree).
    ASSERT_GT(glm::dot(mesh.normals[i], normal), std::cos(glm::radians(2.0f))) << what << " normal " << i;
  }
  // meshopt_encodeIndexBuffer may rotate a triangle's corners (keeping its winding): compare rotations.
  ASSERT_EQ(mesh.indices.size(), grid.indices.size()) << what;
  auto rotated = [](const std::uint32_t* t) {
    const int first = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
    return std::array<std::uint32_t, 3>{t[first], t[(first + 1) % 3], t[(first + 2) % 3]};
  };
  for (size_t t = 0; t < mesh.indices.size(); t += 3)
    ASSERT_EQ(rotated(&mesh.indices[t]), rotated(&grid.indices[t])) << what << " triangle " << t / 3;
}

}  // namespace

TEST(GltfCompression, MeshoptFilesMadeWithTheEncoderLoadAsTheirSource) {
  const Grid grid(17);
  expectGridGeometry(meshoptGrid(grid, false).loadGltf(true), grid, ".gltf, TRIANGLES");
  expectGridGeometry(meshoptGrid(grid, true).loadGltf(true), grid, ".gltf, INDICES");
  expectGridGeometry(meshoptGrid(grid, false).loadGlb(true), grid, ".glb, TRIANGLES");
}

TEST(GltfCompression, BrokenMeshoptStreamsAreRefusedWithOneLine) {
  const Grid grid(9);
  {  // truncated: the stream ends early
    Document d = meshoptGrid(grid, false);
    d.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 20;
    const std::string message = refusal([&] { d.loadGltf(true); });
    EXPECT_NE(message.find("bufferView 0 EXT_meshopt_compression: the compressed data is malformed"), std::string::npos)
        << message;
  }
  {  // a count no stream can hold, over the limit: refused before decoding
    Document d = meshoptGrid(grid, false);
    d.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 1 << 30;
    const std::string message = refusal([&] { d.loadGltf(true); });
    EXPECT_NE(message.find("over the limit"), std::string::npos) << message;
  }
  {  // a source range past its buffer
    Document d = meshoptGrid(grid, false);
    d.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteOffset"] = 1 << 24;
    const std::string message = refusal([&] { d.loadGltf(true); });
    EXPECT_NE(message.find("spans bytes"), std::string::npos) << message;
  }
  {  // an unknown mode, and a filter with the wrong stride
    Document d = meshoptGrid(grid, false);
    d.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["mode"] = "VERTICES";
    EXPECT_NE(refusal([&] { d.loadGltf(true); }).find("has mode 'VERTICES'"), std::string::npos);
    Document e = meshoptGrid(grid, false);
    e.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["filter"] = "QUATERNION";
    EXPECT_NE(refusal([&] { e.loadGltf(true); }).find("QUATERNION needs byteStride 8"), std::string::npos);
  }
  // Every message is one line naming the file.
  Document d = meshoptGrid(grid, false);
  d.doc["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 3;
  const std::string message = refusal([&] { d.loadGltf(true); });
  EXPECT_EQ(message.rfind("compressed.gltf: ", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// KHR_mesh_quantization: positions as unnormalized unsigned shorts under a node scale, normals as normalized bytes,
// texture coordinates as unnormalized bytes (scaled by KHR_texture_transform), morph deltas as normalized shorts.
TEST(GltfCompression, QuantizedAttributesReadAsTheExtensionSays) {
  Document d;
  d.uses("KHR_mesh_quantization", true);
  const std::vector<std::uint16_t> positions = {0, 0, 0, 0, 1000, 0, 0, 0, 1000, 1000, 0, 0, 0, 1000, 0, 0};  // padded
  const std::vector<std::int8_t> normals = {0, 0, 127, 0, 0, 0, 0, 0, 127, 0, 0, 0,
                                            0, 0, 127, 0, 0, 0, 0, 0, 127, 0, 0, 0};  // VEC3 padded to 4 bytes
  const std::vector<std::uint8_t> uvs = {0, 0, 0, 0, 4, 0, 0, 0, 4, 4, 0, 0, 0, 4, 0, 0};  // padded
  const std::vector<std::int16_t> deltas = {0, 0, 0, 0, 0, 0, 0, 0, 16383, 0, 0, 0};  // vertex 2 moves +0.5 z
  const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3};
  const int p = d.accessor(d.plainView(positions.data(), positions.size() * 2, 8), kUnsignedShort, 4, "VEC3");
  const int n = d.accessor(d.plainView(normals.data(), normals.size(), 4), kByte, 4, "VEC3", true);
  const int t = d.accessor(d.plainView(uvs.data(), uvs.size(), 4), kUnsignedByte, 4, "VEC2");
  const int m = d.accessor(d.plainView(deltas.data(), deltas.size() * 2), kShort, 4, "VEC3", true);
  const int i = d.accessor(d.plainView(indices.data(), indices.size() * 2), kUnsignedShort, 6, "SCALAR");
  d.scene({{"attributes", {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", t}}},
           {"targets", json::array({{{"POSITION", m}}})},
           {"indices", i}},
          {{"scale", {0.001, 0.001, 0.001}}});
  const Scene scene = d.loadGltf(false);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& mesh = scene.meshes[0];
  EXPECT_EQ(mesh.positions[2], glm::vec3(1000.0f, 1000.0f, 0.0f));
  EXPECT_EQ(mesh.normals[1], glm::vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(mesh.texcoords[2], glm::vec2(4.0f, 4.0f));
  ASSERT_EQ(mesh.morphTargets.size(), 1u);
  EXPECT_NEAR(mesh.morphTargets[0].positions[2].z, 0.5f, 1e-4f);
  const Bounds bounds = scene.worldBounds();
  EXPECT_NEAR(bounds.max.x, 1.0f, 1e-6f);

  // Without the extension, the same file is refused: integer positions are not glTF 2.0.
  Document plain = d;
  plain.doc.erase("extensionsUsed");
  plain.doc.erase("extensionsRequired");
  const std::string message = refusal([&] { plain.loadGltf(false); });
  EXPECT_NE(message.find("POSITION (accessor 0) has component type UNSIGNED_SHORT"), std::string::npos) << message;
  // Normals must be normalized even under the extension.
  Document raw = d;
  raw.doc["accessors"][1].erase("normalized");
  EXPECT_NE(refusal([&] { raw.loadGltf(false); }).find("NORMAL (accessor 1) has component type BYTE without"),
            std::string::npos);
}

// Debian's assimp-testmodels has 2CylinderEngine twice: as a .glb and Draco-compressed. The Draco copy decodes to
// the same scene within its quantisation (positions quantised to 14 bits of the model's extent, normals to 10).
TEST(GltfCompression, DracoEngineMatchesTheUncompressedOne) {
  GltfLoadReport report;
  const Scene draco = loadGltfFile(test::assimpModels() + "/draco/2CylinderEngine.gltf", &report);
  const Scene plain = loadGltfFile(test::assimpModels() + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  ASSERT_EQ(draco.instances.size(), plain.instances.size());
  ASSERT_EQ(draco.meshes.size(), plain.meshes.size());
  const Bounds a = draco.worldBounds(), b = plain.worldBounds();
  const float extent = glm::length(b.max - b.min);
  EXPECT_LT(glm::length(a.min - b.min), 1e-3f * extent);
  EXPECT_LT(glm::length(a.max - b.max), 1e-3f * extent);
  // Triangle for triangle: Draco may reorder vertices and faces, so compare each mesh's area and centroid.
  for (size_t m = 0; m < draco.meshes.size(); ++m) {
    auto summary = [](const Mesh& mesh) {
      double area = 0.0;
      glm::dvec3 centroid(0.0);
      for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::dvec3 p0 = mesh.positions[mesh.indices[t]], p1 = mesh.positions[mesh.indices[t + 1]],
                         p2 = mesh.positions[mesh.indices[t + 2]];
        const double triangle = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
        area += triangle;
        centroid += triangle * (p0 + p1 + p2) / 3.0;
      }
      return std::make_pair(area, area > 0.0 ? centroid / area : centroid);
    };
    const auto [areaDraco, centroidDraco] = summary(draco.meshes[m]);
    const auto [areaPlain, centroidPlain] = summary(plain.meshes[m]);
    EXPECT_NEAR(areaDraco, areaPlain, 0.01 * areaPlain + 1e-6 * extent * extent) << "mesh " << m;
    EXPECT_LT(glm::length(centroidDraco - centroidPlain), 2e-3 * extent) << "mesh " << m;
  }
  EXPECT_NEAR(double(draco.triangleCount()), double(plain.triangleCount()), 0.001 * double(plain.triangleCount()));
}

TEST(GltfCompression, BrokenDracoDataIsRefusedWithOneLine) {
  // The engine's .bin cut short: the Draco streams no longer decode.
  const std::string dir = test::assimpModels() + "/draco/";
  auto read = [](const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(file), {});
  };
  const std::vector<std::uint8_t> gltf = read(dir + "2CylinderEngine.gltf");
  std::vector<std::uint8_t> bin = read(dir + "2CylinderEngine.bin");
  ASSERT_GT(bin.size(), 1000u);
  for (size_t i = 0; i < bin.size(); i += 7) bin[i] = static_cast<std::uint8_t>(bin[i] ^ 0x5A);  // scrambled
  const std::string message = refusal([&] { loadGltfMemory(gltf, "engine.gltf", {{"2CylinderEngine.bin", bin}}); });
  ASSERT_FALSE(message.empty()) << "a scrambled Draco stream was accepted";
  EXPECT_EQ(message.rfind("engine.gltf: ", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}
