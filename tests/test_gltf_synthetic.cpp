// The glTF loader on small files built in the test, one feature or one fault at a time: index types, node
// transforms, generated normals, texture coordinates and their KHR_texture_transform, materials, sparse accessors,
// the node hierarchy, skins, morph targets and animations, and the refusals the assimp corpus has no file for
// (strides, component types, ranges, absurd counts, and what moves: joints, key times and values, sampler counts).
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

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;

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
  // Integers of type T as an accessor of `componentType`, normalised or not.
  template <typename T>
  int integers(const std::vector<T>& values, int componentType, const char* type, int components, bool normalized) {
    const int index = accessor(view(values), componentType, values.size() / static_cast<size_t>(components), type);
    if (normalized) doc_["accessors"][static_cast<size_t>(index)]["normalized"] = true;
    return index;
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

// tinygltf 2.7 checks a .glb's BIN chunk against the file without the chunk's 8-byte header, and would copy a buffer
// from up to 8 bytes past the end of the file: a chunk that claims those bytes is refused first (the fuzzer found it
// through a mended meshopt file, kept in tests/fuzz/regressions). The same file with the chunk's true length loads.
TEST(GltfSynthetic, AGlbWhoseBinChunkRunsPastTheEndOfTheFileIsRefused) {
  auto glb = [](std::uint32_t declaredBinLength) {
    std::string text = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":)" + std::to_string(declaredBinLength) +
                       "}]}";
    while (text.size() % 4) text += ' ';
    const std::uint32_t binLength = 8;  // the bytes the file holds
    std::vector<std::uint8_t> out(20 + text.size() + 8 + binLength, 0);
    const std::uint32_t header[5] = {0x46546C67u, 2, static_cast<std::uint32_t>(out.size()),
                                     static_cast<std::uint32_t>(text.size()), 0x4E4F534Au};
    std::memcpy(out.data(), header, sizeof(header));
    std::memcpy(out.data() + 20, text.data(), text.size());
    const std::uint32_t chunk[2] = {declaredBinLength, 0x004E4942u};
    std::memcpy(out.data() + 20 + text.size(), chunk, sizeof(chunk));
    return out;
  };
  auto refusal = [](const std::vector<std::uint8_t>& bytes) {
    try {
      loadGltfMemory(bytes, "chunks.glb");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  const std::string pastTheEnd = refusal(glb(16));
  EXPECT_NE(pastTheEnd.find("chunks.glb: the BIN chunk's 16 bytes run past the end of the file"), std::string::npos)
      << pastTheEnd;
  EXPECT_EQ(refusal(glb(8)), "loaded") << "a file without geometry loads (with a warning)";
}

// ---- What moves: the node hierarchy, skins, morph targets, animations (issue 13) ----

namespace {

const std::vector<float> kQuadNormals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};

json quadAttributes(GltfBuilder& g) {
  return {{"POSITION", g.floats(kQuad, "VEC3", 3)}, {"NORMAL", g.floats(kQuadNormals, "VEC3", 3)}};
}
int quadIndices(GltfBuilder& g) { return g.accessor(g.view(kQuadIndices), kUnsignedInt, 6, "SCALAR"); }

// A sampler (as JSON) over float key times and float values of `type`.
json sampler(GltfBuilder& g, const std::vector<float>& times, const std::vector<float>& values, const char* type,
             int components, const char* interpolation = "LINEAR") {
  return {{"input", g.floats(times, "SCALAR", 1)},
          {"output", g.floats(values, type, components)},
          {"interpolation", interpolation}};
}
json channel(int samplerIndex, int node, const char* path) {
  return {{"sampler", samplerIndex}, {"target", {{"node", node}, {"path", path}}}};
}
void addAnimation(GltfBuilder& g, json samplers, json channels, const char* name = "") {
  // A braced single element ({sampler(...)}) is an array of it under GCC and the element itself under clang
  // (nlohmann's initializer lists): both are taken as a list of one.
  if (!samplers.is_array()) samplers = json::array({samplers});
  if (!channels.is_array()) channels = json::array({channels});
  if (!g.doc().contains("animations")) g.doc()["animations"] = json::array();
  json animation = {{"samplers", std::move(samplers)}, {"channels", std::move(channels)}};
  if (*name) animation["name"] = name;
  g.doc()["animations"].push_back(std::move(animation));
}

// The unit quad skinned to a two-joint chain: node 0 places the mesh with skin 0; node 1 ("hip", at the origin) is
// the root joint, node 2 ("knee", one up) its child. Vertices 0 and 1 follow the hip, 2 and 3 the knee, unless the
// caller gives other joints and weights.
struct SkinnedQuad {
  int meshNode = 0, hip = 1, knee = 2;
};
SkinnedQuad addSkinnedQuad(GltfBuilder& g,
                           const std::vector<std::uint8_t>& joints = {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0},
                           const std::vector<float>& weights = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}) {
  json attributes = quadAttributes(g);
  attributes["JOINTS_0"] = g.integers(joints, kUnsignedByte, "VEC4", 4, false);
  attributes["WEIGHTS_0"] = g.floats(weights, "VEC4", 4);
  SkinnedQuad quad;
  quad.meshNode = g.meshNode(attributes, quadIndices(g), -1, {{"skin", 0}});
  quad.knee = g.addNode({{"name", "knee"}, {"translation", {0, 1, 0}}});
  quad.hip = g.addNode({{"name", "hip"}, {"children", {quad.knee}}});
  // Inverse bind matrices (column-major): identity for the hip, a move down by one for the knee.
  const std::vector<float> inverseBind = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                                          1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
  g.doc()["skins"] = json::array(
      {{{"joints", {quad.hip, quad.knee}}, {"inverseBindMatrices", g.floats(inverseBind, "MAT4", 16)},
        {"skeleton", quad.hip}, {"name", "legs"}}});
  return quad;
}

// The quad with two morph targets: target 0 moves vertex 2 by +z (dense POSITION, with NORMAL deltas), target 1
// moves vertex 3 by +x (a sparse POSITION accessor without a buffer view).
int addMorphedQuad(GltfBuilder& g, json node = json::object(), json meshWeights = json()) {
  const std::vector<float> lift = {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0};
  const std::vector<float> tilt = {0, 0, 0, 0, 0, 0, 0, -0.5f, 0, 0, 0, 0};
  const int sparse = g.accessor(-1, kFloat, 4, "VEC3");
  const std::vector<std::uint8_t> which = {3};
  const std::vector<float> moved = {1, 0, 0};
  g.doc()["accessors"][static_cast<size_t>(sparse)]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", g.view(which)}, {"componentType", kUnsignedByte}}},
      {"values", {{"bufferView", g.view(moved)}}}};
  json primitive = {{"attributes", quadAttributes(g)},
                    {"indices", quadIndices(g)},
                    {"targets", {{{"POSITION", g.floats(lift, "VEC3", 3)}, {"NORMAL", g.floats(tilt, "VEC3", 3)}},
                                 {{"POSITION", sparse}}}}};
  json mesh = {{"primitives", {primitive}}};
  if (!meshWeights.is_null()) mesh["weights"] = meshWeights;
  g.doc()["meshes"].push_back(mesh);
  node["mesh"] = g.doc()["meshes"].size() - 1;
  return g.addNode(node);
}

bool hasWarning(const GltfLoadReport& report, const std::string& fragment) {
  for (const std::string& w : report.warnings)
    if (w.find(fragment) != std::string::npos) return true;
  return false;
}

std::string warnings(const GltfLoadReport& report) {
  std::string out;
  for (const std::string& w : report.warnings) out += w + "\n";
  return out;
}

}  // namespace

TEST(GltfSynthetic, KeepsTheNodeHierarchyParentsFirst) {
  GltfBuilder gltf;
  const float h = std::sqrt(0.5f);
  const json matrix = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
  const int leaf = gltf.meshNode(quadAttributes(gltf), quadIndices(gltf), -1, {{"name", "leaf"}, {"matrix", matrix}});
  const int middle = gltf.addNode({{"name", "middle"}, {"translation", {1, 0, 0}}, {"rotation", {0, 0, h, h}},
                                   {"scale", {2, 2, 2}}, {"children", {leaf}}});
  gltf.addNode({{"name", "root"}, {"children", {middle}}});
  const Scene scene = gltf.load();
  // glTF order is leaf, middle, root; the scene's is root, middle, leaf.
  ASSERT_EQ(scene.nodes.size(), 3u);
  EXPECT_EQ(scene.nodes[0].name, "root");
  EXPECT_EQ(scene.nodes[0].parent, -1);
  EXPECT_EQ(scene.nodes[1].name, "middle");
  EXPECT_EQ(scene.nodes[1].parent, 0);
  EXPECT_FALSE(scene.nodes[1].hasMatrix);
  expectNear(scene.nodes[1].translation, glm::vec3(1, 0, 0), "middle translation");
  expectNear(scene.nodes[1].scale, glm::vec3(2), "middle scale");
  EXPECT_NEAR(scene.nodes[1].rotation.z, h, 1e-6f);
  EXPECT_NEAR(scene.nodes[1].rotation.w, h, 1e-6f);
  EXPECT_EQ(scene.nodes[2].name, "leaf");
  EXPECT_EQ(scene.nodes[2].parent, 1);
  EXPECT_TRUE(scene.nodes[2].hasMatrix);
  expectNear(glm::vec3(scene.nodes[2].matrix[3]), glm::vec3(5, 6, 7), "leaf matrix translation");
  EXPECT_TRUE(scene.nodes[2].weights.empty());
  EXPECT_TRUE(scene.skins.empty());
  EXPECT_TRUE(scene.animations.empty());
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].node, 2);
  EXPECT_EQ(scene.instances[0].skin, -1);
  // The instance's world matrix is the product of the kept nodes' rest transforms.
  const glm::mat4 world = scene.nodes[0].localRest() * scene.nodes[1].localRest() * scene.nodes[2].localRest();
  for (int c = 0; c < 4; ++c) expectNear(glm::vec3(scene.instances[0].world[c]), glm::vec3(world[c]), "world column");
  // (0, 0, 0) -> leaf (5, 6, 7) -> scale 2 (10, 12, 14) -> quarter turn about z (-12, 10, 14) -> + (1, 0, 0).
  expectNear(glm::vec3(scene.instances[0].world * glm::vec4(0, 0, 0, 1)), glm::vec3(-11, 10, 14), "rest world");
}

TEST(GltfSynthetic, ANodeUnderTwoParentsGetsACopyPerPath) {
  GltfBuilder gltf;
  const int leaf = gltf.meshNode(quadAttributes(gltf), quadIndices(gltf));
  gltf.addNode({{"translation", {-5, 0, 0}}, {"children", {leaf}}});
  gltf.addNode({{"translation", {5, 0, 0}}, {"children", {leaf}}});
  addAnimation(gltf, {sampler(gltf, {0, 1}, {0, 0, 0, 0, 1, 0}, "VEC3", 3)}, {channel(0, leaf, "translation")});
  GltfLoadReport report;
  const Scene scene = gltf.load(&report);
  ASSERT_EQ(scene.nodes.size(), 4u);
  ASSERT_EQ(scene.instances.size(), 2u);
  EXPECT_NE(scene.instances[0].node, scene.instances[1].node);
  EXPECT_TRUE(hasWarning(report, "more than one parent")) << warnings(report);
  // The animation moves both copies.
  ASSERT_EQ(scene.animations.size(), 1u);
  ASSERT_EQ(scene.animations[0].channels.size(), 2u);
  EXPECT_EQ(scene.animations[0].channels[0].node, scene.instances[0].node);
  EXPECT_EQ(scene.animations[0].channels[1].node, scene.instances[1].node);
  EXPECT_EQ(scene.animations[0].channels[0].sampler, scene.animations[0].channels[1].sampler);
}

TEST(GltfSynthetic, ReadsASkinAndRepairsItsWeights) {
  GltfBuilder gltf;
  // Vertex 0: the hip alone, other slots naming a joint that does not exist with weight zero (pointed at joint 0).
  // Vertex 1: half hip, half knee. Vertex 2: no weight at all (follows its first joint, the knee, with weight 1).
  // Vertex 3: weights summing to 4 (renormalised to a half each).
  const std::vector<std::uint8_t> joints = {0, 9, 9, 9, 0, 1, 0, 0, 1, 7, 0, 0, 0, 1, 0, 0};
  const std::vector<float> weights = {1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0, 0, 0, 0, 2, 2, 0, 0};
  const SkinnedQuad quad = addSkinnedQuad(gltf, joints, weights);
  GltfLoadReport report;
  const Scene scene = gltf.load(&report);

  ASSERT_EQ(scene.nodes.size(), 3u);  // the mesh node, then the hip and its knee
  ASSERT_EQ(scene.skins.size(), 1u);
  const Skin& skin = scene.skins[0];
  EXPECT_EQ(skin.name, "legs");
  ASSERT_EQ(skin.joints.size(), 2u);
  EXPECT_EQ(scene.nodes[static_cast<size_t>(skin.joints[0])].name, "hip");
  EXPECT_EQ(scene.nodes[static_cast<size_t>(skin.joints[1])].name, "knee");
  EXPECT_EQ(skin.skeleton, skin.joints[0]);
  EXPECT_EQ(skin.inverseBind[0], glm::mat4(1.0f));
  expectNear(glm::vec3(skin.inverseBind[1][3]), glm::vec3(0, -1, 0), "the knee's inverse bind translation");
  (void)quad;

  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].skin, 0);
  EXPECT_EQ(scene.instances[0].node, 0);
  const Mesh& mesh = scene.meshes[static_cast<size_t>(scene.instances[0].mesh)];
  ASSERT_TRUE(mesh.skinned());
  ASSERT_EQ(mesh.joints.size(), 4u);
  ASSERT_EQ(mesh.weights.size(), 4u);
  EXPECT_EQ(mesh.joints[0], glm::u16vec4(0, 0, 0, 0));
  EXPECT_EQ(mesh.weights[0], glm::vec4(1, 0, 0, 0));
  EXPECT_EQ(mesh.joints[1], glm::u16vec4(0, 1, 0, 0));
  EXPECT_EQ(mesh.weights[1], glm::vec4(0.5f, 0.5f, 0, 0));
  EXPECT_EQ(mesh.joints[2], glm::u16vec4(1, 0, 0, 0));
  EXPECT_EQ(mesh.weights[2], glm::vec4(1, 0, 0, 0));
  EXPECT_EQ(mesh.joints[3], glm::u16vec4(0, 1, 0, 0));
  EXPECT_EQ(mesh.weights[3], glm::vec4(0.5f, 0.5f, 0, 0));
  EXPECT_TRUE(hasWarning(report, "WEIGHTS_0 of 1 vertices did not sum to 1; renormalised")) << warnings(report);
  EXPECT_TRUE(hasWarning(report, "1 vertices have all WEIGHTS_0 zero")) << warnings(report);
  EXPECT_TRUE(scene.animated());
}

TEST(GltfSynthetic, ReadsNormalisedIntegerWeightsAndIgnoresASecondSet) {
  GltfBuilder gltf;
  json attributes = quadAttributes(gltf);
  const std::vector<std::uint16_t> joints = {0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0};
  // 3/4 and 1/4 as normalised unsigned shorts; vertex 3 has lost its second weight to WEIGHTS_1.
  const std::vector<std::uint16_t> weights = {49151, 16384, 0, 0, 49151, 16384, 0, 0,
                                              49151, 16384, 0, 0, 32768, 0, 0, 0};
  attributes["JOINTS_0"] = gltf.integers(joints, kUnsignedShort, "VEC4", 4, false);
  attributes["WEIGHTS_0"] = gltf.integers(weights, kUnsignedShort, "VEC4", 4, true);
  attributes["JOINTS_1"] = attributes["JOINTS_0"];
  attributes["WEIGHTS_1"] = attributes["WEIGHTS_0"];
  const int meshNode = gltf.meshNode(attributes, quadIndices(gltf), -1, {{"skin", 0}});
  const int joint0 = gltf.addNode(json::object()), joint1 = gltf.addNode(json::object());
  gltf.doc()["skins"] = json::array({{{"joints", {joint0, joint1}}}});
  GltfLoadReport report;
  const Scene scene = gltf.load(&report);
  (void)meshNode;
  ASSERT_EQ(scene.skins.size(), 1u);
  EXPECT_EQ(scene.skins[0].inverseBind[1], glm::mat4(1.0f)) << "identity without inverseBindMatrices";
  EXPECT_EQ(scene.skins[0].skeleton, -1);
  const Mesh& mesh = scene.meshes[0];
  EXPECT_NEAR(mesh.weights[0].x, 0.75f, 1e-4f);
  EXPECT_NEAR(mesh.weights[0].y, 0.25f, 1e-4f);
  EXPECT_EQ(mesh.weights[3], glm::vec4(1, 0, 0, 0)) << "renormalised, its zero-weight joint slot pointed at 0";
  EXPECT_EQ(mesh.joints[3], glm::u16vec4(0, 0, 0, 0));
  EXPECT_TRUE(hasWarning(report, "JOINTS_1 / WEIGHTS_1 ignored")) << warnings(report);
  EXPECT_TRUE(hasWarning(report, "WEIGHTS_0 of 1 vertices did not sum to 1")) << warnings(report);
}

TEST(GltfSynthetic, AJointedPrimitiveWithoutASkinIsDrawnRigid) {
  GltfBuilder gltf;
  const SkinnedQuad quad = addSkinnedQuad(gltf);
  // A second node places the same mesh without a skin.
  gltf.addNode({{"mesh", 0}, {"translation", {3, 0, 0}}});
  GltfLoadReport report;
  const Scene scene = gltf.load(&report);
  (void)quad;
  ASSERT_EQ(scene.instances.size(), 2u);
  const Instance& skinned = scene.instances[0].skin >= 0 ? scene.instances[0] : scene.instances[1];
  const Instance& rigid = scene.instances[0].skin >= 0 ? scene.instances[1] : scene.instances[0];
  EXPECT_EQ(skinned.skin, 0);
  EXPECT_EQ(rigid.skin, -1);
  EXPECT_NE(skinned.mesh, rigid.mesh) << "one mesh per way of drawing it";
  EXPECT_TRUE(scene.meshes[static_cast<size_t>(skinned.mesh)].skinned());
  EXPECT_FALSE(scene.meshes[static_cast<size_t>(rigid.mesh)].skinned());
  EXPECT_TRUE(scene.meshes[static_cast<size_t>(rigid.mesh)].weights.empty());
  EXPECT_TRUE(hasWarning(report, "has JOINTS_0 but a node without a skin places it; drawn rigid")) << warnings(report);
}

TEST(GltfSynthetic, ReadsMorphTargetsAndRestWeights) {
  GltfBuilder gltf;
  const int meshDefaults = addMorphedQuad(gltf, {{"name", "mesh weights"}}, {0.25, 0.5});
  const int own = gltf.addNode({{"name", "own weights"}, {"mesh", 0}, {"weights", {1, 0}}});
  const int none = addMorphedQuad(gltf, {{"name", "no weights"}});
  (void)meshDefaults, (void)own, (void)none;
  const Scene scene = gltf.load();
  ASSERT_EQ(scene.nodes.size(), 3u);
  for (const Node& node : scene.nodes) {
    if (node.name == "mesh weights") EXPECT_EQ(node.weights, (std::vector<float>{0.25f, 0.5f}));
    else if (node.name == "own weights") EXPECT_EQ(node.weights, (std::vector<float>{1.0f, 0.0f}));
    else EXPECT_EQ(node.weights, (std::vector<float>{0.0f, 0.0f})) << node.name;
  }
  const Mesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.morphTargets.size(), 2u);
  const MorphTarget& lift = mesh.morphTargets[0];
  ASSERT_EQ(lift.positions.size(), 4u);
  ASSERT_EQ(lift.normals.size(), 4u);
  expectNear(lift.positions[2], glm::vec3(0, 0, 1), "target 0 lifts vertex 2");
  expectNear(lift.positions[0], glm::vec3(0), "target 0 leaves vertex 0");
  expectNear(lift.normals[2], glm::vec3(0, -0.5f, 0), "target 0 tilts vertex 2's normal");
  const MorphTarget& slide = mesh.morphTargets[1];
  ASSERT_EQ(slide.positions.size(), 4u);
  EXPECT_TRUE(slide.normals.empty());
  expectNear(slide.positions[3], glm::vec3(1, 0, 0), "target 1 (sparse) moves vertex 3");
  expectNear(slide.positions[1], glm::vec3(0), "target 1 leaves vertex 1");
  EXPECT_TRUE(scene.animated());
}

TEST(GltfSynthetic, FlatNormalsOfAMorphedMeshFollowItsTargets) {
  GltfBuilder gltf;
  const std::vector<float> lift = {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0};  // vertex 2 up by one
  json primitive = {{"attributes", {{"POSITION", gltf.floats(kQuad, "VEC3", 3)}}},
                    {"indices", quadIndices(gltf)},
                    {"targets", {{{"POSITION", gltf.floats(lift, "VEC3", 3)}}}}};
  gltf.doc()["meshes"].push_back({{"primitives", {primitive}}});
  gltf.addNode({{"mesh", 0}});
  const Scene scene = gltf.load();
  const Mesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.positions.size(), 6u);  // unwelded
  ASSERT_EQ(mesh.morphTargets.size(), 1u);
  const MorphTarget& target = mesh.morphTargets[0];
  ASSERT_EQ(target.positions.size(), 6u);
  ASSERT_EQ(target.normals.size(), 6u);
  for (size_t v = 0; v < 6; ++v) {
    // Fully applied, each face's normal is that of its displaced corners.
    const size_t first = v / 3 * 3;
    const glm::vec3 a = mesh.positions[first] + target.positions[first];
    const glm::vec3 b = mesh.positions[first + 1] + target.positions[first + 1];
    const glm::vec3 c = mesh.positions[first + 2] + target.positions[first + 2];
    expectNear(mesh.normals[v] + target.normals[v], glm::normalize(glm::cross(b - a, c - a)),
               "vertex " + std::to_string(v));
  }
  expectNear(target.positions[2], glm::vec3(0, 0, 1), "corner 2 of triangle 0 is vertex 2");
}

TEST(GltfSynthetic, AMorphedMeshKeepsTrianglesItsTargetsOpen) {
  GltfBuilder gltf;
  const std::vector<float> line = {0, 0, 0, 1, 0, 0, 2, 0, 0};  // collinear at rest
  const std::vector<float> open = {0, 0, 0, 0, 1, 0, 0, 0, 0};
  json primitive = {{"attributes", {{"POSITION", gltf.floats(line, "VEC3", 3)}}},
                    {"targets", {{{"POSITION", gltf.floats(open, "VEC3", 3)}}}}};
  gltf.doc()["meshes"].push_back({{"primitives", {primitive}}});
  gltf.addNode({{"mesh", 0}, {"weights", {1}}});
  const Scene scene = gltf.load();
  EXPECT_EQ(scene.triangleCount(), 1u);
}

TEST(GltfSynthetic, ReadsAnimationsOfEveryPathAndInterpolation) {
  GltfBuilder gltf;
  const int mover = addMorphedQuad(gltf, {{"name", "mover"}});
  const int outside = gltf.addNode({{"name", "outside"}});
  gltf.doc()["scenes"] = json::array({{{"nodes", {mover}}}});
  gltf.doc()["scene"] = 0;

  const std::vector<std::int16_t> turn = {0, 0, 0, 32767, 0, 0, 32767, 0};  // identity, then half a turn about z
  const std::vector<std::uint8_t> weightKeys = {0, 255, 255, 0};           // two targets, two keys
  json samplers = {
      sampler(gltf, {0, 1, 2}, {0, 0, 0, 1, 0, 0, 1, 2, 0}, "VEC3", 3),
      {{"input", gltf.floats({0, 1}, "SCALAR", 1)},
       {"output", gltf.integers(turn, kShort, "VEC4", 4, true)},
       {"interpolation", "STEP"}},
      sampler(gltf, {0, 1}, {0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 2, 2, 2, 0, 0, 0}, "VEC3", 3, "CUBICSPLINE"),
      {{"input", gltf.floats({0, 0.5f}, "SCALAR", 1)},
       {"output", gltf.integers(weightKeys, kUnsignedByte, "SCALAR", 1, true)}},
  };
  json channels = {channel(0, mover, "translation"), channel(1, mover, "rotation"), channel(2, mover, "scale"),
                   channel(3, mover, "weights"),     channel(0, outside, "translation"),
                   channel(0, mover, "pointer")};
  // KHR_animation_pointer's form: a target without a node.
  const json pointer = {{"KHR_animation_pointer", {{"pointer", "/nodes/0/translation"}}}};
  channels.push_back({{"sampler", 0}, {"target", {{"path", "pointer"}, {"extensions", pointer}}}});
  addAnimation(gltf, samplers, channels, "everything");
  addAnimation(gltf, {sampler(gltf, {0.5f}, {0, 0, 0, 1}, "VEC4", 4)}, {channel(0, mover, "rotation")});

  GltfLoadReport report;
  const Scene scene = gltf.load(&report);
  ASSERT_EQ(scene.animations.size(), 2u);
  const Animation& animation = scene.animations[0];
  EXPECT_EQ(animation.name, "everything");
  EXPECT_FLOAT_EQ(animation.duration(), 2.0f);
  ASSERT_EQ(animation.channels.size(), 4u);
  ASSERT_EQ(animation.samplers.size(), 4u);
  const AnimationPath paths[] = {AnimationPath::Translation, AnimationPath::Rotation, AnimationPath::Scale,
                                 AnimationPath::Weights};
  for (size_t c = 0; c < 4; ++c) {
    EXPECT_EQ(animation.channels[c].node, 0) << c;
    EXPECT_EQ(animation.channels[c].path, paths[c]) << c;
    EXPECT_EQ(animation.channels[c].sampler, static_cast<int>(c)) << c;
  }
  const AnimationSampler& translation = animation.samplers[0];
  EXPECT_EQ(translation.interpolation, Interpolation::Linear);
  EXPECT_EQ(translation.components, 3);
  EXPECT_EQ(translation.times, (std::vector<float>{0, 1, 2}));
  EXPECT_EQ(translation.values, (std::vector<float>{0, 0, 0, 1, 0, 0, 1, 2, 0}));
  const AnimationSampler& rotation = animation.samplers[1];
  EXPECT_EQ(rotation.interpolation, Interpolation::Step);
  EXPECT_EQ(rotation.components, 4);
  EXPECT_EQ(rotation.values, (std::vector<float>{0, 0, 0, 1, 0, 0, 1, 0})) << "normalised shorts, x y z w";
  const AnimationSampler& scale = animation.samplers[2];
  EXPECT_EQ(scale.interpolation, Interpolation::CubicSpline);
  EXPECT_EQ(scale.values.size(), 18u) << "in-tangent, value, out-tangent per key";
  EXPECT_FLOAT_EQ(scale.values[3], 1.0f);
  EXPECT_FLOAT_EQ(scale.values[12], 2.0f);
  const AnimationSampler& weights = animation.samplers[3];
  EXPECT_EQ(weights.components, 2);
  EXPECT_EQ(weights.values, (std::vector<float>{0, 1, 1, 0}));
  EXPECT_EQ(scene.animations[1].name, "");
  ASSERT_EQ(scene.animations[1].samplers.size(), 1u) << warnings(report);
  EXPECT_EQ(scene.animations[1].samplers[0].times, (std::vector<float>{0.5f}));

  EXPECT_TRUE(hasWarning(report, "animation 0: 1 channels target nodes outside the default scene")) << warnings(report);
  EXPECT_TRUE(hasWarning(report, "animation 0: 1 channels have a path other than")) << warnings(report);
  EXPECT_TRUE(hasWarning(report, "animation 0: 1 channels have no target node")) << warnings(report);
}

TEST(GltfSynthetic, RefusesBadSkinsMorphsAndAnimationsWithOneLine) {
  struct Case {
    const char* name;
    std::function<void(GltfBuilder&)> build;
    const char* expect;
    GltfLimits limits = {};
  };
  const auto translationAnimation = [](GltfBuilder& g, int node, std::vector<float> times, std::vector<float> values,
                                       const char* interpolation = "LINEAR") {
    addAnimation(g, {sampler(g, times, values, "VEC3", 3, interpolation)}, {channel(0, node, "translation")});
  };
  GltfLimits oneJoint;
  oneJoint.maxSkinJoints = 1;
  GltfLimits fewMorphs;
  fewMorphs.maxMorphTargetVertices = 7;  // the morphed quad's two targets need 8
  GltfLimits fewKeys;
  fewKeys.maxAnimationValues = 10;
  const float nan = std::nanf("");
  const float inf = INFINITY;
  const std::vector<Case> cases = {
      {"a joint index beyond the skin's joints",
       [](GltfBuilder& g) { addSkinnedQuad(g, {0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0}); },
       "mesh 0 primitive 0 has joint index 2 but skin 0 has 2 joints"},
      {"a negative weight",
       [](GltfBuilder& g) { addSkinnedQuad(g, {0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0},
                                           {1, -0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}); },
       "mesh 0 primitive 0 WEIGHTS_0 0 is negative or not finite"},
      {"a weight that is not finite",
       [nan](GltfBuilder& g) { addSkinnedQuad(g, {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0},
                                              {1, 0, 0, 0, nan, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}); },
       "WEIGHTS_0 1 is negative or not finite"},
      {"JOINTS_0 without WEIGHTS_0",
       [](GltfBuilder& g) {
         json attributes = quadAttributes(g);
         attributes["JOINTS_0"] = g.integers(std::vector<std::uint8_t>(16, 0), kUnsignedByte, "VEC4", 4, false);
         g.meshNode(attributes, quadIndices(g), -1, {{"skin", 0}});
         g.doc()["skins"] = json::array({{{"joints", {0}}}});
       },
       "has JOINTS_0 without WEIGHTS_0"},
      {"normalised joints",
       [](GltfBuilder& g) {
         addSkinnedQuad(g);
         g.doc()["accessors"][2]["normalized"] = true;
       },
       "JOINTS_0 (accessor 2) is normalized"},
      {"weights of unsigned bytes, not normalised",
       [](GltfBuilder& g) {
         json attributes = quadAttributes(g);
         attributes["JOINTS_0"] = g.integers(std::vector<std::uint8_t>(16, 0), kUnsignedByte, "VEC4", 4, false);
         attributes["WEIGHTS_0"] = g.integers(std::vector<std::uint8_t>(16, 1), kUnsignedByte, "VEC4", 4, false);
         g.meshNode(attributes, quadIndices(g), -1, {{"skin", 0}});
         g.doc()["skins"] = json::array({{{"joints", {0}}}});
       },
       "WEIGHTS_0 (accessor 3) has component type UNSIGNED_BYTE without normalized: true"},
      {"a skin over the joint limit", [](GltfBuilder& g) { addSkinnedQuad(g); },
       "skin 0 has 2 joints, over the limit of 1", oneJoint},
      {"a skin joint outside the default scene",
       [](GltfBuilder& g) {
         const SkinnedQuad quad = addSkinnedQuad(g);
         g.doc()["scenes"] = json::array({{{"nodes", {quad.meshNode}}}});
       },
       "skin 0 joint 0 is node 2, which is not in the default scene"},
      {"a skin joint that does not exist",
       [](GltfBuilder& g) {
         addSkinnedQuad(g);
         g.doc()["skins"][0]["joints"][1] = 42;
       },
       "skin 0 joint 1 is node 42, which does not exist"},
      {"fewer inverse bind matrices than joints",
       [](GltfBuilder& g) {
         addSkinnedQuad(g);
         g.doc()["accessors"][g.doc()["skins"][0]["inverseBindMatrices"].get<size_t>()]["count"] = 1;
       },
       "skin 0 has 1 inverse bind matrices for 2 joints"},
      {"a node referring to a skin that does not exist",
       [](GltfBuilder& g) {
         addSkinnedQuad(g);
         g.doc()["nodes"][0]["skin"] = 3;
       },
       "node 0 refers to skin 3, which does not exist"},
      {"primitives with different morph target counts",
       [](GltfBuilder& g) {
         addMorphedQuad(g);
         json second = g.doc()["meshes"][0]["primitives"][0];
         second["targets"].erase(1);
         g.doc()["meshes"][0]["primitives"].push_back(second);
       },
       "mesh 0 primitive 1 has 1 morph targets but primitive 0 has 2"},
      {"mesh weights for another target count", [](GltfBuilder& g) { addMorphedQuad(g, json::object(), {1}); },
       "mesh 0 has 1 weights for 2 morph targets"},
      {"node weights for another target count",
       [](GltfBuilder& g) { addMorphedQuad(g, {{"weights", {1, 0, 0}}}); },
       "node 0 has 3 weights for its mesh's 2 morph targets"},
      {"a morph target shorter than the primitive",
       [](GltfBuilder& g) {
         addMorphedQuad(g);
         g.doc()["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = g.floats({0, 0, 1}, "VEC3", 3);
       },
       "mesh 0 primitive 0 target 0 has 1 POSITION displacements for 4 positions"},
      {"a morph target displacement that is not finite",
       [inf](GltfBuilder& g) {
         addMorphedQuad(g);
         g.doc()["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] =
             g.floats({0, 0, 0, 0, 0, 0, 0, 0, inf, 0, 0, 0}, "VEC3", 3);
       },
       "mesh 0 primitive 0 target 0 POSITION has a displacement that is not finite"},
      {"more morph target vertices than the limit", [](GltfBuilder& g) { addMorphedQuad(g); },
       "more than 7 morph target vertices in the scene", fewMorphs},
      {"a key time that is not finite",
       [nan, translationAnimation](GltfBuilder& g) {
         translationAnimation(g, g.meshNode(quadAttributes(g)), {0, nan}, {0, 0, 0, 1, 1, 1});
       },
       "animation 0 sampler 0 input time 1 is not finite"},
      {"key times not strictly increasing",
       [translationAnimation](GltfBuilder& g) {
         translationAnimation(g, g.meshNode(quadAttributes(g)), {0, 1, 1}, {0, 0, 0, 1, 1, 1, 2, 2, 2});
       },
       "animation 0 sampler 0 input time 2 (1.000000) is not after the one before (1.000000)"},
      {"a key value that is not finite",
       [inf, translationAnimation](GltfBuilder& g) {
         translationAnimation(g, g.meshNode(quadAttributes(g)), {0, 1}, {0, 0, 0, 1, inf, 1});
       },
       "animation 0 sampler 0 output has a value that is not finite"},
      {"fewer output values than key times",
       [translationAnimation](GltfBuilder& g) {
         translationAnimation(g, g.meshNode(quadAttributes(g)), {0, 1, 2}, {0, 0, 0, 1, 1, 1});
       },
       "animation 0 sampler 0 has 2 output values for 3 key times (expected 3: 1 per key)"},
      {"CUBICSPLINE without tangents",
       [translationAnimation](GltfBuilder& g) {
         translationAnimation(g, g.meshNode(quadAttributes(g)), {0, 1}, {0, 0, 0, 1, 1, 1}, "CUBICSPLINE");
       },
       "has 2 output values for 2 key times (expected 6: 3 per key for CUBICSPLINE)"},
      {"weights keys not times the target count",
       [](GltfBuilder& g) {
         const int node = addMorphedQuad(g);
         addAnimation(g, {sampler(g, {0, 1}, {0, 1}, "SCALAR", 1)}, {channel(0, node, "weights")});
       },
       "has 2 output values for 2 key times (expected 4: 1 per key, times 2 morph targets)"},
      {"an unknown interpolation",
       [translationAnimation](GltfBuilder& g) {
         translationAnimation(g, g.meshNode(quadAttributes(g)), {0}, {0, 0, 0}, "BEZIER");
       },
       "animation 0 sampler 0 has interpolation 'BEZIER'"},
      {"key times of unsigned bytes",
       [](GltfBuilder& g) {
         const int node = g.meshNode(quadAttributes(g));
         addAnimation(g,
                      {{{"input", g.integers(std::vector<std::uint8_t>{0, 1}, kUnsignedByte, "SCALAR", 1, false)},
                        {"output", g.floats({0, 0, 0, 1, 1, 1}, "VEC3", 3)}}},
                      {channel(0, node, "translation")});
       },
       "animation 0 sampler 0 input (accessor 2) has component type UNSIGNED_BYTE"},
      {"a rotation of bytes not normalised",
       [](GltfBuilder& g) {
         const int node = g.meshNode(quadAttributes(g));
         addAnimation(g,
                      {{{"input", g.floats({0}, "SCALAR", 1)},
                        {"output", g.integers(std::vector<std::int8_t>{0, 0, 0, 1}, kByte, "VEC4", 4, false)}}},
                      {channel(0, node, "rotation")});
       },
       "animation 0 sampler 0 output (accessor 3) has component type BYTE without normalized: true"},
      {"a translation of shorts",
       [](GltfBuilder& g) {
         const int node = g.meshNode(quadAttributes(g));
         addAnimation(g,
                      {{{"input", g.floats({0}, "SCALAR", 1)},
                        {"output", g.integers(std::vector<std::int16_t>{0, 0, 0}, kShort, "VEC3", 3, true)}}},
                      {channel(0, node, "translation")});
       },
       "animation 0 sampler 0 output (accessor 3) has component type SHORT, which glTF does not allow here"},
      {"a zero rotation key",
       [](GltfBuilder& g) {
         const int node = g.meshNode(quadAttributes(g));
         addAnimation(g, {sampler(g, {0, 1}, {0, 0, 0, 1, 0, 0, 0, 0}, "VEC4", 4)}, {channel(0, node, "rotation")});
       },
       "animation 0 sampler 0 output rotation 1 is a zero quaternion"},
      {"a channel on a matrix node",
       [translationAnimation](GltfBuilder& g) {
         const int node = g.meshNode(quadAttributes(g), -1, -1,
                                     {{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}});
         translationAnimation(g, node, {0}, {0, 0, 0});
       },
       "animation 0 channel 0 animates node 0, which has a matrix (glTF allows animating only TRS nodes)"},
      {"a weights channel on a node without morph targets",
       [](GltfBuilder& g) {
         const int node = g.meshNode(quadAttributes(g));
         addAnimation(g, {sampler(g, {0}, {1}, "SCALAR", 1)}, {channel(0, node, "weights")});
       },
       "animation 0 channel 0 animates the weights of node 0, which has no morph targets"},
      {"two channels on one node and path",
       [](GltfBuilder& g) {
         const int node = g.meshNode(quadAttributes(g));
         addAnimation(g, {sampler(g, {0}, {0, 0, 0}, "VEC3", 3), sampler(g, {0}, {1, 1, 1}, "VEC3", 3)},
                      {channel(0, node, "scale"), channel(1, node, "scale")});
       },
       "animation 0 channel 1 animates node 0 scale, as channel 0 does"},
      {"one sampler for a translation and a rotation",
       [](GltfBuilder& g) {
         const int node = g.meshNode(quadAttributes(g));
         addAnimation(g, {sampler(g, {0}, {0, 0, 0}, "VEC3", 3)},
                      {channel(0, node, "translation"), channel(0, node, "rotation")});
       },
       "animation 0 channel 1 shares sampler 0 with a channel that needs other values"},
      {"a channel on a node that does not exist",
       [translationAnimation](GltfBuilder& g) {
         g.meshNode(quadAttributes(g));
         translationAnimation(g, 9, {0}, {0, 0, 0});
       },
       "animation 0 channel 0 targets node 9, which does not exist"},
      {"a channel with a sampler that does not exist",
       [](GltfBuilder& g) {
         const int node = g.meshNode(quadAttributes(g));
         addAnimation(g, {sampler(g, {0}, {0, 0, 0}, "VEC3", 3)}, {channel(4, node, "translation")});
       },
       "animation 0 channel 0 refers to sampler 4, which does not exist"},
      {"more animation values than the limit",
       [translationAnimation](GltfBuilder& g) {
         translationAnimation(g, g.meshNode(quadAttributes(g)), {0, 1, 2}, {0, 0, 0, 1, 1, 1, 2, 2, 2});
       },
       "animation 0 sampler 0: more than 10 animation values in the scene", fewKeys},
  };
  for (const Case& c : cases) {
    GltfBuilder gltf;
    c.build(gltf);
    const std::string message = gltf.refusal(c.limits);
    EXPECT_EQ(message.rfind("synthetic.gltf: ", 0), 0u) << c.name << ": " << message;
    EXPECT_NE(message.find(c.expect), std::string::npos) << c.name << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << c.name << ": " << message;
  }
}

// glTF cameras on nodes: perspective (with and without an aspect ratio and a far plane) and orthographic, placed by
// their nodes' world matrices, named by node and camera; the values the spec requires checked in one line.
TEST(GltfSynthetic, ReadsTheFilesCamerasWhereTheirNodesPutThem) {
  GltfBuilder gltf;
  gltf.meshNode({{"POSITION", gltf.floats(kQuad, "VEC3", 3)}});
  gltf.doc()["cameras"] = json::array(
      {{{"type", "perspective"},
        {"name", "wide"},
        {"perspective", {{"yfov", 0.9}, {"aspectRatio", 1.5}, {"znear", 0.05}, {"zfar", 80.0}}}},
       {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}},
       {{"type", "orthographic"},
        {"name", "plan"},
        {"orthographic", {{"xmag", 4.0}, {"ymag", -2.0}, {"znear", 0.0}, {"zfar", 50.0}}}}});
  const float h = std::sqrt(0.5f);
  gltf.addNode({{"name", "Front"}, {"camera", 0}, {"translation", {0, 1, 5}}});
  gltf.addNode({{"camera", 1}, {"translation", {2, 0, 0}}});
  const int top = gltf.addNode({{"name", "Top"}, {"camera", 2}, {"translation", {0, 0, 3}}});
  // The top camera under a parent turned 90 degrees about x: it looks down -y from (0, 3, 0)... (0, -3, 0) rotated.
  gltf.addNode({{"name", "Rig"}, {"rotation", {-h, 0, 0, h}}, {"children", {top}}});
  GltfLoadReport report;
  const Scene scene = gltf.load(&report);
  ASSERT_EQ(scene.cameras.size(), 3u);
  const SceneCamera& wide = scene.cameras[0];
  EXPECT_EQ(wide.name, "wide");
  EXPECT_EQ(wide.nodeName, "Front");
  EXPECT_FALSE(wide.orthographic);
  EXPECT_FLOAT_EQ(wide.yfov, 0.9f);
  EXPECT_FLOAT_EQ(wide.aspectRatio, 1.5f);
  EXPECT_FLOAT_EQ(wide.frameAspect(), 1.5f);
  EXPECT_FLOAT_EQ(wide.znear, 0.05f);
  EXPECT_FLOAT_EQ(wide.zfar, 80.0f);
  expectNear(glm::vec3(wide.world[3]), glm::vec3(0, 1, 5), "the front camera's place");
  EXPECT_EQ(scene.cameras[1].label(1), "camera 1");
  EXPECT_FLOAT_EQ(scene.cameras[1].zfar, 0.0f) << "no zfar: infinite";
  const SceneCamera& plan = scene.cameras[2];
  EXPECT_TRUE(plan.orthographic);
  EXPECT_FLOAT_EQ(plan.xmag, 4.0f);
  EXPECT_FLOAT_EQ(plan.ymag, 2.0f) << "a negative ymag is drawn with its magnitude";
  EXPECT_FLOAT_EQ(plan.frameAspect(), 2.0f);
  expectNear(glm::vec3(plan.world[3]), glm::vec3(0, 3, 0), "the top camera, turned by its parent");
  expectNear(-glm::vec3(plan.world[2]), glm::vec3(0, -1, 0), "it looks down");
  std::string warnings;
  for (const std::string& w : report.warnings) warnings += w + "\n";
  EXPECT_NE(warnings.find("camera 2 has a negative xmag or ymag: drawn with their magnitudes"), std::string::npos)
      << warnings;

  auto refusal = [](json cameras, json node) {
    GltfBuilder g;
    g.meshNode({{"POSITION", g.floats(kQuad, "VEC3", 3)}});
    g.doc()["cameras"] = std::move(cameras);
    g.addNode(std::move(node));
    return g.refusal();
  };
  const json perspective = {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}};
  EXPECT_EQ(refusal(json::array({perspective}), {{"camera", 3}}),
            "synthetic.gltf: node 1 refers to camera 3, which does not exist");
  EXPECT_EQ(refusal(json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1},
                                                                             {"zfar", 0.05}}}}}),
                    {{"camera", 0}}),
            "synthetic.gltf: camera 0 needs zfar > znear (or none: infinite)");
  EXPECT_EQ(refusal(json::array({{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 2},
                                                                               {"zfar", 1}}}}}),
                    {{"camera", 0}}),
            "synthetic.gltf: camera 0 needs 0 <= znear < zfar");
  EXPECT_EQ(refusal(json::array({{{"type", "orthographic"}, {"orthographic", {{"xmag", 0}, {"ymag", 1}, {"znear", 0},
                                                                               {"zfar", 1}}}}}),
                    {{"camera", 0}}),
            "synthetic.gltf: camera 0 needs xmag and ymag other than 0");
}

// Issue 31's material extensions as the loader reads them: unlit, ior, specular, clearcoat, transmission; textures of
// those extensions named in a warning (no texture unit is left for them); each extension it does not implement named
// once per file, however many materials use it; and the slots' texture coordinate sets, TEXCOORD_1 included.
TEST(GltfSynthetic, ReadsTheMaterialExtensionsAndNamesThoseItDoesNotImplementOnce) {
  GltfBuilder gltf;
  json attributes = quadAttributes(gltf);
  const std::vector<float> uv0 = {0, 0, 1, 0, 1, 1, 0, 1}, uv1 = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
  attributes["TEXCOORD_0"] = gltf.floats(uv0, "VEC2", 2);
  attributes["TEXCOORD_1"] = gltf.floats(uv1, "VEC2", 2);
  const std::vector<float> colors = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 0.5f, 1, 1, 1, 1};
  attributes["COLOR_0"] = gltf.floats(colors, "VEC4", 4);
  gltf.doc()["textures"] = json::array({json::object()});  // a texture without an image: drawn white
  gltf.doc()["materials"] = json::array(
      {{{"extensions", {{"KHR_materials_unlit", json::object()}}}},
       {{"occlusionTexture", {{"index", 0}, {"texCoord", 1}}},
        {"extensions",
         {{"KHR_materials_ior", {{"ior", 1.8}}},
          {"KHR_materials_specular", {{"specularFactor", 0.5}, {"specularColorFactor", {1.0, 0.5, 0.25}}}},
          {"KHR_materials_clearcoat",
           {{"clearcoatFactor", 0.75}, {"clearcoatRoughnessFactor", 0.2}, {"clearcoatTexture", {{"index", 0}}}}},
          {"KHR_materials_transmission", {{"transmissionFactor", 0.9}}},
          {"KHR_materials_sheen", {{"sheenColorFactor", {1, 1, 1}}}}}},
        {"alphaMode", "BLEND"}},
       {{"extensions", {{"KHR_materials_sheen", {{"sheenColorFactor", {1, 0, 0}}}}}}}});
  gltf.doc()["extensionsUsed"] = {"KHR_materials_unlit", "KHR_materials_ior", "KHR_materials_specular",
                                  "KHR_materials_clearcoat", "KHR_materials_transmission", "KHR_materials_sheen",
                                  "EXT_made_up"};
  gltf.meshNode(attributes, quadIndices(gltf), 0);
  gltf.meshNode(attributes, quadIndices(gltf), 1);
  gltf.meshNode(attributes, quadIndices(gltf), 2);
  GltfLoadReport report;
  const Scene scene = gltf.load(&report);
  ASSERT_EQ(scene.materials.size(), 3u);
  EXPECT_TRUE(scene.materials[0].unlit);
  const Material& layered = scene.materials[1];
  EXPECT_FALSE(layered.unlit);
  EXPECT_FLOAT_EQ(layered.ior, 1.8f);
  EXPECT_FLOAT_EQ(layered.specularFactor, 0.5f);
  EXPECT_EQ(layered.specularColorFactor, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(layered.clearcoatFactor, 0.75f);
  EXPECT_FLOAT_EQ(layered.clearcoatRoughnessFactor, 0.2f);
  EXPECT_FLOAT_EQ(layered.transmissionFactor, 0.9f);
  EXPECT_TRUE(layered.layered());
  EXPECT_TRUE(layered.transparent());
  const float f0 = std::pow(0.8f / 2.8f, 2.0f);
  EXPECT_NEAR(layered.dielectricF0().g, f0 * 0.5f * 0.5f, 1e-6f);
  // The occlusion texture samples TEXCOORD_1: the slot is kept, and the mesh keeps the second set.
  EXPECT_EQ(layered.occlusionTexture, 0);
  EXPECT_EQ(layered.texCoords[static_cast<size_t>(TextureSlot::Occlusion)], 1);
  for (const Mesh& mesh : scene.meshes) {
    ASSERT_EQ(mesh.colors.size(), 4u);
    EXPECT_EQ(mesh.colors[2], glm::vec4(0, 0, 1, 0.5f));
    if (mesh.material == 1) {
      ASSERT_EQ(mesh.texcoords1.size(), 4u);
      EXPECT_EQ(mesh.texcoords1[3], glm::vec2(0.5f));
    } else {
      EXPECT_TRUE(mesh.texcoords1.empty()) << "material " << mesh.material << " samples no TEXCOORD_1";
    }
  }
  EXPECT_TRUE(hasWarning(report, "clearcoatTexture not read")) << warnings(report);
  int sheen = 0, madeUp = 0;
  for (const std::string& w : report.warnings) {
    sheen += w.find("KHR_materials_sheen") != std::string::npos;
    madeUp += w.find("EXT_made_up") != std::string::npos;
  }
  EXPECT_EQ(sheen, 1) << warnings(report);
  EXPECT_EQ(madeUp, 1) << warnings(report);
  EXPECT_FALSE(hasWarning(report, "KHR_materials_clearcoat is not")) << warnings(report);

  // Required: one that can be drawn without (sheen) loads; one nobody knows is refused in one line.
  gltf.doc()["extensionsRequired"] = {"KHR_materials_sheen"};
  EXPECT_NO_THROW(gltf.load());
  gltf.doc()["extensionsRequired"] = {"EXT_made_up"};
  EXPECT_NE(gltf.refusal().find("requires unsupported extension EXT_made_up"), std::string::npos);
}

// Morph targets' TANGENT deltas are read beside POSITION and NORMAL (a target without them gets zeros beside one
// with), and KHR_lights_punctual directional lights are loaded, intensity in lux, no range.
TEST(GltfSynthetic, ReadsMorphTangentsAndDirectionalLights) {
  GltfBuilder gltf;
  const std::vector<float> tangents = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
  const std::vector<float> turn = {-1, 1, 0, -1, 1, 0, -1, 1, 0, -1, 1, 0};
  json attributes = quadAttributes(gltf);
  attributes["TANGENT"] = gltf.floats(tangents, "VEC4", 4);
  attributes["TEXCOORD_0"] = gltf.floats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2", 2);
  json primitive = {{"attributes", attributes},
                    {"indices", quadIndices(gltf)},
                    {"material", 0},
                    {"targets", {{{"POSITION", gltf.floats(std::vector<float>(12, 0.0f), "VEC3", 3)},
                                  {"TANGENT", gltf.floats(turn, "VEC3", 3)}},
                                 {{"POSITION", gltf.floats(std::vector<float>(12, 0.0f), "VEC3", 3)}}}}};
  gltf.doc()["meshes"].push_back({{"primitives", {primitive}}});
  gltf.doc()["textures"] = json::array({json::object()});
  gltf.doc()["materials"] = json::array({{{"normalTexture", {{"index", 0}}}}});
  gltf.addNode({{"mesh", 0}});
  gltf.doc()["extensionsUsed"] = {"KHR_lights_punctual"};
  gltf.doc()["extensions"] = {
      {"KHR_lights_punctual",
       {{"lights", {{{"type", "directional"}, {"color", {1, 0.9, 0.8}}, {"intensity", 3.5}}}}}}};
  gltf.addNode({{"rotation", {-0.38268343, 0, 0, 0.92387953}},
                {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  GltfLoadReport report;
  const Scene scene = gltf.load(&report);
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.meshes[0].morphTargets.size(), 2u);
  ASSERT_EQ(scene.meshes[0].morphTargets[0].tangents.size(), 4u);
  EXPECT_EQ(scene.meshes[0].morphTargets[0].tangents[1], glm::vec3(-1, 1, 0));
  EXPECT_EQ(scene.meshes[0].morphTargets[1].tangents, std::vector<glm::vec3>(4, glm::vec3(0.0f)));
  ASSERT_EQ(scene.lights.size(), 1u) << warnings(report);
  EXPECT_EQ(scene.lights[0].type, LightType::Directional);
  EXPECT_FLOAT_EQ(scene.lights[0].intensity, 3.5f);
  EXPECT_FALSE(hasWarning(report, "directional")) << warnings(report);
}

// TEXCOORD_1 through KHR_mesh_quantization (the compressed path's accessors are read as these are): normalised
// unsigned shorts, and raw bytes the extension allows unnormalised.
TEST(GltfSynthetic, ReadsAQuantizedSecondTextureCoordinateSet) {
  GltfBuilder gltf;
  json attributes = quadAttributes(gltf);
  attributes["TEXCOORD_0"] = gltf.integers(std::vector<std::uint16_t>{0, 0, 65535, 0, 65535, 65535, 0, 65535},
                                           kUnsignedShort, "VEC2", 2, true);
  attributes["TEXCOORD_1"] = gltf.integers(std::vector<std::uint8_t>{0, 0, 2, 0, 2, 2, 0, 2, 0, 0, 0, 0},
                                           kUnsignedByte, "VEC2", 2, false);
  gltf.doc()["textures"] = json::array({json::object()});
  gltf.doc()["materials"] = json::array({{{"occlusionTexture", {{"index", 0}, {"texCoord", 1}}}}});
  gltf.doc()["extensionsUsed"] = {"KHR_mesh_quantization"};
  gltf.doc()["extensionsRequired"] = {"KHR_mesh_quantization"};
  // The byte accessor holds 6 pairs for 4 vertices: cut it to four.
  gltf.meshNode(attributes, quadIndices(gltf), 0);
  gltf.doc()["accessors"][static_cast<size_t>(attributes["TEXCOORD_1"].get<int>())]["count"] = 4;
  const Scene scene = gltf.load();
  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.texcoords1.size(), 4u);
  EXPECT_EQ(mesh.texcoords1[2], glm::vec2(2.0f, 2.0f));
  EXPECT_EQ(mesh.texcoords[2], glm::vec2(1.0f, 1.0f));
}
