// CPU tests of the scene side: glTF loading (Debian's assimp-testmodels), the built-in scene, 16-bit index splitting
// and camera files.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>

#include "TestSupport.h"
#include "base/Error.h"
#include "scene/BuiltinScene.h"
#include "scene/Camera.h"
#include "scene/GltfLoader.h"
#include "scene/MeshDetail.h"
#include "scene/MeshProcessing.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {
std::string model(const std::string& relative) { return test::assimpModels() + "/" + relative; }

std::string refusal(const std::function<void()>& load) {
  try {
    load();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(GltfLoader, LoadsTheSameBoxFromGltfEmbeddedAndGlb) {
  const char* variants[] = {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Embedded/BoxTextured.gltf",
                            "BoxTextured-glTF-Binary/BoxTextured.glb"};
  for (const char* variant : variants) {
    GltfLoadReport report;
    const Scene scene = loadGltfFile(model(variant), &report);
    ASSERT_EQ(scene.instances.size(), 1u) << variant;
    EXPECT_EQ(scene.triangleCount(), 12u) << variant;
    ASSERT_EQ(scene.materials.size(), 1u) << variant;
    ASSERT_GE(scene.materials[0].baseColorTexture, 0) << variant;
    const Texture& texture = scene.textures[static_cast<size_t>(scene.materials[0].baseColorTexture)];
    ASSERT_GE(texture.image, 0) << variant;
    EXPECT_GT(scene.images[static_cast<size_t>(texture.image)].width, 0) << variant;
    EXPECT_EQ(scene.meshes[0].texcoords.size(), scene.meshes[0].positions.size()) << variant;
    // The box is a unit cube, rotated and scaled by its node hierarchy.
    const Bounds bounds = scene.worldBounds();
    EXPECT_NEAR(bounds.radius(), std::sqrt(3.0f) / 2.0f, 1e-3f) << variant;
  }
}

TEST(GltfLoader, LoadsTheTwoCylinderEngineHierarchy) {
  const Scene scene = loadGltfFile(model("2CylinderEngine-glTF-Binary/2CylinderEngine.glb"));
  EXPECT_GT(scene.instances.size(), 20u);
  EXPECT_GT(scene.triangleCount(), 50000u);
  for (const Mesh& mesh : scene.meshes) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (const glm::vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-3f);
  }
}

TEST(GltfLoader, RefusesMissingAndMalformedFilesWithOneLineNamingTheFile) {
  struct Case {
    std::string path;
    std::string expect;  // a fragment of the message
  };
  const Case cases[] = {
      {"/nonexistent/scene.gltf", "cannot open"},
      {model("MissingBin/BoxTextured.gltf"), "BoxTextured0.bin"},
      {model("IndexOutOfRange/IndexOutOfRange.gltf"), "index 255 but only 24 vertices"},
      {model("RecursiveNodes/RecursiveNodes.gltf"), "cycle"},
      {model("BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf"), "KHR_technique_webgl"},
  };
  for (const Case& c : cases) {
    const std::string message = refusal([&] { loadGltfFile(c.path); });
    ASSERT_FALSE(message.empty()) << c.path << " was accepted";
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind(c.path, 0), 0u) << message;
    if (!c.expect.empty()) {
      EXPECT_NE(message.find(c.expect), std::string::npos) << message;
    }
  }
}

TEST(GltfLoader, LoadsFromMemoryWithSideFiles) {
  auto read = [](const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(file), {});
  };
  const std::string dir = model("BoxTextured-glTF/");
  const std::map<std::string, std::vector<std::uint8_t>> sideFiles = {
      {"BoxTextured0.bin", read(dir + "BoxTextured0.bin")}, {"CesiumLogoFlat.png", read(dir + "CesiumLogoFlat.png")}};
  const Scene scene = loadGltfMemory(read(dir + "BoxTextured.gltf"), "BoxTextured.gltf", sideFiles);
  EXPECT_EQ(scene.triangleCount(), 12u);
  // Without its buffer, the same file is refused (not crashed on).
  const std::string message = refusal([&] { loadGltfMemory(read(dir + "BoxTextured.gltf"), "dropped.gltf"); });
  EXPECT_EQ(message.rfind("dropped.gltf: ", 0), 0u) << message;
}

TEST(GltfLoader, GeneratesFlatNormalsWhenMissing) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  mesh.indices = {0, 1, 2, 2, 1, 3};
  generateFlatNormals(mesh);
  ASSERT_EQ(mesh.positions.size(), 6u);
  for (const glm::vec3& n : mesh.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(MeshProcessing, SplitsLargeMeshesIntoSixteenBitPieces) {
  Mesh big = makeSphere(1.0f, 400, 200);  // 80 k vertices
  ASSERT_GT(big.positions.size(), 65535u);
  const std::vector<Mesh> pieces = splitForShortIndices(big);
  ASSERT_GT(pieces.size(), 1u);
  size_t triangles = 0;
  std::multiset<std::tuple<float, float, float>> original, split;
  for (size_t t = 0; t < big.indices.size(); ++t) {
    const glm::vec3 p = big.positions[big.indices[t]];
    original.insert({p.x, p.y, p.z});
  }
  for (const Mesh& piece : pieces) {
    EXPECT_LE(piece.positions.size(), 65535u);
    for (std::uint32_t index : piece.indices) {
      ASSERT_LT(index, piece.positions.size());
      const glm::vec3 p = piece.positions[index];
      split.insert({p.x, p.y, p.z});
    }
    triangles += piece.indices.size() / 3;
  }
  EXPECT_EQ(triangles, big.indices.size() / 3);
  EXPECT_TRUE(original == split) << "the pieces must draw exactly the original triangles";
}

// Levels of detail (scene/MeshDetail.h): coarser lists over the mesh's own vertices, each at most 80 % of the finer
// one's triangles, at a larger error within the coarsest bound (1/64 of the extent); a flat grid collapses at no
// error at all; small and deforming meshes get none.
TEST(MeshDetail, CoarserLevelsOverTheSameVerticesWithGrowingBoundedError) {
  const Mesh sphere = makeSphere(1.0f, 128, 64);
  const std::vector<DetailLevel> levels = detailLevels(sphere);
  ASSERT_GE(levels.size(), 3u);
  size_t finer = sphere.indices.size();
  float finerError = 0.0f;
  for (const DetailLevel& level : levels) {
    ASSERT_FALSE(level.indices.empty());
    EXPECT_EQ(level.indices.size() % 3, 0u);
    EXPECT_LE(level.indices.size() * 5, finer * 4);
    EXPECT_GT(level.error, finerError);
    EXPECT_LE(level.error, 2.0f / 64.0f * 1.001f);  // the sphere's extent is its diameter
    for (std::uint32_t index : level.indices) ASSERT_LT(index, sphere.positions.size());
    finer = level.indices.size();
    finerError = level.error;
  }

  Mesh grid;  // 64 x 64 quads in the plane z = 0
  const int n = 64;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      grid.positions.push_back({static_cast<float>(x), static_cast<float>(y), 0.0f});
      grid.normals.push_back({0, 0, 1});
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const auto v = static_cast<std::uint32_t>(y * (n + 1) + x), up = v + n + 1;
      grid.indices.insert(grid.indices.end(), {v, v + 1, up, up, v + 1, up + 1});
    }
  const std::vector<DetailLevel> flat = detailLevels(grid);
  ASSERT_EQ(flat.size(), 1u) << "a plane is as coarse as it gets at the first level";
  EXPECT_LT(flat[0].error, 1e-4f);
  EXPECT_LT(flat[0].indices.size(), grid.indices.size() / 10);

  EXPECT_TRUE(detailLevels(makeSphere(1.0f, 16, 8)).empty()) << "under kDetailMinTriangles";
  Mesh skinned = sphere;
  skinned.joints.assign(skinned.positions.size(), glm::u16vec4(0));
  skinned.weights.assign(skinned.positions.size(), glm::vec4(1, 0, 0, 0));
  EXPECT_TRUE(detailLevels(skinned).empty());
  Mesh morphed = sphere;
  morphed.morphTargets.push_back({std::vector<glm::vec3>(sphere.positions.size(), glm::vec3(0.1f)), {}, {}});
  EXPECT_TRUE(detailLevels(morphed).empty());
}

// The levels are made once, where a scene is loaded: a loaded file's meshes carry exactly what detailLevels makes of
// them, and adding levels again keeps those a mesh has.
TEST(MeshDetail, LoadedScenesCarryTheirLevels) {
  Scene scene = loadGltfFile(test::assimpModels() + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  size_t withLevels = 0;
  for (const Mesh& mesh : scene.meshes) {
    const std::vector<DetailLevel> made = detailLevels(mesh);
    ASSERT_EQ(mesh.levels.size(), made.size());
    for (size_t k = 0; k < made.size(); ++k) {
      EXPECT_EQ(mesh.levels[k].indices, made[k].indices);
      EXPECT_EQ(mesh.levels[k].error, made[k].error);
    }
    withLevels += made.empty() ? 0 : 1;
  }
  EXPECT_GE(withLevels, 10u) << "the engine's larger parts";
  Mesh& first =
      *std::find_if(scene.meshes.begin(), scene.meshes.end(), [](const Mesh& m) { return !m.levels.empty(); });
  first.levels.resize(1);
  addDetailLevels(scene);
  EXPECT_EQ(first.levels.size(), 1u) << "a mesh's own levels are kept";
}

TEST(BuiltinScene, IsRichAndSitsOnTheFloor) {
  const Scene scene = makeBuiltinScene();
  EXPECT_GE(scene.instances.size(), 20u);
  EXPECT_GT(scene.triangleCount(), 10000u);
  const Bounds bounds = scene.worldBounds();
  EXPECT_NEAR(bounds.min.y, -0.2f, 1e-4f);  // the floor slab's underside
  EXPECT_GT(bounds.max.y, 3.5f);
}

TEST(CameraJson, ParsesAllFieldsAndRoundTrips) {
  const Camera camera = Camera::fromJson(
      R"({"eye":[1,2,3],"target":[0,1,0],"up":[0,1,0],"fovy_deg":45,"near":0.2,"far":80,"width":320,"height":200})",
      "cam.json");
  EXPECT_EQ(camera.eye, glm::vec3(1, 2, 3));
  EXPECT_EQ(camera.width, 320);
  EXPECT_FLOAT_EQ(camera.near, 0.2f);
  const Camera again = Camera::fromJson(camera.toJson(), "again");
  EXPECT_EQ(again.eye, camera.eye);
  EXPECT_EQ(again.target, camera.target);
  EXPECT_FLOAT_EQ(again.fovyDegrees, camera.fovyDegrees);
}

TEST(CameraJson, RefusesBadInputSayingWhatAndWhere) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"eye":[1,2,3],"target":[0,1,0],)", "malformed JSON at byte"},
      {R"({"target":[0,1,0]})", "eye: missing"},
      {R"({"eye":[1,2],"target":[0,1,0]})", "eye: expected an array of three numbers"},
      {R"({"eye":[0,0,0],"target":[0,0,0]})", "target: must differ from eye"},
      {R"({"eye":[0,5,0],"target":[0,0,0]})", "up: must not be parallel"},
      {R"({"eye":[0,0,5],"target":[0,0,0],"near":0})", "near: must be > 0"},
      {R"({"eye":[0,0,5],"target":[0,0,0],"near":1,"far":0.5})", "far: must be greater than near"},
      {R"({"eye":[0,0,5],"target":[0,0,0],"fovy_deg":200})", "fovy_deg: must be in"},
      {R"({"eye":[0,0,5],"target":[0,0,0],"width":0})", "width: must be in"},
      {R"({"eye":[0,0,5],"target":[0,0,0],"fov":50})", "unknown field 'fov'"},
  };
  for (const auto& [text, expect] : cases) {
    const std::string& json = text;  // a structured binding cannot be captured before C++20 (clang refuses)
    const std::string message = refusal([&] { Camera::fromJson(json, "cam.json"); });
    EXPECT_EQ(message.rfind("cam.json: ", 0), 0u) << text << " -> " << message;
    EXPECT_NE(message.find(expect), std::string::npos) << text << " -> " << message;
  }
}

TEST(CameraFit, FramesTheBoundsInsideTheFrustum) {
  Bounds bounds;
  bounds.add({-3, 0, -1});
  bounds.add({5, 2, 4});
  const Camera camera = Camera::fit(bounds, 640, 360);
  camera.validate("fit");
  const glm::mat4 viewProjection = camera.projection() * camera.view();
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                      (corner & 4) ? bounds.max.z : bounds.min.z);
    const glm::vec4 clip = viewProjection * glm::vec4(p, 1.0f);
    EXPECT_LE(std::abs(clip.x), clip.w * 1.0001f);
    EXPECT_LE(std::abs(clip.y), clip.w * 1.0001f);
    EXPECT_LE(std::abs(clip.z), clip.w * 1.0001f);
  }
}

// Frustum culling's test (GpuScene::cullToView): a box is outside only when all its corners lie beyond one clip
// plane; one across a plane is kept.
TEST(Bounds, OutsideClipOnlyWhenWhollyBeyondOnePlane) {
  auto box = [](glm::vec3 centre, glm::vec3 half) {
    Bounds b;
    b.add(centre - half);
    b.add(centre + half);
    return b;
  };
  // The eye at the origin looking down -z, 60 degrees high, 16:9, from 0.1 to 100.
  const glm::mat4 perspective =
      glm::perspective(glm::radians(60.0f), 16.0f / 9.0f, 0.1f, 100.0f) * glm::lookAt(glm::vec3(0.0f),
                                                                                     glm::vec3(0, 0, -1),
                                                                                     glm::vec3(0, 1, 0));
  const glm::vec3 unit(0.5f);
  EXPECT_FALSE(box({0, 0, -5}, unit).outsideClip(perspective)) << "in front";
  // At 5 in front, the view reaches 5 tan 30 degrees x 16/9 = 5.13 to either side.
  EXPECT_FALSE(box({5.2f, 0, -5}, unit).outsideClip(perspective)) << "across the right edge";
  EXPECT_TRUE(box({6.5f, 0, -5}, unit).outsideClip(perspective)) << "just past the right edge";
  EXPECT_FALSE(box({0, 0, 0}, glm::vec3(1.0f)).outsideClip(perspective)) << "around the eye, across the near plane";
  EXPECT_FALSE(box({0, 0, -100}, glm::vec3(1.0f)).outsideClip(perspective)) << "across the far plane";
  EXPECT_TRUE(box({0, 0, 5}, unit).outsideClip(perspective)) << "behind the eye";
  EXPECT_TRUE(box({-50, 0, -5}, unit).outsideClip(perspective)) << "left of the view";
  EXPECT_TRUE(box({0, 20, -5}, unit).outsideClip(perspective)) << "above the view";
  EXPECT_TRUE(box({0, 0, -200}, glm::vec3(1.0f)).outsideClip(perspective)) << "beyond the far plane";
  // Moved by the model matrix too (toClip is model-view-projection).
  const glm::mat4 moved = perspective * glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 10));
  EXPECT_TRUE(box({0, 0, -5}, unit).outsideClip(moved)) << "placed behind the eye";

  const glm::mat4 orthographic = glm::ortho(-2.0f, 2.0f, -2.0f, 2.0f, 0.1f, 10.0f);
  EXPECT_TRUE(box({3, 0, -5}, unit).outsideClip(orthographic));
  EXPECT_FALSE(box({2.2f, 0, -5}, unit).outsideClip(orthographic)) << "across the right edge";
  EXPECT_TRUE(box({0, 0, 1}, unit).outsideClip(orthographic)) << "behind the near plane";
  EXPECT_TRUE(Bounds{}.outsideClip(perspective)) << "an empty box";
}

// Unwelding (flat normals) and the 16-bit split move vertices around; each vertex's joints, weights and morph
// displacements must move with it. Here every attribute of vertex v encodes v, so any mix-up shows.
TEST(MeshProcessing, VertexAttributesOfSkinningAndMorphingFollowTheirVertex) {
  Mesh mesh = makeSphere(1.0f, 400, 200);  // 80 k vertices: the split makes several pieces
  const size_t count = mesh.positions.size();
  MorphTarget target;
  for (size_t v = 0; v < count; ++v) {
    const float f = static_cast<float>(v);
    mesh.joints.push_back(glm::u16vec4(v % 7, v % 11, v % 13, v % 17));
    mesh.weights.push_back(glm::vec4(f, 0, 0, 0));
    target.positions.push_back(glm::vec3(0, f, 0));
    target.normals.push_back(glm::vec3(0, 0, f));
  }
  mesh.morphTargets.push_back(target);
  auto expectFollow = [](const Mesh& piece, const char* what) {
    ASSERT_EQ(piece.joints.size(), piece.positions.size()) << what;
    ASSERT_EQ(piece.weights.size(), piece.positions.size()) << what;
    ASSERT_EQ(piece.morphTargets.size(), 1u) << what;
    ASSERT_EQ(piece.morphTargets[0].positions.size(), piece.positions.size()) << what;
    for (size_t v = 0; v < piece.positions.size(); ++v) {
      const auto source = static_cast<size_t>(piece.weights[v].x);
      ASSERT_EQ(piece.joints[v], glm::u16vec4(source % 7, source % 11, source % 13, source % 17)) << what;
      ASSERT_EQ(piece.morphTargets[0].positions[v].y, static_cast<float>(source)) << what;
    }
  };
  for (const Mesh& piece : splitForShortIndices(mesh)) {
    expectFollow(piece, "split");
    ASSERT_EQ(piece.morphTargets[0].normals.size(), piece.positions.size());
    for (size_t v = 0; v < piece.positions.size(); ++v)
      ASSERT_EQ(piece.morphTargets[0].normals[v].z, piece.weights[v].x);
  }
  generateFlatNormals(mesh);
  expectFollow(mesh, "unwelded");
}
