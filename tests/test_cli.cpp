// obscura-render end to end: bad input exits with status 2 and one line saying what and where; good input writes
// the image. Runs the real binary.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "TestSupport.h"
#include "renderer/EffectTable.h"
#include "renderer/RenderSettings.h"
#include "scene/ImageIo.h"

namespace {

obscura::test::ProcessResult run(const std::string& args) {
  return obscura::test::runProcess(OBSCURA_RENDER_BINARY, args);
}

std::string writeFile(const std::string& name, const std::string& text) {
  return obscura::test::writeTempFile(name, text);
}

}  // namespace

TEST(Cli, BadInputExitsWithStatusTwoAndOneLine) {
  const std::string badJson = writeFile("bad.json", R"({"eye":[1,2,3],"target":)");
  const std::string badCamera = writeFile("near.json", R"({"eye":[0,0,5],"target":[0,0,0],"near":-1})");
  const std::string notGltf = writeFile("garbage.glb", "glTF this is not a binary glTF at all");
  const std::string orthographicWithoutSize =
      writeFile("ortho.json", R"({"eye":[0,0,5],"target":[0,0,0],"type":"orthographic"})");
  const std::string repairable = obscura::test::assimpModels() + "/BoxBadNormals-glTF-Binary/BoxBadNormals.glb";
  const std::pair<std::string, std::string> cases[] = {
      {"--scene /nonexistent/scene.glb", "/nonexistent/scene.glb: cannot open"},
      {"--camera " + badJson, badJson + ": malformed JSON at byte"},
      {"--camera " + badCamera, badCamera + ": near: must be > 0"},
      {"--camera /nonexistent/cam.json", "/nonexistent/cam.json: cannot open"},
      {"--scene " + notGltf, notGltf + ": "},
      {"--frobnicate", "unknown option '--frobnicate'"},
      {"--radius -1", "--radius: -1 is out of range"},
      {"--radius", "--radius: missing value"},
      {"--samples 0", "--samples: 0 is out of range"},
      {"--size 10x", "--size: expected WxH"},
      {"--size 0x10", "--size: 0x10 is out of range"},
      {"--view sideways", "--view: expected final, split, normals, normals-from-depth, depth, mask, "},
      {"--tonemap.operator filmic", "--tonemap.operator: expected linear, reinhard, aces, neutral or agx"},
      {"--no-radius", "unknown option '--no-radius'"},
      {"--bench many", "--bench: expected a whole number"},
      {"--backend vulkan", "--backend: expected osmesa or egl"},
      {"--fit --camera x.json", "--camera and --fit exclude each other"},
      {"--fit --camera-node 0", "--camera-node: the file's camera excludes --camera and --fit"},
      {"--camera-node 0", "--camera-node: the built-in scene has no cameras"},
      {"--scene " + obscura::test::assimpModels() + "/cameras/Cameras.gltf --camera-node Top",
       "--camera-node 'Top' is not one of the scene's cameras: 0 'camera 0', 1 'camera 1'"},
      {"--camera " + orthographicWithoutSize, orthographicWithoutSize + ": ymag: missing"},
      {"--scene-scale 0", "--scene-scale: 0 is out of range"},
      {"--scene-scale big", "--scene-scale: expected a number"},
      {"--time -1", "--time: -1 is out of range (0 .. 1e+06 seconds)"},
      {"--time soon", "--time: expected a number of seconds, got 'soon'"},
      {"--fps 0", "--fps: 0 is out of range"},
      {"--frames 0", "--frames: 0 is out of range"},
      {"--frames 2.5", "--frames: expected a whole number"},
      {"--frames 4 --at 2 fog.density", "--at: expected NAME=VALUE, got 'fog.density'"},
      {"--frames 4 --at 2 fog.density=-1", "--at: fog.density: -1 is out of range"},
      {"--frames 4 --at 2 fog.thickness=1", "--at: unknown parameter 'fog.thickness'"},
      {"--frames 4 --at 4 fog=on", "--at 4: the sequence has only 4 frame(s) (--frames N)"},
      {"--view split --compare ao.radius", "--compare: expected a switch, one of ao, "},
      {"--compare fxaa", "--compare: only --view split compares"},
      {"--accumulate 0", "--accumulate: 0 is out of range"},
      {"--accumulate 4 --view ao", "--accumulate: writes the final image's reference; it takes no --view"},
      {"--shutter 0.25", "--shutter and --supersample shape the reference: they need --accumulate N"},
      {"--accumulate 4 --shutter 2", "--shutter: 2 is out of range"},
      {"--aperture 4 --accumulate 4", "--aperture: the lens's reference is of one instant"},
      {"--aperture 4 --view depth", "--aperture: writes the final image's reference; it takes no --view"},
      {"--aperture 0", "--aperture: 0 is out of range"},
      {"--animation walk", "--animation 'walk' is not in the scene; "},
      {"--scene " + obscura::test::assimpModels() + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb --animation 0",
       "--animation 0 is not in the scene; the scene has no animations (choices: none, all)"},
      {"--scene " + obscura::test::assimpModels() + "/IndexOutOfRange/IndexOutOfRange.gltf", "index 255"},
      // A file the loader repairs with a warning, refused for another input: still one line, the refusal.
      {"--scene " + repairable + " --camera " + badCamera, badCamera + ": near: must be > 0"},
      {"--scene " + repairable + " --size 16385x16", "--size: 16385x16 is out of range"},
  };
  for (const auto& [args, expect] : cases) {
    const obscura::test::ProcessResult r = run("--out " + ::testing::TempDir() + "never.png " + args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << args << " -> " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << " -> " << r.err;
  }
}

// obscura-gltf-check prints one JSON line per file whatever the file is called: a name that is not UTF-8 (which
// the refusal quotes) prints with U+FFFD in place of the stray byte, and the files after it are still checked.
TEST(Cli, GltfCheckPrintsALineForAFileNamedInBytesThatAreNotUtf8) {
  const std::string strange = writeFile("latin1-caf\xe9.gltf", "{\"asset\": ");
  const std::string box = obscura::test::assimpModels() + "/BoxTextured-glTF/BoxTextured.gltf";
  const obscura::test::ProcessResult result =
      obscura::test::runProcess(OBSCURA_GLTF_CHECK_BINARY, "'" + strange + "' '" + box + "'");
  EXPECT_EQ(result.status, 0) << result.err;
  const std::string replacement = "\xef\xbf\xbd";
  EXPECT_NE(result.out.find("latin1-caf" + replacement + ".gltf\",\"loaded\":false"), std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("BoxTextured.gltf\",\"loaded\":true"), std::string::npos) << result.out;
}

TEST(Cli, RendersEveryViewOfTheBuiltinSceneOnBothBackends) {
  for (const char* backend : {"osmesa", "egl"}) {
    // The sanitized tree tests OSMesa only: Mesa's EGL driver leaks in a module LSan cannot name (docs/robustness.md).
    if (!obscura::test::backendTested(backend)) continue;
    for (const std::string& view : obscura::frameViewNames()) {
      const std::string out = obscura::test::tempPath(std::string("view-") + backend + "-" + view + ".png");
      const obscura::test::ProcessResult r =
          run(std::string("--backend ") + backend + " --size 96x64 --view " + view + " --out " + out);
      ASSERT_EQ(r.status, 0) << backend << " " << view << ": " << r.err;
      const obscura::Image image = obscura::readPng(out);
      EXPECT_EQ(image.width, 96);
      EXPECT_EQ(image.height, 64);
    }
  }
}

// --fit frames the bounds for the output's own aspect: in a portrait image the engine stays clear of the left and
// right edges (fitted for a landscape frustum and then narrowed, it would be cut at both sides).
TEST(Cli, FitFramesTheSceneForThePortraitSizeAsked) {
  const std::string mask = obscura::test::tempPath("fit-portrait-mask.png");
  const std::string engine = obscura::test::assimpModels() + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  const obscura::test::ProcessResult r = run("--scene " + engine + " --fit --size 90x160 --view mask --out " + mask);
  ASSERT_EQ(r.status, 0) << r.err;
  const obscura::Image m = obscura::readPng(mask);
  ASSERT_EQ(m.width, 90);
  size_t geometry = 0;
  for (int y = 0; y < m.height; ++y) {
    for (int x = 0; x < m.width; ++x) {
      const bool covered = m.rgba[(static_cast<size_t>(y) * m.width + x) * 4] == 255;
      geometry += covered;
      if (x == 0 || x == m.width - 1) {
        EXPECT_FALSE(covered) << "geometry at the side edge, pixel " << x << "," << y;
      }
    }
  }
  EXPECT_GT(geometry, static_cast<size_t>(m.width * m.height) / 10);  // ... and still fills a good part of it
}

// A file's cameras (Debian's Cameras.gltf: a perspective and an orthographic camera, both with a square frame,
// looking at a square): without --size the output takes the frame's shape; an output of another shape keeps the
// whole frame, so the orthographic view of the square keeps its size in pixels along the side the frame fills.
TEST(Cli, CameraNodeLooksThroughTheFilesCamerasAndKeepsTheirFrame) {
  const std::string scene = "--scene " + obscura::test::assimpModels() + "/cameras/Cameras.gltf --view mask ";
  struct Extent {
    int width = 0, height = 0, columns = 0, rows = 0;  // the image's; the square's extent
  };
  auto extent = [&](const std::string& args) {
    const std::string out = obscura::test::tempPath("camera-node.png");
    const obscura::test::ProcessResult r = run(scene + args + " --out " + out);
    EXPECT_EQ(r.status, 0) << args << ": " << r.err;
    const obscura::Image m = obscura::readPng(out);
    Extent e{m.width, m.height, 0, 0};
    int x0 = m.width, x1 = -1, y0 = m.height, y1 = -1;
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x)
        if (m.rgba[(static_cast<size_t>(y) * m.width + x) * 4] == 255) {
          x0 = std::min(x0, x);
          x1 = std::max(x1, x);
          y0 = std::min(y0, y);
          y1 = std::max(y1, y);
        }
    e.columns = x1 - x0 + 1;
    e.rows = y1 - y0 + 1;
    return e;
  };
  const Extent perspective = extent("--camera-node 0 --size 200x200");
  EXPECT_GT(perspective.columns, 40);
  const Extent byDefault = extent("--camera-node 1");
  EXPECT_EQ(byDefault.width, 1280);
  EXPECT_EQ(byDefault.height, 1280) << "xmag = ymag: a square frame";
  const Extent square = extent("--camera-node 1 --size 200x200");
  const Extent wide = extent("--camera-node 1 --size 400x200");
  const Extent tall = extent("--camera-node 1 --size 200x400");
  EXPECT_GT(square.columns, 40);
  EXPECT_NEAR(wide.rows, square.rows, 1) << "wider: the frame's height fills the output's";
  EXPECT_NEAR(wide.columns, square.columns, 1) << "and nothing is stretched";
  EXPECT_NEAR(tall.columns, square.columns, 1) << "narrower: the frame's width fills the output's";
  EXPECT_NEAR(tall.rows, square.rows, 1);
}

TEST(Cli, MaskViewMarksExactlyTheGeometry) {
  const std::string mask = obscura::test::tempPath("mask.png"), depth = obscura::test::tempPath("mask-depth.png");
  ASSERT_EQ(run("--size 96x64 --view mask --out " + mask).status, 0);
  ASSERT_EQ(run("--size 96x64 --view depth --out " + depth).status, 0);
  const obscura::Image m = obscura::readPng(mask), d = obscura::readPng(depth);
  size_t geometry = 0;
  for (size_t i = 0; i < m.rgba.size(); i += 4) {
    ASSERT_TRUE(m.rgba[i] == 0 || m.rgba[i] == 255) << int(m.rgba[i]);
    geometry += m.rgba[i] == 255;
    // Background is white in the depth view; geometry of the built-in scene's camera lies well before the far plane.
    EXPECT_EQ(m.rgba[i] == 0, d.rgba[i] == 255) << "pixel " << i / 4;
  }
  const size_t pixels = m.rgba.size() / 4;
  EXPECT_GT(geometry, pixels / 2);  // the built-in scene fills most of its camera's view
  EXPECT_LT(geometry, pixels);      // ... with sky above the walls
}

TEST(Cli, RendersAGltfFileWithFitAndBenchPrintsEveryPass) {
  const std::string out = obscura::test::tempPath("engine.png");
  const obscura::test::ProcessResult r = run("--scene " + obscura::test::assimpModels() +
                       "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb --fit --size 160x90 --bench 2 --out " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* pass : {"gbuffer", "sao", "blur-h", "blur-v", "lighting", "tonemap", "fxaa", "total"})
    EXPECT_NE(r.out.find(pass), std::string::npos) << r.out;
  const obscura::Image image = obscura::readPng(out);
  // Not blank: the engine covers part of the frame in colours other than the background.
  std::set<std::uint32_t> colours;
  for (size_t i = 0; i < image.rgba.size(); i += 4)
    colours.insert(image.rgba[i] << 16 | image.rgba[i + 1] << 8 | image.rgba[i + 2]);
  EXPECT_GT(colours.size(), 50u);
}

TEST(Cli, HelpListsEveryParameterAndItsOldName) {
  const obscura::test::ProcessResult r = run("--help");
  EXPECT_EQ(r.status, 0);
  for (const char* name : {"--radius", "--bias", "--intensity", "--contrast", "--samples", "--blur-radius", "--no-blur"})
    EXPECT_NE(r.out.find(name), std::string::npos) << name;
  for (const obscura::ParameterInfo& p : obscura::RenderSettings::parameters())
    EXPECT_NE(r.out.find("--" + p.name + " "), std::string::npos) << p.name;
  for (const std::string& view : obscura::frameViewNames()) EXPECT_NE(r.out.find(view), std::string::npos) << view;
}

// Old and new names reach the same parameter, switches have --no- forms, and every effect's parameters are options.
TEST(Cli, OldNamesNewNamesAndSwitches) {
  const std::string a = obscura::test::tempPath("names-old.png"), b = obscura::test::tempPath("names-new.png");
  ASSERT_EQ(run("--size 96x64 --view ao --radius 2 --samples 16 --no-blur --out " + a).status, 0);
  ASSERT_EQ(run("--size 96x64 --view ao --ao.radius 2 --ao.samples 16 --ao.blur off --out " + b).status, 0);
  EXPECT_EQ(obscura::readPng(a).rgba, obscura::readPng(b).rgba);
  const std::string c = obscura::test::tempPath("names-tone.png"), d = obscura::test::tempPath("names-off.png");
  ASSERT_EQ(run("--size 96x64 --tonemap.operator agx --tonemap.exposure 1 --fxaa.preset ultra --out " + c).status, 0);
  ASSERT_EQ(run("--size 96x64 --no-tonemap --no-fxaa --no-ao --out " + d).status, 0);
  EXPECT_NE(obscura::readPng(c).rgba, obscura::readPng(d).rgba);
  // A switch without a value (followed by another option, or last) is on.
  const std::string e = obscura::test::tempPath("names-bare.png"), f = obscura::test::tempPath("names-on.png");
  ASSERT_EQ(run("--size 96x64 --out " + e + " --bloom --fog --fog.mode exp2 --no-fxaa --taa").status, 0);
  ASSERT_EQ(run("--size 96x64 --out " + f + " --bloom on --fog on --fog.mode exp2 --fxaa off --taa on").status, 0);
  EXPECT_EQ(obscura::readPng(e).rgba, obscura::readPng(f).rgba);
}

// Without --ao.radius a scene gets 5 % of its bounding-sphere diameter to two significant figures (scene/SceneScale.h;
// 42 for the engine, in centimetres), said on stderr and used: the same image as with --ao.radius 42. A radius
// given is used as given, without the note.
TEST(Cli, ChoosesTheSceneDefaultRadiusUnlessOneIsGiven) {
  const std::string engine = "--scene " + obscura::test::assimpModels() +
                             "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb --size 96x54 --view ao --out ";
  const std::string chosen = obscura::test::tempPath("radius-default.png");
  const obscura::test::ProcessResult r = run(engine + chosen);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("obscura-render: AO radius 42 (5 % of the scene's bounding-sphere diameter, 836.05"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("set --ao.radius to choose)\n"), std::string::npos) << r.err;

  const std::string given = obscura::test::tempPath("radius-42.png"), one = obscura::test::tempPath("radius-1.png");
  const obscura::test::ProcessResult r42 = run(engine + given + " --ao.radius 42");
  ASSERT_EQ(r42.status, 0) << r42.err;
  EXPECT_EQ(r42.err.find("AO radius"), std::string::npos) << "no note when the radius is given: " << r42.err;
  ASSERT_EQ(run(engine + one + " --radius 1").status, 0);
  EXPECT_EQ(obscura::readPng(chosen).rgba, obscura::readPng(given).rgba) << "the default is used";
  EXPECT_NE(obscura::readPng(one).rgba, obscura::readPng(given).rgba) << "and a radius given is used instead";

  // --scene-scale composes: the rule reads the scaled scene; the built-in scene keeps its own metre.
  const obscura::test::ProcessResult scaled = run(engine + chosen + " --scene-scale 0.01");
  ASSERT_EQ(scaled.status, 0) << scaled.err;
  EXPECT_NE(scaled.err.find("AO radius 0.42 (5 %"), std::string::npos) << scaled.err;
  const obscura::test::ProcessResult builtin = run("--size 32x18 --out " + chosen);
  ASSERT_EQ(builtin.status, 0) << builtin.err;
  EXPECT_NE(builtin.err.find("obscura-render: AO radius 1 (the radius the built-in scene was designed for"),
            std::string::npos)
      << builtin.err;
  EXPECT_NE(run("--help").out.find("AO radius: without --ao.radius, 5 % of the scene's bounding-sphere diameter"),
            std::string::npos);
}

namespace {

// Renders with `args` at 160x90 and returns the pixels (an empty vector, and a test failure, if it failed).
std::vector<std::uint8_t> renderPixels(const std::string& args, const std::string& name) {
  const std::string out = obscura::test::tempPath("timeline-" + name + ".png");
  const obscura::test::ProcessResult r = run("--size 160x90 --out " + out + " " + args);
  EXPECT_EQ(r.status, 0) << args << ": " << r.err;
  return r.status == 0 ? obscura::readPng(out).rgba : std::vector<std::uint8_t>{};
}

double meanDifference(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  if (a.size() != b.size() || a.empty()) return 255.0;
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += std::abs(int(a[i]) - int(b[i]));
  return sum / static_cast<double>(a.size());
}

}  // namespace

// The timeline on the command line, on Debian's simple_skin (a skinned strip, one unnamed 5.5 s animation). --time
// picks the moment: the strip bends otherwise at 2 s than at 0 s; the animation by index or "all" (the only one) is
// the default; "none" is the rest pose at any time; an animation the scene lacks is refused in one line listing the
// scene's.
TEST(Cli, TimeAndAnimationChooseThePose) {
  const std::string skin = "--scene " + obscura::test::assimpModels() + "/simple_skin/simple_skin.gltf --view normals";
  const auto start = renderPixels(skin, "start"), later = renderPixels(skin + " --time 2", "2");
  EXPECT_NE(start, later) << "simple_skin moves";
  EXPECT_EQ(renderPixels(skin + " --time 2 --animation 0", "index"), later);
  EXPECT_EQ(renderPixels(skin + " --time 2 --animation all", "all"), later);
  EXPECT_EQ(renderPixels(skin + " --time 2 --animation none", "none-2"),
            renderPixels(skin + " --time 4.5 --animation none", "none-4.5"));
  EXPECT_EQ(renderPixels(skin + " --time 7.5", "looped"), later) << "the timeline loops at 5.5 s";

  const obscura::test::ProcessResult bad =
      run("--out " + ::testing::TempDir() + "never.png " + skin + " --animation walk");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("obscura-render: --animation 'walk' is not in the scene; choices: none, all, 0\n"),
            std::string::npos)
      << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

// --fps is the frame interval the motion vectors measure: a moving strip's velocity differs between 10 and 60 frames
// per second; the rest pose has none at any rate.
TEST(Cli, FpsSetsTheIntervalTheVelocityMeasures) {
  const std::string skin = "--scene " + obscura::test::assimpModels() +
                           "/simple_skin/simple_skin.gltf --view velocity --time 2";
  EXPECT_NE(renderPixels(skin + " --fps 10", "velocity-10"), renderPixels(skin + " --fps 60", "velocity-60"));
  EXPECT_EQ(renderPixels(skin + " --fps 10 --animation none", "still-10"),
            renderPixels(skin + " --fps 60 --animation none", "still-60"));
}

// --frames N draws frames at T, T + 1/F, ... through one Renderer (the history carried from frame to frame) and
// writes the last: the frame at T + (N - 1)/F, as drawn alone with the same --fps, up to what the history changes.
TEST(Cli, FramesEndOnTheLastFramesTime) {
  const std::string skin = "--scene " + obscura::test::assimpModels() + "/simple_skin/simple_skin.gltf --fps 10 ";
  for (const char* view : {"final", "velocity"}) {
    const std::string v = std::string("--view ") + view + " ";
    const auto sequence = renderPixels(v + skin + "--time 1.5 --frames 6", std::string("sequence-") + view);
    const auto alone = renderPixels(v + skin + "--time 2", std::string("alone-") + view);
    const auto first = renderPixels(v + skin + "--time 1.5", std::string("first-") + view);
    EXPECT_LT(meanDifference(sequence, alone), 0.5) << view << ": the last frame is at 2 s";
    EXPECT_GT(meanDifference(sequence, first), meanDifference(sequence, alone))
        << view << ": not at the first frame's time";
  }
  const obscura::test::ProcessResult help = run("--help");
  for (const char* option : {"--time T", "--animation A", "--fps F", "--frames N"})
    EXPECT_NE(help.out.find(option), std::string::npos) << option;
}

// --at K NAME=VALUE changes a parameter from frame K on: a sequence whose last frames have fog on ends as a frame with
// fog on; and with auto exposure, a sun 16x brighter from frame 2 of 4 has not adapted by the last frame (60 fps), so
// the frame is brighter than one rendered with that sun alone (no history: adapted at once).
TEST(Cli, AtChangesAParameterWithinTheSequence) {
  const std::string small = "--size 160x90 --animation none ";
  const auto fogged = renderPixels(small + "--frames 3 --at 1 fog=on", "at-fog");
  const auto fog = renderPixels(small + "--fog", "fog-alone");
  const auto clear = renderPixels(small, "clear");
  EXPECT_LT(meanDifference(fogged, fog), 0.5);
  EXPECT_GT(meanDifference(fogged, clear), 2.0);
  const std::string exposure = small + "--auto-exposure ";
  const auto stepping = renderPixels(exposure + "--frames 4 --at 2 lighting.sun-intensity=50", "at-exposure");
  const auto adapted = renderPixels(exposure + "--lighting.sun-intensity 50", "adapted");
  double brighter = 0.0;
  for (size_t i = 0; i < stepping.size(); i += 4) brighter += static_cast<double>(stepping[i + 1]) - adapted[i + 1];
  EXPECT_GT(brighter / static_cast<double>(stepping.size() / 4), 5.0) << "not yet adapted: brighter";
  EXPECT_NE(run("--help").out.find("--at K NAME=V"), std::string::npos);
}

// --accumulate N writes the shutter reference: over a still scene, the frame itself; over simple_skin's motion, the
// mean of frames spread over the shutter, which lies between the frames at the shutter's ends.
TEST(Cli, AccumulateWritesTheShutterReference) {
  const std::string skin = "--scene " + obscura::test::assimpModels() + "/simple_skin/simple_skin.gltf --fps 2 ";
  EXPECT_LT(meanDifference(renderPixels(skin + "--time 1 --animation none --accumulate 8", "still-reference"),
                           renderPixels(skin + "--time 1 --animation none", "still-frame")),
            0.01);
  const auto reference = renderPixels(skin + "--time 1 --accumulate 16 --shutter 1", "moving-reference");
  const auto opens = renderPixels(skin + "--time 0.75", "shutter-opens");
  const auto closes = renderPixels(skin + "--time 1.25", "shutter-closes");
  const auto middle = renderPixels(skin + "--time 1", "shutter-middle");
  EXPECT_GT(meanDifference(opens, closes), 0.5) << "simple_skin moves over the shutter";
  EXPECT_LT(meanDifference(reference, middle), meanDifference(opens, closes));
  EXPECT_GT(meanDifference(reference, middle), 0.0) << "the reference integrates the motion";
  const obscura::test::ProcessResult help = run("--help");
  for (const char* option : {"--accumulate N", "--shutter S", "--supersample K"})
    EXPECT_NE(help.out.find(option), std::string::npos) << option;
}

// --aperture N writes depth of field's reference: with a pinhole-like lens (f/64) the frame without depth of field,
// with a wide one (f/0.7) a blurred frame, nearer to the effect's frame than the sharp one is (the room's blur is
// 1 to 7 pixels wide, where the half-size fields do least well: tests/test_dof.cpp holds the issue's margin on a
// scene made for it). The reference is the lens's image through the tone curve, without the display stages after it
// (AccumulationReference.h), so the frames it is compared with are undithered: dithered, the pinhole frame differs
// from the f/64 reference by 0.22 of a step on average.
TEST(Cli, ApertureWritesTheLensReference) {
  const std::string lens = "--size 480x270 --no-ao --no-fxaa --no-dither --dof.focus 6 ";
  const auto sharp = renderPixels(lens, "pinhole");
  EXPECT_LT(meanDifference(renderPixels(lens + "--dof.fstop 64 --aperture 8", "narrow-reference"), sharp), 0.1);
  const auto reference = renderPixels(lens + "--dof.fstop 0.7 --aperture 32", "wide-reference");
  const auto blurred = renderPixels(lens + "--dof.fstop 0.7 --dof", "wide-dof");
  EXPECT_GT(meanDifference(reference, sharp), 0.5) << "a wide aperture blurs the room";
  EXPECT_LT(meanDifference(reference, blurred), 0.9 * meanDifference(reference, sharp));
  const obscura::test::ProcessResult help = run("--help");
  EXPECT_NE(help.out.find("--aperture N"), std::string::npos);
  EXPECT_NE(help.out.find("--dof.fstop"), std::string::npos);
}

// --compare chooses what --view split compares: FXAA's split differs from the AO's, and its left half is the frame
// without FXAA (away from the middle, which FXAA's neighbourhood reaches across).
TEST(Cli, CompareChoosesTheSplitViewsSwitch) {
  const auto ao = renderPixels("--view split", "split-ao");
  const auto fxaa = renderPixels("--view split --compare fxaa", "split-fxaa");
  const auto noFxaa = renderPixels("--no-fxaa", "no-fxaa");
  EXPECT_NE(ao, fxaa);
  ASSERT_EQ(fxaa.size(), noFxaa.size());
  size_t leftDiffers = 0;
  for (int y = 0; y < 90; ++y)
    for (int x = 0; x < 160 / 2 - 2; ++x)
      for (int c = 0; c < 3; ++c) leftDiffers += fxaa[(y * 160 + x) * 4 + c] != noFxaa[(y * 160 + x) * 4 + c];
  EXPECT_EQ(leftDiffers, 0u);
}

// glTF files that move (Debian's assimp test models): skinning (simple_skin, one unnamed animation) and morph targets
// (AnimatedMorphCube, "Square") change the image with the time; animations go by name or index.
TEST(Cli, SkinnedAndMorphedFilesMoveWithTheTime) {
  const std::string models = obscura::test::assimpModels();
  const std::string skin = "--scene " + models + "/simple_skin/simple_skin.gltf --view normals";
  EXPECT_NE(renderPixels(skin, "skin-0"), renderPixels(skin + " --time 2", "skin-2"));
  const std::string cube =
      "--scene " + models + "/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf --view normals";
  const auto cubeLater = renderPixels(cube + " --time 1", "cube-1");
  EXPECT_NE(renderPixels(cube, "cube-0"), cubeLater);
  EXPECT_EQ(renderPixels(cube + " --time 1 --animation Square", "cube-square"), cubeLater);
  const obscura::test::ProcessResult bad =
      run("--out " + ::testing::TempDir() + "never.png " + cube + " --animation 1");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("--animation 1 is not in the scene; choices: none, all, 0 'Square'\n"), std::string::npos)
      << bad.err;
}
