// Every glTF file Debian's assimp-testmodels ships (valid samples and deliberately broken ones: wrongTypes,
// SchemaFailures, IndexOutOfRange, MissingBin, BoxWithInfinites, BoxBadNormals, draco, texcoord_crash, ...) either
// loads into a scene the renderer can draw, or is refused with one line naming the file and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "TestSupport.h"
#include "base/Error.h"
#include "scene/GltfLoader.h"
#include "scene/TexturePreparation.h"

using namespace obscura;

namespace {

std::vector<std::string> corpus() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(test::assimpModels())) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".gltf" || ext == ".glb") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// What the renderer relies on from a loaded scene.
void expectDrawable(const Scene& scene, const std::string& file) {
  ASSERT_FALSE(scene.instances.empty()) << file;
  for (const Instance& instance : scene.instances) {
    ASSERT_GE(instance.mesh, 0) << file;
    ASSERT_LT(static_cast<size_t>(instance.mesh), scene.meshes.size()) << file;
  }
  for (const Mesh& mesh : scene.meshes) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << file;
    ASSERT_TRUE(mesh.texcoords.empty() || mesh.texcoords.size() == mesh.positions.size()) << file;
    ASSERT_EQ(mesh.indices.size() % 3, 0u) << file;
    for (std::uint32_t index : mesh.indices) ASSERT_LT(index, mesh.positions.size()) << file;
    for (const glm::vec3& p : mesh.positions) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z)) << file;
    for (const glm::vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-3f) << file;
    ASSERT_TRUE(mesh.material < 0 || static_cast<size_t>(mesh.material) < scene.materials.size()) << file;
  }
  for (const Material& material : scene.materials)
    ASSERT_TRUE(material.baseColorTexture < 0 || static_cast<size_t>(material.baseColorTexture) < scene.textures.size())
        << file;
  const Bounds bounds = scene.worldBounds();
  ASSERT_TRUE(std::isfinite(bounds.radius())) << file;
}

}  // namespace

TEST(GltfCorpus, EveryFileLoadsOrIsRefusedWithOneLine) {
  const std::vector<std::string> files = corpus();
  ASSERT_GE(files.size(), 40u) << "assimp-testmodels not installed?";
  int loaded = 0, refused = 0;
  for (const std::string& file : files) {
    try {
      GltfLoadReport report;
      const Scene scene = loadGltfFile(file, &report);
      expectDrawable(scene, file);
      ++loaded;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_GT(message.size(), file.size() + 10) << "say what the problem is: " << message;
      ++refused;
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << " threw something other than InputError: " << e.what();
    }
  }
  RecordProperty("loaded", loaded);
  RecordProperty("refused", refused);
  EXPECT_GE(loaded, 20);
  EXPECT_GE(refused, 10);
}

TEST(GltfCorpus, KnownBrokenFilesSayWhatIsWrong) {
  const std::map<std::string, std::string> expected = {
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "is not finite"},
      {"IndexOutOfRange/IndexOutOfRange.gltf", "has index 255 but only 24 vertices"},
      {"IndexOutOfRange/AllIndicesOutOfRange.gltf", "has index 65535 but only 24 vertices"},
      {"MissingBin/BoxTextured.gltf", "BoxTextured0.bin"},
      {"RecursiveNodes/RecursiveNodes.gltf", "cycle"},
      {"draco/2CylinderEngine.gltf", "requires unsupported extension KHR_draco_mesh_compression"},
      {"BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf", "requires unsupported extension KHR_technique_webgl"},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf", "only point or line primitives"},
      {"TestNoRootNode/SceneWithoutNodes.gltf", "no triangle geometry"},
  };
  for (const auto& [relative, fragment] : expected) {
    const std::string file = test::assimpModels() + "/" + relative;
    try {
      loadGltfFile(file);
      ADD_FAILURE() << relative << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  }
}

TEST(GltfCorpus, RepairableFilesLoadWithAWarning) {
  GltfLoadReport report;
  const Scene scene = loadGltfFile(test::assimpModels() + "/BoxBadNormals-glTF-Binary/BoxBadNormals.glb", &report);
  expectDrawable(scene, "BoxBadNormals");
  ASSERT_FALSE(report.warnings.empty());
  EXPECT_NE(report.warnings.front().find("flat normals generated"), std::string::npos) << report.warnings.front();
  // texcoord_crash crashed another loader; here it loads.
  expectDrawable(loadGltfFile(test::assimpModels() + "/issue_3269/texcoord_crash.gltf"), "texcoord_crash");
}

TEST(GltfLimits, AbsurdCountsAreRefusedNotAttempted) {
  GltfLimits tight;
  tight.maxAccessorElements = 10;  // the box has 24 vertices
  try {
    loadGltfFile(test::assimpModels() + "/BoxTextured-glTF/BoxTextured.gltf", nullptr, tight);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("over the limit of 10"), std::string::npos) << e.what();
  }
  tight = GltfLimits{};
  tight.maxImageDimension = 64;  // its texture is 256x256
  GltfLoadReport report;
  try {
    loadGltfFile(test::assimpModels() + "/BoxTextured-glTF/BoxTextured.gltf", &report, tight);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("over the limit of 64 per side"), std::string::npos) << e.what();
  }
}

TEST(TexturePreparation, FollowsWebGl1NonPowerOfTwoRules) {
  Image npot;
  npot.width = 100;
  npot.height = 60;
  npot.rgba.assign(100 * 60 * 4, 128);
  SamplerState repeat;  // glTF default: REPEAT, LINEAR_MIPMAP_LINEAR
  PreparedTexture p = prepareTextureForGles2(npot, repeat, 4096);
  EXPECT_EQ(p.image.width, 128);
  EXPECT_EQ(p.image.height, 64);
  EXPECT_TRUE(p.mipmaps);
  SamplerState clamp;
  clamp.wrapS = clamp.wrapT = 0x812F;  // CLAMP_TO_EDGE
  clamp.minFilter = 0x2601;            // LINEAR
  p = prepareTextureForGles2(npot, clamp, 4096);
  EXPECT_EQ(p.image.width, 100);  // legal as it is
  EXPECT_FALSE(p.mipmaps);
  p = prepareTextureForGles2(npot, clamp, 50);
  EXPECT_EQ(p.image.width, 50);  // scaled to the context's limit, aspect kept
  EXPECT_EQ(p.image.height, 30);
  SamplerState bogus;
  bogus.minFilter = 12345;
  bogus.wrapS = -1;
  p = prepareTextureForGles2(npot, bogus, 4096);
  EXPECT_EQ(p.sampler.minFilter, 0x2703);
  EXPECT_EQ(p.sampler.wrapS, 0x2901);
}

// Inputs the fuzzer (tests/fuzz, tools/fuzz-gltf.sh) once broke the loader with; each must now be refused cleanly.
// Under the sanitizer leg (tools/test-sanitizers.sh) a memory error here fails the suite.
TEST(GltfCorpus, FuzzerRegressionsAreRefusedCleanly) {
  int count = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(test::sourceDir() + "/tests/fuzz/regressions")) {
    const std::string file = entry.path().string();
    try {
      loadGltfFile(file);
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(file + ": ", 0), 0u) << e.what();
    }
    ++count;
  }
  EXPECT_GE(count, 1);
}
