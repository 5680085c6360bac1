// obscura-reference and obscura-compare end to end: bad input exits with status 2 and one line; good input writes
// the views obscura-render writes, and the compare tool's figures agree with the images. Runs the real binaries.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>

#include "TestSupport.h"
#include "scene/ImageIo.h"

namespace {

using obscura::test::ProcessResult;

ProcessResult reference(const std::string& args) { return obscura::test::runProcess(OBSCURA_REFERENCE_BINARY, args); }
ProcessResult compare(const std::string& args) { return obscura::test::runProcess(OBSCURA_COMPARE_BINARY, args); }
ProcessResult render(const std::string& args) { return obscura::test::runProcess(OBSCURA_RENDER_BINARY, args); }

void expectOneLineError(const ProcessResult& r, const std::string& args, const std::string& expect) {
  EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  EXPECT_NE(r.err.find(expect), std::string::npos) << args << " -> " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << " -> " << r.err;
}

}  // namespace

TEST(ReferenceCli, BadInputExitsWithStatusTwoAndOneLine) {
  const std::string badCamera =
      obscura::test::writeTempFile("ref-near.json", R"({"eye":[0,0,5],"target":[0,0,0],"near":-1})");
  const std::pair<std::string, std::string> cases[] = {
      {"--scene /nonexistent/scene.glb", "/nonexistent/scene.glb: cannot open"},
      {"--camera " + badCamera, badCamera + ": near: must be > 0"},
      {"--radius 0", "--radius: 0 is out of range (0.0001 .. 1e+06 scene units)"},
      {"--rays 100", "--rays: 100 must be a power of two"},
      {"--rays 0", "--rays: 0 is out of range"},
      {"--threads x", "--threads: expected a whole number"},
      {"--view normals", "--view: expected ao, depth or mask"},
      {"--size 5", "--size: expected WxH"},
      {"--scene-scale -2", "--scene-scale: -2 is out of range"},
      {"--fit --camera c.json", "--camera and --fit exclude each other"},
      {"--camera-node 0", "--camera-node: the built-in scene has no cameras"},
      {"--camera-node 0 --orthographic", "--orthographic: the file's camera (--camera-node) has its own projection"},
      {"--time -2", "--time: -2 is out of range"},
      {"--animation walk", "--animation 'walk' is not in the scene; "},
      {"--out", "--out: missing value"},
      {"--frobnicate", "unknown option '--frobnicate'"},
      {"--scene " + obscura::test::assimpModels() + "/IndexOutOfRange/IndexOutOfRange.gltf", "index 255"},
  };
  for (const auto& [args, expect] : cases)
    expectOneLineError(reference("--out " + obscura::test::tempPath("never.png") + " " + args), args, expect);
}

// The same projection, clipping and encoding: the built-in view, its orthographic twin (--orthographic), and a
// file's own orthographic and perspective cameras (--camera-node, Debian's Cameras.gltf).
TEST(ReferenceCli, WritesTheSameViewsAsObscuraRender) {
  const std::string dir = obscura::test::tempPath("");  // a per-process prefix
  const std::string cameras = "--scene " + obscura::test::assimpModels() + "/cameras/Cameras.gltf --camera-node ";
  for (const std::string& camera : {std::string(), std::string("--orthographic"), cameras + "1", cameras + "0"}) {
    const ProcessResult traced = reference("--size 96x54 --rays 16 " + camera + " --out " + dir +
                                           "ref-ao.png --depth-out " + dir + "ref-depth.png --mask-out " + dir +
                                           "ref-mask.png");
    ASSERT_EQ(traced.status, 0) << traced.err;
    EXPECT_NE(traced.out.find("16 rays per pixel"), std::string::npos) << traced.out;
    for (const char* view : {"depth", "mask"}) {
      const std::string out = dir + "sao-" + view + ".png";
      const ProcessResult r = render("--size 96x54 " + camera + " --view " + view + " --out " + out);
      ASSERT_EQ(r.status, 0) << r.err;
      const obscura::Image a = obscura::readPng(dir + "ref-" + view + ".png");
      const obscura::Image b = obscura::readPng(out);
      ASSERT_EQ(a.width, b.width);
      ASSERT_EQ(a.height, b.height);
      // Equal except where a triangle edge crosses a pixel centre.
      size_t differing = 0, geometry = 0;
      for (size_t i = 0; i < a.rgba.size(); i += 4) {
        differing += std::abs(a.rgba[i] - b.rgba[i]) > 1;
        geometry += std::string(view) == "mask" && a.rgba[i] == 255;
      }
      EXPECT_LE(differing, a.rgba.size() / 4 / 100) << view << " " << camera;
      if (std::string(view) == "mask") {
        EXPECT_GT(geometry, a.rgba.size() / 4 / 20) << camera;
      }
    }
  }
}

// obscura-reference traces the scene posed as obscura-render draws it (Debian's simple_skin, a skinned strip): at
// --time 2 their depth views agree as they do at rest, and differ from those at rest where the strip moved.
TEST(ReferenceCli, TracesTheSceneAtTheTimeAndAnimationGiven) {
  const std::string dir = obscura::test::tempPath("");  // a per-process prefix
  auto depths = [&](const std::string& args, const std::string& name) {
    const std::string traced = dir + "ref-time-" + name + ".png", drawn = dir + "sao-time-" + name + ".png";
    const std::string scene = "--scene " + obscura::test::assimpModels() + "/simple_skin/simple_skin.gltf ";
    const ProcessResult r = reference(scene + "--size 96x54 --rays 1 --view depth " + args + " --out " + traced);
    EXPECT_EQ(r.status, 0) << r.err;
    const ProcessResult d = render(scene + "--size 96x54 --view depth " + args + " --out " + drawn);
    EXPECT_EQ(d.status, 0) << d.err;
    return std::make_pair(obscura::readPng(traced), obscura::readPng(drawn));
  };
  // Pixels whose depth differs by more than the edge of a triangle crossing a pixel centre explains.
  auto differing = [](const obscura::Image& a, const obscura::Image& b) {
    size_t count = 0;
    for (size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); i += 4) count += std::abs(a.rgba[i] - b.rgba[i]) > 1;
    return count;
  };
  const auto [tracedRest, drawnRest] = depths("", "rest");
  const auto [tracedLater, drawnLater] = depths("--time 2 --animation 0", "later");
  const size_t pixels = tracedRest.rgba.size() / 4;
  EXPECT_LE(differing(tracedRest, drawnRest), pixels / 100);
  EXPECT_LE(differing(tracedLater, drawnLater), pixels / 100) << "the same pose";
  EXPECT_GT(differing(tracedLater, tracedRest), pixels / 500) << "another pose than at rest";
  const std::string help = reference("--help").out;
  EXPECT_NE(help.find("--time T"), std::string::npos);
  EXPECT_NE(help.find("--animation A"), std::string::npos);
}

// Without --radius, obscura-reference takes the radius obscura-render takes for the same scene (scene/SceneScale.h:
// 42 for the engine in centimetres), says so on stderr and traces with it; --radius is used as given.
TEST(ReferenceCli, ChoosesTheSameDefaultRadiusAsObscuraRender) {
  const std::string engine = "--scene " + obscura::test::assimpModels() +
                             "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb --size 48x27 --rays 16 --out ";
  const std::string chosen = obscura::test::tempPath("ref-radius-default.png");
  const ProcessResult r = reference(engine + chosen);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("obscura-reference: AO radius 42 (5 % of the scene's bounding-sphere diameter, 836.05"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("set --radius to choose)\n"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("radius 42, 16 rays"), std::string::npos) << r.out;
  const ProcessResult rendered = render(engine.substr(0, engine.find(" --rays")) + " --view mask --out " +
                                        obscura::test::tempPath("ref-radius-mask.png"));
  ASSERT_EQ(rendered.status, 0) << rendered.err;
  EXPECT_NE(rendered.err.find("obscura-render: AO radius 42 ("), std::string::npos) << rendered.err;

  const std::string given = obscura::test::tempPath("ref-radius-42.png");
  const std::string seven = obscura::test::tempPath("ref-radius-7.png");
  const ProcessResult r42 = reference(engine + given + " --radius 42");
  ASSERT_EQ(r42.status, 0) << r42.err;
  EXPECT_EQ(r42.err.find("AO radius"), std::string::npos) << r42.err;
  const ProcessResult r7 = reference(engine + seven + " --radius 7");
  ASSERT_EQ(r7.status, 0) << r7.err;
  EXPECT_NE(r7.out.find("radius 7, 16 rays"), std::string::npos) << r7.out;
  EXPECT_EQ(obscura::readPng(chosen).rgba, obscura::readPng(given).rgba) << "the default is used";
  EXPECT_NE(obscura::readPng(seven).rgba, obscura::readPng(given).rgba) << "and a radius given is used instead";

  const ProcessResult scaled = reference(engine + chosen + " --scene-scale 0.01");
  ASSERT_EQ(scaled.status, 0) << scaled.err;
  EXPECT_NE(scaled.err.find("AO radius 0.42 (5 %"), std::string::npos) << scaled.err;
  EXPECT_NE(reference("--help").out.find("AO radius: without --radius, 5 % of the scene's bounding-sphere"),
            std::string::npos);
}

TEST(CompareCli, BadInputExitsWithStatusTwoAndOneLine) {
  const std::string dir = obscura::test::tempPath("");  // a per-process prefix
  ASSERT_EQ(render("--size 32x20 --view ao --out " + dir + "cmp-a.png").status, 0);
  ASSERT_EQ(render("--size 30x20 --view ao --out " + dir + "cmp-small.png").status, 0);
  const std::string a = dir + "cmp-a.png", small = dir + "cmp-small.png";
  const std::pair<std::string, std::string> cases[] = {
      {a, "expected two images A.png B.png, got 1"},
      {a + " /nonexistent/b.png", "/nonexistent/b.png: cannot read image"},
      {a + " " + small, small + ": 30x20 differs from 32x20"},
      {a + " " + a + " --mask " + small, small + ": 30x20 differs from 32x20"},
      {a + " " + a + " --depth /nonexistent/d.png", "/nonexistent/d.png: cannot read image"},
      {a + " " + a + " --halo-width 2.5", "--halo-width: expected a whole number"},
      {a + " " + a + " --halo-jump -1", "--halo-jump: -1 is out of range"},
      {a + " " + a + " --wobble", "unknown option '--wobble'"},
  };
  for (const auto& [args, expect] : cases) expectOneLineError(compare(args), args, expect);
}

TEST(CompareCli, ReportsFiguresAndWritesThePictures) {
  const std::string dir = obscura::test::tempPath("");  // a per-process prefix
  ASSERT_EQ(render("--size 64x36 --view ao --out " + dir + "cmp-ao.png").status, 0);
  ASSERT_EQ(render("--size 64x36 --view ao --radius 2 --out " + dir + "cmp-ao2.png").status, 0);
  ASSERT_EQ(render("--size 64x36 --view mask --out " + dir + "cmp-mask.png").status, 0);
  ASSERT_EQ(render("--size 64x36 --view depth --out " + dir + "cmp-depth.png").status, 0);
  const std::string common = " --mask " + dir + "cmp-mask.png --depth " + dir + "cmp-depth.png --json";
  const ProcessResult same = compare(dir + "cmp-ao.png " + dir + "cmp-ao.png" + common);
  ASSERT_EQ(same.status, 0) << same.err;
  EXPECT_NE(same.out.find("\"mae\": 0.000000"), std::string::npos) << same.out;
  EXPECT_NE(same.out.find("\"ssim\": 1.000000"), std::string::npos) << same.out;
  EXPECT_NE(same.out.find("\"pearson\": 1.000000"), std::string::npos) << same.out;
  const ProcessResult different = compare(dir + "cmp-ao.png " + dir + "cmp-ao2.png" + common + " --side-by-side " +
                                          dir + "cmp-sbs.png");
  ASSERT_EQ(different.status, 0) << different.err;
  EXPECT_EQ(different.out.find("\"mae\": 0.000000"), std::string::npos) << different.out;
  EXPECT_NE(different.out.find("\"halo_mae\""), std::string::npos) << different.out;
  // Twice the radius darkens more, in much the same places: correlated, not identical (0.497 at 64x36 with GTAO by
  // sectors and its refitted table, 0.5 the bound before them; the bound leaves room for the next fit).
  const size_t at = different.out.find("\"pearson\": ");
  ASSERT_NE(at, std::string::npos) << different.out;
  const double pearson = std::stod(different.out.substr(at + 11));
  EXPECT_GT(pearson, 0.4) << different.out;
  EXPECT_LT(pearson, 1.0) << different.out;
  const obscura::Image sbs = obscura::readPng(dir + "cmp-sbs.png");
  EXPECT_EQ(sbs.width, 3 * 64 + 2 * 4);
  EXPECT_EQ(sbs.height, 36);
}

// The furnished room in millimetres (assets/scenes/room-mm.glb, used by the accuracy views) is what its generator
// writes: regenerating it gives the committed bytes, and the loader reads it in millimetres (a room about 6 m wide
// is about 6000 units, so the default radius is hundreds of units).
TEST(MakeRoom, TheCommittedRoomIsWhatTheGeneratorWrites) {
  const std::string out = obscura::test::tempPath("room-mm.glb");
  const ProcessResult made = obscura::test::runProcess(OBSCURA_MAKE_ROOM_BINARY, out);
  ASSERT_EQ(made.status, 0) << made.err;
  auto bytes = [](const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  };
  const std::string committed = bytes(obscura::test::sourceDir() + "/assets/scenes/room-mm.glb");
  ASSERT_FALSE(committed.empty());
  EXPECT_TRUE(bytes(out) == committed) << "re-run build/obscura-make-room assets/scenes/room-mm.glb and commit it";
  const ProcessResult rendered =
      render("--scene " + obscura::test::sourceDir() + "/assets/scenes/room-mm.glb --size 64x36 --view ao --out " +
             obscura::test::tempPath("room.png"));
  ASSERT_EQ(rendered.status, 0) << rendered.err;
  EXPECT_NE(rendered.err.find("AO radius 430 "), std::string::npos) << rendered.err;
}
