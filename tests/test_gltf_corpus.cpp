// Every glTF file Debian's assimp-testmodels ships (valid samples and deliberately broken ones: wrongTypes,
// SchemaFailures, IndexOutOfRange, MissingBin, BoxWithInfinites, BoxBadNormals, draco, texcoord_crash, ...) either
// loads into a scene the renderer can draw, or is refused with one line naming the file and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
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

// What posing relies on from a loaded scene (scene/Scene.h): parents before children, indices in range, skinning
// attributes per vertex with weights summing to 1 and joints inside the instance's skin, morph displacements per
// vertex and rest weights per target, sampler values agreeing with their keys and channels.
void expectConsistentMotion(const Scene& scene, const std::string& file) {
  for (size_t n = 0; n < scene.nodes.size(); ++n) ASSERT_LT(scene.nodes[n].parent, static_cast<int>(n)) << file;
  for (const Skin& skin : scene.skins) {
    ASSERT_FALSE(skin.joints.empty()) << file;
    ASSERT_EQ(skin.inverseBind.size(), skin.joints.size()) << file;
    for (int joint : skin.joints) ASSERT_TRUE(joint >= 0 && static_cast<size_t>(joint) < scene.nodes.size()) << file;
  }
  for (const Instance& instance : scene.instances) {
    ASSERT_TRUE(instance.node >= 0 && static_cast<size_t>(instance.node) < scene.nodes.size()) << file;
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    ASSERT_EQ(mesh.skinned(), instance.skin >= 0) << file;
    if (instance.skin >= 0) {
      ASSERT_LT(static_cast<size_t>(instance.skin), scene.skins.size()) << file;
      const size_t jointCount = scene.skins[static_cast<size_t>(instance.skin)].joints.size();
      for (const glm::u16vec4& joints : mesh.joints)
        for (int c = 0; c < 4; ++c) ASSERT_LT(joints[c], jointCount) << file;
    }
    ASSERT_EQ(scene.nodes[static_cast<size_t>(instance.node)].weights.size(), mesh.morphTargets.size()) << file;
  }
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.skinned()) {
      ASSERT_EQ(mesh.joints.size(), mesh.positions.size()) << file;
      ASSERT_EQ(mesh.weights.size(), mesh.positions.size()) << file;
      for (const glm::vec4& w : mesh.weights) ASSERT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-5f) << file;
    }
    for (const MorphTarget& target : mesh.morphTargets) {
      ASSERT_EQ(target.positions.size(), mesh.positions.size()) << file;
      ASSERT_TRUE(target.normals.empty() || target.normals.size() == mesh.positions.size()) << file;
    }
  }
  for (const Animation& animation : scene.animations) {
    for (const AnimationSampler& sampler : animation.samplers) {
      ASSERT_FALSE(sampler.times.empty()) << file;
      for (size_t k = 1; k < sampler.times.size(); ++k) ASSERT_GT(sampler.times[k], sampler.times[k - 1]) << file;
      const size_t perKey = sampler.interpolation == Interpolation::CubicSpline ? 3 : 1;
      ASSERT_EQ(sampler.values.size(), sampler.times.size() * perKey * static_cast<size_t>(sampler.components))
          << file;
    }
    for (const AnimationChannel& channel : animation.channels) {
      ASSERT_LT(static_cast<size_t>(channel.sampler), animation.samplers.size()) << file;
      ASSERT_LT(static_cast<size_t>(channel.node), scene.nodes.size()) << file;
      ASSERT_FALSE(scene.nodes[static_cast<size_t>(channel.node)].hasMatrix) << file;
      const int components = animation.samplers[static_cast<size_t>(channel.sampler)].components;
      if (channel.path == AnimationPath::Weights)
        ASSERT_EQ(static_cast<size_t>(components), scene.nodes[static_cast<size_t>(channel.node)].weights.size())
            << file;
      else ASSERT_EQ(components, channel.path == AnimationPath::Rotation ? 4 : 3) << file;
    }
  }
}

// What the renderer relies on from a loaded scene.
void expectDrawable(const Scene& scene, const std::string& file) {
  ASSERT_FALSE(scene.instances.empty() && scene.lineInstances.empty()) << file;
  for (const LineInstance& instance : scene.lineInstances) {
    ASSERT_LT(static_cast<size_t>(instance.mesh), scene.lineMeshes.size()) << file;
    const LineMesh& lines = scene.lineMeshes[static_cast<size_t>(instance.mesh)];
    ASSERT_FALSE(lines.positions.empty()) << file;
    ASSERT_TRUE(lines.points || lines.positions.size() % 2 == 0) << file;
    ASSERT_TRUE(lines.colors.empty() || lines.colors.size() == lines.positions.size()) << file;
  }
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
  expectConsistentMotion(scene, file);
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
      if (scene.instances.empty() && scene.lineInstances.empty()) {
        // Nothing to draw (an empty scene, or one whose geometry was all skipped): said in a warning.
        ASSERT_FALSE(report.warnings.empty()) << file;
        EXPECT_NE(report.warnings.back().find("nothing is drawn"), std::string::npos) << file;
      } else {
        expectDrawable(scene, file);
      }
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
  EXPECT_GE(refused, 7);
}

TEST(GltfCorpus, KnownBrokenFilesSayWhatIsWrong) {
  const std::map<std::string, std::string> expected = {
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "is not finite"},
      {"IndexOutOfRange/IndexOutOfRange.gltf", "has index 255 but only 24 vertices"},
      {"IndexOutOfRange/AllIndicesOutOfRange.gltf", "has index 65535 but only 24 vertices"},
      {"MissingBin/BoxTextured.gltf", "BoxTextured0.bin"},
      {"RecursiveNodes/RecursiveNodes.gltf", "cycle"},
      {"BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf", "requires unsupported extension KHR_technique_webgl"},
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

// glTF-Asset-Generator's Mesh_PrimitiveMode: points, lines, line loops and strips, each without and with indices
// (00 .. 03, 07 .. 10), are drawn as such; strips and loops become segment lists.
TEST(GltfCorpus, PointAndLinePrimitivesLoadAsLines) {
  struct Expected {
    int file;
    bool points;
    size_t vertices;  // after strips and loops are expanded into segments
  };
  // 00 / 07: 1024 points; 01 / 08: 4 segments; 02 / 09: a loop of 4 (4 segments); 03 / 10: a strip of 5 (4).
  const Expected expected[] = {{0, true, 1024}, {1, false, 8}, {2, false, 8}, {3, false, 8},
                               {7, true, 1024}, {8, false, 8}, {9, false, 8}, {10, false, 8}};
  for (const Expected& e : expected) {
    char name[96];
    std::snprintf(name, sizeof name, "/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_%02d.gltf", e.file);
    const Scene scene = loadGltfFile(test::assimpModels() + name);
    EXPECT_TRUE(scene.instances.empty()) << name;
    ASSERT_EQ(scene.lineInstances.size(), 1u) << name;
    ASSERT_EQ(scene.lineMeshes.size(), 1u) << name;
    EXPECT_EQ(scene.lineMeshes[0].points, e.points) << name;
    EXPECT_EQ(scene.lineMeshes[0].positions.size(), e.vertices) << name;
    EXPECT_GT(scene.worldBounds().radius(), 0.1f) << name;  // the camera frames them
  }
}

TEST(GltfCorpus, RepairableFilesLoadWithAWarning) {
  GltfLoadReport report;
  const Scene scene = loadGltfFile(test::assimpModels() + "/BoxBadNormals-glTF-Binary/BoxBadNormals.glb", &report);
  expectDrawable(scene, "BoxBadNormals");
  ASSERT_FALSE(report.warnings.empty());
  EXPECT_NE(report.warnings.front().find("flat normals generated"), std::string::npos) << report.warnings.front();
  // texcoord_crash crashed another loader; here it loads, and says what its texture coordinates lack.
  GltfLoadReport crash;
  expectDrawable(loadGltfFile(test::assimpModels() + "/issue_3269/texcoord_crash.gltf", &crash), "texcoord_crash");
  ASSERT_FALSE(crash.warnings.empty());
  // The wrongTypes files' properties of the wrong JSON type, which tinygltf skips, are named (GltfSchema.h).
  for (const char* file : {"badExtension", "badNumber", "badObject", "badString", "badUint"}) {
    GltfLoadReport wrong;
    loadGltfFile(test::assimpModels() + "/wrongTypes/" + file + ".gltf", &wrong);
    bool named = false;
    for (const std::string& w : wrong.warnings) named = named || w.find("does not follow the glTF schema") == 0;
    EXPECT_TRUE(named) << file;
  }
  // A valid file with an empty scene loads, with nothing to draw, and says so.
  GltfLoadReport empty;
  const Scene nothing = loadGltfFile(test::assimpModels() + "/TestNoRootNode/SceneWithoutNodes.gltf", &empty);
  EXPECT_TRUE(nothing.instances.empty() && nothing.lineInstances.empty());
  ASSERT_FALSE(empty.warnings.empty());
  EXPECT_NE(empty.warnings.back().find("nothing is drawn"), std::string::npos) << empty.warnings.back();
}

// The corpus's moving samples are read whole: their skins, morph targets and animations, not only the bind pose.
TEST(GltfCorpus, AnimatedSamplesKeepTheirMotion) {
  GltfLoadReport report;
  const Scene skin = loadGltfFile(test::assimpModels() + "/simple_skin/simple_skin.gltf", &report);
  expectDrawable(skin, "simple_skin");
  EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
  ASSERT_EQ(skin.nodes.size(), 3u);  // the skinned mesh's node, its child (joint 0) and grandchild (joint 1)
  EXPECT_EQ(skin.nodes[1].parent, 0);
  EXPECT_EQ(skin.nodes[2].parent, 1);
  ASSERT_EQ(skin.skins.size(), 1u);
  EXPECT_EQ(skin.skins[0].joints, (std::vector<int>{1, 2}));
  // Both inverse bind matrices move by (-0.5, -1, 0) (the file's accessor min and max).
  for (const glm::mat4& inverseBind : skin.skins[0].inverseBind)
    EXPECT_EQ(glm::vec3(inverseBind[3]), glm::vec3(-0.5f, -1.0f, 0.0f));
  ASSERT_EQ(skin.instances.size(), 1u);
  EXPECT_EQ(skin.instances[0].skin, 0);
  const Mesh& skinned = skin.meshes[static_cast<size_t>(skin.instances[0].mesh)];
  // The file has no NORMAL: flat normals unweld its 10 vertices into 8 triangles' 24, each keeping its joints.
  ASSERT_EQ(skinned.positions.size(), 24u);
  ASSERT_EQ(skinned.joints.size(), 24u);
  // Its strip of height 2 blends from joint 0 alone at the bottom to joint 1 alone at the top.
  for (size_t v = 0; v < skinned.positions.size(); ++v) {
    const float up = skinned.positions[v].y / 2.0f;
    EXPECT_EQ(skinned.joints[v], glm::u16vec4(0, up > 0.0f ? 1 : 0, 0, 0)) << v << " (a slot of weight 0: joint 0)";
    EXPECT_EQ(skinned.weights[v], glm::vec4(1.0f - up, up, 0, 0)) << v;
  }
  ASSERT_EQ(skin.animations.size(), 1u);
  ASSERT_EQ(skin.animations[0].channels.size(), 1u);
  EXPECT_EQ(skin.animations[0].channels[0].node, 2);
  EXPECT_EQ(skin.animations[0].channels[0].path, AnimationPath::Rotation);
  const AnimationSampler& turn = skin.animations[0].samplers[0];
  EXPECT_EQ(turn.times.size(), 12u);
  EXPECT_FLOAT_EQ(turn.times.back(), 5.5f);
  EXPECT_EQ(turn.values.size(), 48u);

  const Scene cube = loadGltfFile(test::assimpModels() +
                                  "/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
  expectDrawable(cube, "AnimatedMorphCube");
  ASSERT_EQ(cube.meshes.size(), 1u);
  ASSERT_EQ(cube.meshes[0].morphTargets.size(), 2u);  // "thin" and "angle"
  for (const MorphTarget& target : cube.meshes[0].morphTargets) EXPECT_EQ(target.normals.size(), 24u);
  ASSERT_EQ(cube.nodes.size(), 1u);
  EXPECT_EQ(cube.nodes[0].weights, (std::vector<float>{0.0f, 0.0f}));
  ASSERT_EQ(cube.animations.size(), 1u);
  EXPECT_EQ(cube.animations[0].name, "Square");
  ASSERT_EQ(cube.animations[0].channels.size(), 1u);
  EXPECT_EQ(cube.animations[0].channels[0].path, AnimationPath::Weights);
  EXPECT_EQ(cube.animations[0].samplers[0].components, 2);
  EXPECT_EQ(cube.animations[0].samplers[0].times.size(), 127u);
  EXPECT_NEAR(cube.animations[0].duration(), 4.2f, 1e-4f);
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

// The fuzzer's own seeds (tests/fuzz/seeds: README.md lists the input forms each holds) load as the fuzzer loads them
// (from memory, the input's second half offered as "buffer.bin"): each is drawable, with what it is there for read,
// so that the fuzzer starts from inputs that reach those code paths; the refused-* ones are refused in one line.
TEST(GltfCorpus, FuzzerSeedsLoadAsTheFuzzerLoadsThem) {
  std::map<std::string, Scene> loaded;
  int refused = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::sourceDir() + "/tests/fuzz/seeds")) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".gltf" && ext != ".glb") continue;
    const std::string name = entry.path().filename().string();
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::map<std::string, std::vector<std::uint8_t>> sideFiles = {
        {"buffer.bin", std::vector<std::uint8_t>(bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2),
                                                 bytes.end())}};
    if (name.rfind("refused-", 0) == 0) {
      try {
        loadGltfMemory(bytes, name, sideFiles);
        ADD_FAILURE() << name << " loaded";
      } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(name + ": ", 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      }
      ++refused;
      continue;
    }
    const Scene scene = loadGltfMemory(bytes, name, sideFiles);
    expectDrawable(scene, name);
    loaded[name] = scene;
  }
  EXPECT_EQ(loaded.size(), 10u);
  EXPECT_EQ(refused, 2);
  // What moves.
  for (const char* name : {"skin-animated.gltf", "morph-sparse.glb", "hierarchy-animated.glb", "skin-40-joints.glb"}) {
    EXPECT_FALSE(loaded[name].animations.empty()) << name;
    EXPECT_TRUE(loaded[name].animated()) << name;
  }
  ASSERT_EQ(loaded["skin-40-joints.glb"].skins.size(), 1u);
  EXPECT_EQ(loaded["skin-40-joints.glb"].skins[0].joints.size(), 40u);  // beyond GLES 2's 16-joint uniform palette
  // The compressed seeds (make-compressed-seeds.mjs) are still.
  EXPECT_EQ(loaded["meshopt-quantized.glb"].triangleCount(), 128u);
  EXPECT_EQ(loaded["meshopt-quantized.glb"].lineInstances.size(), 1u);
  EXPECT_GT(loaded["draco-engine.glb"].triangleCount(), 1000u);
  // The small Draco seed: the grid twice (edgebreaker, sequential), each with its normals and texture coordinates,
  // its positions within the 14-bit quantization's step of the grid's 0..8.
  const Scene& dracoGrid = loaded["draco-grid.glb"];
  EXPECT_EQ(dracoGrid.triangleCount(), 256u);
  for (const Mesh& mesh : dracoGrid.meshes) EXPECT_EQ(mesh.texcoords.size(), mesh.positions.size());
  EXPECT_NEAR(dracoGrid.worldBounds().max.x, 8.0f, 1e-3f);
  // Materials and textures: every slot, decoded images, cut-out and blended materials.
  const Scene& materials = loaded["materials-textured.glb"];
  EXPECT_EQ(materials.materials.size(), 5u);
  EXPECT_GE(materials.textures.size(), 2u);
  // Lights (the point, the spot and the directional one, loaded beside the renderer's sun), the cameras and the
  // external buffer's quad.
  EXPECT_EQ(loaded["lights-cameras.gltf"].lights.size(), 3u);
  EXPECT_FALSE(loaded["lights-cameras.gltf"].cameras.empty());
  EXPECT_EQ(loaded["external-buffer.glb"].triangleCount(), 4u);
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
