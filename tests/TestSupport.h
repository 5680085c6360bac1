#pragma once
// Shared helpers for the GPU tests: one headless context per test binary (backend from OBSCURA_TEST_BACKEND,
// "osmesa" by default; ctest runs the GPU suite once per backend), synthetic scenes and image statistics.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <gtest/gtest.h>

#include "effects/ao/AoSettings.h"
#include "gl/Program.h"
#include "gl/RenderTarget.h"
#include "platform/HeadlessContext.h"
#include "renderer/EffectTable.h"
#include "renderer/RenderSettings.h"
#include "renderer/Renderer.h"
#include "scene/Camera.h"
#include "scene/Scene.h"

namespace obscura::test {

HeadlessContext& context();

// A renderer for the test context with GL error checks (and strict programs, and the baseline-state check) after
// every pass.
Renderer makeRenderer(const RendererOptions& options = {});
// What a Renderer lends its effects, for tests that build a pass alone (strict programs).
const EffectResources& effectResources();

// Renders `view` into an offscreen RGBA8 target and reads it back (rows top to bottom).
struct RenderedImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  std::uint8_t channel(int x, int y, int c) const { return rgba[(static_cast<size_t>(y) * width + x) * 4 + c]; }
  float red(int x, int y) const { return channel(x, y, 0) / 255.0f; }
};
RenderedImage render(Renderer& renderer, const Camera& camera, const RenderSettings& settings, const View& view,
                     const FrameOptions& options = {});
// FrameOptions that keep these targets readable after the frame (Renderer::retained).
FrameOptions retaining(std::vector<std::string> targets);
// The largest difference of any byte between two images of one size.
int worstByteDifference(const RenderedImage& a, const RenderedImage& b);
// How many bytes of two byte arrays of one size differ by more than `tolerance`.
size_t bytesDifferingBeyond(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int tolerance);
// Over the colour channels (alpha left out) of two images of one size: the largest difference and the mean, in
// levels of 255.
struct ColorDifference {
  int worst = 0;
  double mean = 0.0;
};
ColorDifference colorDifference(const RenderedImage& a, const RenderedImage& b);
// The live passes of the renderer's last plan, by name, each followed by the stages it absorbed as
// "NAME (done by PASS)".
std::vector<std::string> livePasses(const Renderer& renderer);
// The live pass of the last frame that drew the output ("" where none did).
std::string passWritingOutput(const Renderer& renderer);
// The passes among livePasses' names (the absorbed stages left out).
long passCount(const std::vector<std::string>& livePassNames);
// One frame of `scene` drawn by two Renderers: one fusing the per-pixel stages into the passes before them, one
// running each as a pass of its own (RendererOptions::fuseStages); their plans stay readable (lastPlan()).
struct FusedAndSeparate {
  FusedAndSeparate(const Scene& scene, const Camera& camera, const RenderSettings& settings);
  Renderer fused, separate;
  ColorDifference difference;
};

// A retained RGB9E5 target (scene-color, bloom's and the flare's targets) decoded, rows bottom to top (GL's order,
// as uv).
struct HdrImage {
  glm::ivec2 size{0};
  std::vector<glm::vec3> pixels;
  const glm::vec3& at(int x, int y) const { return pixels[static_cast<size_t>(y) * size.x + x]; }
};
HdrImage retainedHdr(Renderer& renderer, const std::string& target);
// An RGB9E5 target's bytes as read back (rows top to bottom), decoded texel by texel on demand.
struct HdrFrame {
  int width = 0, height = 0;
  std::vector<std::uint8_t> bytes;
  glm::dvec3 at(int x, int row) const;
};
// The largest colour channel of any pixel.
float brightestChannel(const HdrImage& image);

// Shader tests at one value per pixel: draws one point per value into pixel i (row-major from the bottom) of a
// kPointSide x kPointSide RGBA8 target cleared to 0, with normal[i] in the attribute a_normal (slot kAttribNormal;
// a vec3 attribute takes xyz) and texcoord[i], where given, in a_texcoord (0 elsewhere), and returns the target's bytes
// in that order (pixel i at 4 i).
constexpr int kPointSide = 256;
// The vertex shader for drawPoints with two values per point: a_normal (vec4) to v_first, a_texcoord (vec3) to
// v_second.
extern const char* const kTwoValuePointVertex;
std::vector<std::uint8_t> drawPoints(const gl::Program& program, const std::vector<glm::vec4>& normal,
                                     const std::vector<glm::vec3>& texcoord = {});
// The same target drawn whole by `program` with a full-screen triangle (kFullscreenVertex: a_position in clip space),
// `input`, where given, bound to the program's sampler u_input on unit 0; the bytes in drawPoints' order (pixel (x, y)
// from the bottom at 4 (y kPointSide + x)).
extern const char* const kFullscreenVertex;
std::vector<std::uint8_t> drawFullscreen(const gl::Program& program, const gl::Texture2D* input = nullptr);
// A program from test shader text that includes the library's files (ShaderLibrary::composeText), with `defines`.
gl::Program composedProgram(const std::string& name, const std::string& vertex, const std::string& fragment,
                            const std::vector<std::pair<std::string, std::string>>& defines = {});

// Scenes made of one material-less mesh placed with an identity transform.
Scene sceneOf(std::vector<Mesh> meshes);
// A rectangle in the plane through `origin` spanned by `u` and `v` (normal u x v), one quad.
Mesh makeRectangle(const glm::vec3& origin, const glm::vec3& u, const glm::vec3& v);

// Adds a material of base colour `color` (opaque, the other factors at glTF's defaults); returns its index.
int addMaterial(Scene& scene, const glm::vec3& color);
// Adds `mesh` in a material of that colour, and an instance of it where its vertices put it (no node: still).
void addStill(Scene& scene, Mesh mesh, const glm::vec3& color);

// Adds an instance of `mesh` (placed by its own vertices) on a new node that a LINEAR translation, in animation 0
// (made if the scene has none), moves from `from` to `to` over `seconds`. Returns the instance's index.
int addSlidingInstance(Scene& scene, int mesh, const glm::vec3& from, const glm::vec3& to, float seconds);

// A floor (y = 0, 20 m square) and a 6 x 2 m quad standing on it in the plane z = 0 (x from -3 to 3, facing +z),
// whose base colour (factor alpha 0.8 times a nearest, clamped texture) is below the 0.5 cutoff on its left half
// (x < 0) and above it on the right, with alphaMode `mode`.
Scene cutOutQuadOnAFloor(AlphaMode mode);

// A scene and a camera at a size that frames it: the cases of tests that draw several scenes the same two ways.
struct FramedScene {
  std::string name;
  Scene scene;
  Camera camera;
};
// The built-in scene with its own camera, and a scene (or a glTF file's) with Camera::fit's.
FramedScene framedBuiltinScene(int width, int height);
FramedScene framedScene(std::string name, Scene scene, int width, int height);
FramedScene framedFile(std::string name, const std::string& path, int width, int height);

// Camera looking from eye to target, with explicit size and planes.
Camera makeCamera(const glm::vec3& eye, const glm::vec3& target, int width, int height, float near = 0.1f,
                  float far = 100.0f, float fovyDegrees = 50.0f);

// Runs `binary args` through the shell, capturing stdout and stderr (in files named after the process and the test:
// ctest runs the tests of one binary as parallel processes).
struct ProcessResult {
  int status = -1;  // exit status, or 128 + signal
  std::string out, err;
};
ProcessResult runProcess(const std::string& binary, const std::string& args);
// TempDir()/obscura-<pid>-<name>: unique per process, since several test runs may share the machine's TempDir().
std::string tempPath(const std::string& name);
// Writes `text` to tempPath(name) and returns the path.
std::string writeTempFile(const std::string& name, const std::string& text);

std::string sourceDir();  // the repository root (for assets and goldens)
// Whether this tree tests `backend` ("osmesa", "egl"): the comma-separated OBSCURA_TEST_BACKENDS ctest sets from the
// CMake option of that name; every backend where it is unset.
bool backendTested(const std::string& backend);
std::string assimpModels();  // /usr/share/assimp/models/glTF2

}  // namespace obscura::test
