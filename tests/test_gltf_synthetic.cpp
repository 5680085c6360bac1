// The glTF loader on small files built in the test, one feature or one fault at a time: index types, node
// transforms, generated normals, texture coordinates and their KHR_texture_transform, materials, sparse accessors,
// and the refusals the assimp corpus has no file for (strides, component types, ranges, absurd counts).
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cmath>
#include <cstring>
#include <functional>

#include <nlohmann/json.hpp>

#include "base/Error.h"
#include "scene/GltfLoader.h"

using namespace obscura;
using nlohmann::json;

namespace {

constexpr int kUnsignedByte = 5121, kUnsignedShort = 5123, kUnsignedInt = 5125, kFloat = 5126;

// A .gltf document whose one buffer ("buffer.bin") is handed to the loader as a side file.
class GltfBuilder {
 public:
  GltfBuilder() {
    doc_["asset"] = {{"version", "2.0"}};
    doc_["bufferViews"] = json::array();
    doc_["accessors"] = json::array();
    doc_["meshes"] = json::array();
    doc_["nodes"] = json::array();
  }

  // Appends raw bytes (4-byte aligned) as a buffer view; returns its index.
  int view(const void* data, size_t bytes, int stride = 0) {
    while (bin_.size() % 4) bin_.push_back(0);
    const size_t offset = bin_.size();
    bin_.resize(offset + bytes);
    std::memcpy(bin_.data() + offset, data, bytes);
    json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
    if (stride) v["byteStride"] = stride;
    doc_["bufferViews"].push_back(v);
    return static_cast<int>(doc_["bufferViews"].size()) - 1;
  }
  template <typename T>
  int view(const std::vector<T>& values, int stride = 0) {
    return view(values.data(), values.size() * sizeof(T), stride);
  }

  int accessor(int bufferView, int componentType, size_t count, const char* type, size_t byteOffset = 0) {
    json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
    if (bufferView >= 0) a["bufferView"] = bufferView;
    if (byteOffset) a["byteOffset"] = byteOffset;
    doc_["accessors"].push_back(a);
    return static_cast<int>(doc_["accessors"].size()) - 1;
  }
  int floats(const std::vector<float>& values, const char* type, int components) {
    return accessor(view(values), kFloat, values.size() / static_cast<size_t>(components), type);
  }

  // A mesh of one primitive; returns the node that places it (with `node` merged in: matrix, TRS, children).
  int meshNode(json attributes, int indices = -1, int material = -1, json node = json::object()) {
    json primitive = {{"attributes", std::move(attributes)}};
    if (indices >= 0) primitive["indices"] = indices;
    if (material >= 0) primitive["material"] = material;
    doc_["meshes"].push_back({{"primitives", json::array({primitive})}});
    node["mesh"] = doc_["meshes"].size() - 1;
    return addNode(std::move(node));
  }
  int addNode(json node) {
    doc_["nodes"].push_back(std::move(node));
    return static_cast<int>(doc_["nodes"].size()) - 1;
  }

  json& doc() { return doc_; }

  Scene load(GltfLoadReport* report = nullptr, const GltfLimits& limits = {}) {
    json doc = doc_;
    doc["buffers"] = json::array({{{"uri", "buffer.bin"}, {"byteLength", bin_.size()}}});
    if (!doc.contains("scenes")) {
      json roots = json::array();
      std::vector<bool> isChild(doc["nodes"].size(), false);
      for (const json& n : doc["nodes"])
        if (n.contains("children"))
          for (const json& c : n["children"]) isChild[c.get<size_t>()] = true;
      for (size_t i = 0; i < isChild.size(); ++i)
        if (!isChild[i]) roots.push_back(i);
      doc["scenes"] = json::array({{{"nodes", roots}}});
      doc["scene"] = 0;
    }
    const std::string text = doc.dump();
    return loadGltfMemory(std::vector<std::uint8_t>(text.begin(), text.end()), "synthetic.gltf",
                          {{"buffer.bin", bin_}}, report, limits);
  }

  std::string refusal(const GltfLimits& limits = {}) {
    try {
      load(nullptr, limits);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

 private:
  json doc_;
  std::vector<std::uint8_t> bin_;
};

// A unit quad in the XY plane, counter-clockwise seen from +z: two triangles over four vertices.
const std::vector<float> kQuad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<std::uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

long peakResidentKilobytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

void expectNear(const glm::vec3& actual, const glm::vec3& expected, const std::string& what) {
  EXPECT_NEAR(actual.x, expected.x, 1e-5f) << what;
  EXPECT_NEAR(actual.y, expected.y, 1e-5f) << what;
  EXPECT_NEAR(actual.z, expected.z, 1e-5f) << what;
}

}  // namespace

TEST(GltfSynthetic, ReadsEveryIndexTypeAndNonIndexedPrimitives) {
  const std::vector<std::uint8_t> u8(kQuadIndices.begin(), kQuadIndices.end());
  const std::vector<std::uint16_t> u16(kQuadIndices.begin(), kQuadIndices.end());
  for (int type : {kUnsignedByte, kUnsignedShort, kUnsignedInt}) {
    GltfBuilder gltf;
    const int indexView = type == kUnsignedByte    ? gltf.view(u8)
                          : type == kUnsignedShort ? gltf.view(u16)
                                                   : gltf.view(kQuadIndices);
    gltf.meshNode({{"POSITION", gltf.floats(kQuad, "VEC3", 3)}}, gltf.accessor(indexView, type, 6, "SCALAR"));
    const Scene scene = gltf.load();
    ASSERT_EQ(scene.meshes.size(), 1u) << type;
    EXPECT_EQ(scene.triangleCount(), 2u) << type;
    // Normals are generated (flat), which unshares the vertices: each triangle keeps its corners, in order.
    const Mesh& mesh = scene.meshes[0];
    ASSERT_EQ(mesh.indices.size(), 6u);
    for (size_t k = 0; k < 6; ++k) {
      const float* expected = &kQuad[kQuadIndices[k] * 3];
      expectNear(mesh.positions[mesh.indices[k]], glm::vec3(expected[0], expected[1], expected[2]),
                 "index type " + std::to_string(type) + ", corner " + std::to_string(k));
    }
  }
  // The same two triangles without an index accessor: six vertices drawn in order.
  std::vector<float> soup;
  for (std::uint32_t index : kQuadIndices) soup.insert(soup.end(), &kQuad[index * 3], &kQuad[index * 3] + 3);
  GltfBuilder gltf;
  gltf.meshNode({{"POSITION", gltf.floats(soup, "VEC3", 3)}});
  const Scene scene = gltf.load();
  EXPECT_EQ(scene.triangleCount(), 2u);
}

TEST(GltfSynthetic, GeneratesNormalsFacingTheWindingWhenNormalIsMissing) {
  GltfBuilder gltf;
  gltf.meshNode({{"POSITION", gltf.floats(kQuad, "VEC3", 3)}},
                gltf.accessor(gltf.view(kQuadIndices), kUnsignedInt, 6, "SCALAR"));
  const Scene scene = gltf.load();
  ASSERT_FALSE(scene.meshes[0].normals.empty());
  for (const glm::vec3& n : scene.meshes[0].normals) expectNear(n, glm::vec3(0, 0, 1), "counter-clockwise from +z");
}

TEST(GltfSynthetic, AppliesTranslationRotationScaleInThatOrder) {
  GltfBuilder gltf;
  const float h = std::sqrt(0.5f);
  // 90 degrees about z, x scaled by 2, then moved: (1,0,0) -> S (2,0,0) -> R (0,2,0) -> T (1,4,3).
  gltf.meshNode({{"POSITION", gltf.floats(kQuad, "VEC3", 3)}},
                gltf.accessor(gltf.view(kQuadIndices), kUnsignedInt, 6, "SCALAR"), -1,
                {{"translation", {1, 2, 3}}, {"rotation", {0, 0, h, h}}, {"scale", {2, 1, 1}}});
  const Scene scene = gltf.load();
  ASSERT_EQ(scene.instances.size(), 1u);
  const glm::vec4 x = scene.instances[0].world * glm::vec4(1, 0, 0, 1);
  expectNear(glm::vec3(x), glm::vec3(1, 4, 3), "T * R * S applied to (1, 0, 0)");
}

TEST(GltfSynthetic, ReadsAColumnMajorMatrixAndComposesParentsFirst) {
  GltfBuilder gltf;
  // Columns: x -> x, y -> (0.5, 1, 0) (a shear that a transposed read would put elsewhere), z -> z, then (5, 6, 7).
  const json matrix = {1, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
  const int child = gltf.meshNode({{"POSITION", gltf.floats(kQuad, "VEC3", 3)}}, -1, -1, {{"matrix", matrix}});
  gltf.addNode({{"translation", {10, 0, 0}}, {"scale", {2, 2, 2}}, {"children", {child}}});
  const Scene scene = gltf.load();
  ASSERT_EQ(scene.instances.size(), 1u);
  // (0, 1, 0) -> child (5.5, 7, 7) -> parent 2 * that + (10, 0, 0).
  const glm::vec4 p = scene.instances[0].world * glm::vec4(0, 1, 0, 1);
  expectNear(glm::vec3(p), glm::vec3(21, 14, 14), "parent * child matrix applied to (0, 1, 0)");
}

TEST(GltfSynthetic, ReadsTexcoordsMaterialsAndTheirTextureTransform) {
  GltfBuilder gltf;
  const std::vector<float> uv = {0, 0, 1, 0, 1, 1, 0, 1};
  const int positions = gltf.floats(kQuad, "VEC3", 3), texcoords = gltf.floats(uv, "VEC2", 2);
  const int indices = gltf.accessor(gltf.view(kQuadIndices), kUnsignedInt, 6, "SCALAR");
  const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const int normal = gltf.floats(normals, "VEC3", 3);
  // One 1x1 PNG is enough for a texture to exist; the loader is checked for what it reads, not for the pixels.
  static const std::uint8_t kPng[] = {
      0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
      0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1F, 0x15, 0xC4, 0x89, 0x00, 0x00, 0x00,
      0x0D, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9C, 0x63, 0xF8, 0xCF, 0xC0, 0xF0, 0x1F, 0x00, 0x05, 0x00, 0x01, 0xFF,
      0x89, 0x99, 0x3D, 0x1D, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82};
  gltf.doc()["images"] = json::array({{{"bufferView", gltf.view(kPng, sizeof kPng)}, {"mimeType", "image/png"}}});
  gltf.doc()["textures"] = json::array({{{"source", 0}}});
  const float quarterTurn = 1.5707963f;
  gltf.doc()["materials"] = json::array(
      {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.25, 0.5, 0.75, 0.6}}}},
        {"alphaMode", "MASK"},
        {"alphaCutoff", 0.3},
        {"doubleSided", true}},
       {{"pbrMetallicRoughness",
         {{"baseColorTexture",
           {{"index", 0},
            {"extensions",
             {{"KHR_texture_transform",
               {{"offset", {0.5, 0.25}}, {"rotation", quarterTurn}, {"scale", {2, 4}}}}}}}}}}}});
  gltf.doc()["extensionsUsed"] = {"KHR_texture_transform"};
  gltf.doc()["extensionsRequired"] = {"KHR_texture_transform"};
  // Both primitives share the TEXCOORD_0 accessor; only the second material transforms it.
  gltf.meshNode({{"POSITION", positions}, {"NORMAL", normal}, {"TEXCOORD_0", texcoords}}, indices, 0);
  gltf.meshNode({{"POSITION", positions}, {"NORMAL", normal}, {"TEXCOORD_0", texcoords}}, indices, 1);
  const Scene scene = gltf.load();
  ASSERT_EQ(scene.meshes.size(), 2u);
  ASSERT_EQ(scene.materials.size(), 2u);

  const Material& masked = scene.materials[0];
  EXPECT_EQ(masked.baseColorFactor, glm::vec4(0.25f, 0.5f, 0.75f, 0.6f));
  EXPECT_EQ(masked.alphaMode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(masked.alphaCutoff, 0.3f);
  EXPECT_TRUE(masked.doubleSided);
  EXPECT_EQ(masked.baseColorTexture, -1);
  EXPECT_EQ(scene.materials[1].baseColorTexture, 0);
  EXPECT_EQ(scene.materials[1].alphaMode, AlphaMode::Opaque);

  const Mesh& plain = scene.meshes[static_cast<size_t>(scene.meshes[0].material == 0 ? 0 : 1)];
  const Mesh& transformed = scene.meshes[static_cast<size_t>(scene.meshes[0].material == 0 ? 1 : 0)];
  ASSERT_EQ(plain.texcoords.size(), 4u);
  ASSERT_EQ(transformed.texcoords.size(), 4u);
  for (size_t v = 0; v < 4; ++v) {
    const glm::vec2 in(uv[2 * v], uv[2 * v + 1]);
    EXPECT_EQ(plain.texcoords[v], in) << "vertex " << v;
    // Scale (2, 4), then the quarter turn u' = cos u + sin v = v, v' = -sin u + cos v = -u, then the offset.
    const glm::vec2 scaled(2.0f * in.x, 4.0f * in.y);
    const glm::vec2 expected(scaled.y + 0.5f, -scaled.x + 0.25f);
    EXPECT_NEAR(transformed.texcoords[v].x, expected.x, 1e-5f) << "vertex " << v;
    EXPECT_NEAR(transformed.texcoords[v].y, expected.y, 1e-5f) << "vertex " << v;
  }
}

TEST(GltfSynthetic, AppliesSparseSubstitutions) {
  GltfBuilder gltf;
  const int positions = gltf.floats(kQuad, "VEC3", 3);
  const std::vector<std::uint16_t> which = {2};
  const std::vector<float> moved = {3, 3, 0};
  gltf.doc()["accessors"][static_cast<size_t>(positions)]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", gltf.view(which)}, {"componentType", kUnsignedShort}}},
      {"values", {{"bufferView", gltf.view(moved)}}}};
  gltf.meshNode({{"POSITION", positions}}, gltf.accessor(gltf.view(kQuadIndices), kUnsignedInt, 6, "SCALAR"));
  const Scene scene = gltf.load();
  Bounds bounds = scene.worldBounds();
  expectNear(bounds.max, glm::vec3(3, 3, 0), "vertex 2 replaced by (3, 3, 0)");
}

TEST(GltfSynthetic, RefusesFaultsTheCorpusDoesNotCoverWithOneLine) {
  struct Case {
    const char* name;
    std::function<void(GltfBuilder&)> build;
    const char* expect;
  };
  const std::vector<Case> cases = {
      {"stride below the element size",
       [](GltfBuilder& g) {
         g.meshNode({{"POSITION", g.accessor(g.view(kQuad, 8), kFloat, 4, "VEC3")}});
       },
       "has byteStride 8, expected a multiple of 4 in 12 .. 252"},
      {"stride not a multiple of 4",
       [](GltfBuilder& g) {
         std::vector<std::uint8_t> bytes(14 * 4, 0);
         g.meshNode({{"POSITION", g.accessor(g.view(bytes, 14), kFloat, 4, "VEC3")}});
       },
       "byteStride"},  // tinygltf refuses it while parsing, with its own words
      {"POSITION of unsigned bytes",
       [](GltfBuilder& g) {
         std::vector<std::uint8_t> bytes(12, 1);
         g.meshNode({{"POSITION", g.accessor(g.view(bytes), kUnsignedByte, 4, "VEC3")}});
       },
       "POSITION (accessor 0) has component type UNSIGNED_BYTE"},
      {"float indices",
       [](GltfBuilder& g) {
         const std::vector<float> indices = {0, 1, 2};
         g.meshNode({{"POSITION", g.floats(kQuad, "VEC3", 3)}}, g.accessor(g.view(indices), kFloat, 3, "SCALAR"));
       },
       "has component type FLOAT"},
      {"attribute past its buffer view",
       [](GltfBuilder& g) {
         g.meshNode({{"POSITION", g.accessor(g.view(kQuad), kFloat, 4, "VEC3", 8)}});
       },
       "reads up to byte 56 of bufferView 0, which holds 48"},
      {"index past the vertices",
       [](GltfBuilder& g) {
         const std::vector<std::uint16_t> indices = {0, 1, 4};
         g.meshNode({{"POSITION", g.floats(kQuad, "VEC3", 3)}},
                    g.accessor(g.view(indices), kUnsignedShort, 3, "SCALAR"));
       },
       "index 4"},
      {"integer texture coordinates that are not normalised",
       [](GltfBuilder& g) {
         const std::vector<std::uint8_t> uv(8, 1);
         g.meshNode({{"POSITION", g.floats(kQuad, "VEC3", 3)},
                     {"TEXCOORD_0", g.accessor(g.view(uv), kUnsignedByte, 4, "VEC2")}});
       },
       "TEXCOORD_0 (accessor 1) has component type UNSIGNED_BYTE without normalized: true"},
      {"normal count differs from the positions",
       [](GltfBuilder& g) {
         const std::vector<float> normals = {0, 0, 1};
         g.meshNode({{"POSITION", g.floats(kQuad, "VEC3", 3)}, {"NORMAL", g.floats(normals, "VEC3", 3)}});
       },
       "has 1 normals for 4 positions"},
  };
  for (const Case& c : cases) {
    GltfBuilder gltf;
    c.build(gltf);
    const std::string message = gltf.refusal();
    EXPECT_EQ(message.rfind("synthetic.gltf: ", 0), 0u) << c.name << ": " << message;
    EXPECT_NE(message.find(c.expect), std::string::npos) << c.name << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << c.name << ": " << message;
  }
}

// A few bytes declaring an accessor of 30 million elements over a 48-byte buffer are refused on the bounds check,
// before anything of that size is allocated (with the production limits, which allow the count itself). Reading
// the accessor first would fill 720 MB of doubles, which the process's peak resident size would show.
TEST(GltfSynthetic, AHugeCountOverAShortBufferIsRefusedBeforeAllocating) {
  GltfBuilder gltf;
  gltf.meshNode({{"POSITION", gltf.accessor(gltf.view(kQuad), kFloat, 30'000'000, "VEC3")}});
  const long peakBefore = peakResidentKilobytes();
  const std::string message = gltf.refusal();
  const long grownMegabytes = (peakResidentKilobytes() - peakBefore) / 1024;
  EXPECT_NE(message.find("reads up to byte 360000000 of bufferView 0, which holds 48"), std::string::npos) << message;
  EXPECT_LT(grownMegabytes, 100) << "the peak resident size grew by " << grownMegabytes << " MB";
}
