#include "TestSupport.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>

#include "encoding/HdrEncoding.h"
#include "frame/FullscreenTriangle.h"
#include "gl/GlObjects.h"
#include "gl/PipelineState.h"
#include "gl/ShaderLibrary.h"
#include "scene/BuiltinScene.h"
#include "scene/GltfLoader.h"

namespace obscura::test {

const char* const kTwoValuePointVertex = R"(
attribute vec2 a_position;
attribute vec4 a_normal;
attribute vec3 a_texcoord;
varying vec4 v_first;
varying vec3 v_second;
void main() {
  v_first = a_normal;
  v_second = a_texcoord;
  gl_Position = vec4(a_position, 0.0, 1.0);
  gl_PointSize = 1.0;
}
)";

HeadlessContext& context() {
  static std::unique_ptr<HeadlessContext> instance = [] {
    const char* backend = std::getenv("OBSCURA_TEST_BACKEND");
    return std::make_unique<HeadlessContext>(parseBackend(backend ? backend : "osmesa"));
  }();
  return *instance;
}

Renderer makeRenderer(const RendererOptions& options) {
  RendererOptions checked = options;
  checked.checkGlErrors = true;
  return Renderer(context().caps(), checked);
}

const EffectResources& effectResources() {
  static const RendererOptions options = [] {
    context();  // the GL objects below need the context current
    RendererOptions checked;
    checked.checkGlErrors = true;
    return checked;
  }();
  static const FullscreenTriangle* triangle = new FullscreenTriangle();  // lives as long as the context
  static ProgramCache* programs = new ProgramCache(true);
  static SurfaceShading* surfaces = new SurfaceShading();
  static const EffectResources resources{context().caps(), options, *triangle, *programs, *surfaces};
  return resources;
}

FrameOptions retaining(std::vector<std::string> targets) {
  FrameOptions options;
  options.retain = std::move(targets);
  return options;
}

int worstByteDifference(const RenderedImage& a, const RenderedImage& b) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  int worst = 0;
  for (size_t i = 0; i < std::min(a.rgba.size(), b.rgba.size()); ++i)
    worst = std::max(worst, std::abs(a.rgba[i] - b.rgba[i]));
  return worst;
}

size_t bytesDifferingBeyond(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int tolerance) {
  EXPECT_EQ(a.size(), b.size());
  size_t differing = 0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) differing += std::abs(a[i] - b[i]) > tolerance;
  return differing;
}

ColorDifference colorDifference(const RenderedImage& a, const RenderedImage& b) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  ColorDifference d;
  double sum = 0.0;
  size_t count = 0;
  for (size_t i = 0; i < std::min(a.rgba.size(), b.rgba.size()); ++i) {
    if (i % 4 == 3) continue;
    const int difference = std::abs(a.rgba[i] - b.rgba[i]);
    d.worst = std::max(d.worst, difference);
    sum += difference;
    ++count;
  }
  d.mean = count ? sum / static_cast<double>(count) : 0.0;
  return d;
}

std::vector<std::string> livePasses(const Renderer& renderer) {
  std::vector<std::string> names;
  for (const PlannedPass& pass : renderer.lastPlan().passes()) {
    if (!pass.live) continue;
    names.push_back(pass.decl.name);
    for (const std::string& absorbed : pass.absorbed) names.push_back(absorbed + " (done by " + pass.decl.name + ")");
  }
  return names;
}

std::string passWritingOutput(const Renderer& renderer) {
  const FramePlan& plan = renderer.lastPlan();
  std::string writer;
  for (const PlannedPass& pass : plan.passes())
    if (pass.live)
      for (const auto& [target, version] : pass.writes)
        if (plan.versions()[static_cast<size_t>(version)].output) writer = pass.decl.name;
  return writer;
}

long passCount(const std::vector<std::string>& livePassNames) {
  return std::count_if(livePassNames.begin(), livePassNames.end(),
                       [](const std::string& n) { return n.find(" (done by ") == std::string::npos; });
}

namespace {
RendererOptions separateStages() {
  RendererOptions options;
  options.fuseStages = false;
  return options;
}
}  // namespace

FusedAndSeparate::FusedAndSeparate(const Scene& scene, const Camera& camera, const RenderSettings& settings)
    : fused(makeRenderer()), separate(makeRenderer(separateStages())) {
  fused.setScene(scene);
  separate.setScene(scene);
  difference = colorDifference(render(fused, camera, settings, View::Final),
                               render(separate, camera, settings, View::Final));
}

HdrImage retainedHdr(Renderer& renderer, const std::string& target) {
  const gl::RenderTarget& t = renderer.retained(target);
  const std::vector<std::uint8_t> bytes = t.readRgba();  // rows top to bottom
  HdrImage image{{t.width(), t.height()}, std::vector<glm::vec3>(static_cast<size_t>(t.width()) * t.height())};
  for (int row = 0; row < t.height(); ++row)
    for (int x = 0; x < t.width(); ++x) {
      const size_t i = (static_cast<size_t>(row) * t.width() + x) * 4;
      image.pixels[static_cast<size_t>(t.height() - 1 - row) * t.width() + x] =
          decodeHdr(HdrTexel{bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]});
    }
  return image;
}

glm::dvec3 HdrFrame::at(int x, int row) const {
  const size_t i = (static_cast<size_t>(row) * width + x) * 4;
  return glm::dvec3(decodeHdr(HdrTexel{bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]}));
}

float brightestChannel(const HdrImage& image) {
  float brightest = 0.0f;
  for (const glm::vec3& c : image.pixels) brightest = std::max(brightest, std::max(c.r, std::max(c.g, c.b)));
  return brightest;
}

namespace {

// A kPointSide x kPointSide target's bytes, bottom row first (GL's order), and the default framebuffer bound again.
std::vector<std::uint8_t> bytesFromTheBottom(const gl::RenderTarget& target) {
  const std::vector<std::uint8_t> topDown = target.readRgba();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  std::vector<std::uint8_t> bottomUp(topDown.size());
  for (int y = 0; y < kPointSide; ++y)
    std::copy_n(&topDown[static_cast<size_t>(kPointSide - 1 - y) * kPointSide * 4], kPointSide * 4,
                &bottomUp[static_cast<size_t>(y) * kPointSide * 4]);
  return bottomUp;
}

}  // namespace

std::vector<std::uint8_t> drawPoints(const gl::Program& program, const std::vector<glm::vec4>& normal,
                                     const std::vector<glm::vec3>& texcoord) {
  const gl::RenderTarget target("points", kPointSide, kPointSide, GL_NEAREST, gl::RenderTarget::Depth::None, false);
  target.bindForDrawing();
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT);
  std::vector<float> vertices;
  for (size_t i = 0; i < normal.size(); ++i) {
    const float x = (static_cast<float>(i % kPointSide) + 0.5f) / kPointSide * 2.0f - 1.0f;
    const float y = (static_cast<float>(i / kPointSide) + 0.5f) / kPointSide * 2.0f - 1.0f;
    const glm::vec3 t = i < texcoord.size() ? texcoord[i] : glm::vec3(0.0f);
    vertices.insert(vertices.end(), {x, y, normal[i].x, normal[i].y, normal[i].z, normal[i].w, t.x, t.y, t.z});
  }
  gl::BufferHandle buffer = gl::BufferHandle::create();
  glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * 4), vertices.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(gl::kAttribPosition);
  glEnableVertexAttribArray(gl::kAttribNormal);
  glEnableVertexAttribArray(gl::kAttribTexcoord);
  glVertexAttribPointer(gl::kAttribPosition, 2, GL_FLOAT, GL_FALSE, 36, nullptr);
  glVertexAttribPointer(gl::kAttribNormal, 4, GL_FLOAT, GL_FALSE, 36, reinterpret_cast<const void*>(8));
  glVertexAttribPointer(gl::kAttribTexcoord, 3, GL_FLOAT, GL_FALSE, 36, reinterpret_cast<const void*>(24));
  program.use();
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(normal.size()));
  gl::restoreBaselineState();
  return bytesFromTheBottom(target);
}

const char* const kFullscreenVertex = R"(
attribute vec2 a_position;
void main() { gl_Position = vec4(a_position, 0.0, 1.0); }
)";

std::vector<std::uint8_t> drawFullscreen(const gl::Program& program, const gl::Texture2D* input) {
  const gl::RenderTarget target("full screen", kPointSide, kPointSide, GL_NEAREST, gl::RenderTarget::Depth::None,
                                false);
  target.bindForDrawing();
  const FullscreenTriangle triangle;
  program.use();
  if (input) {
    input->bind(0);
    program.set(program.uniform("u_input"), 0);
  }
  triangle.draw();
  gl::restoreBaselineState();
  return bytesFromTheBottom(target);
}

gl::Program composedProgram(const std::string& name, const std::string& vertex, const std::string& fragment,
                            const std::vector<std::pair<std::string, std::string>>& defines) {
  return gl::Program(name, ShaderLibrary::composeText(vertex, defines, {}),
                     ShaderLibrary::composeText(fragment, defines, {}));
}

RenderedImage render(Renderer& renderer, const Camera& camera, const RenderSettings& settings, const View& view,
                     const FrameOptions& options) {
  const gl::RenderTarget output("test output", camera.width, camera.height, GL_NEAREST,
                                gl::RenderTarget::Depth::None, false);
  renderer.render(camera, settings, view, OutputTarget{output.framebuffer(), camera.width, camera.height, {}},
                  options);
  RenderedImage image;
  image.width = camera.width;
  image.height = camera.height;
  image.rgba = output.readRgba();
  return image;
}

Scene sceneOf(std::vector<Mesh> meshes) {
  Scene scene;
  for (Mesh& mesh : meshes) {
    scene.meshes.push_back(std::move(mesh));
    scene.instances.push_back({static_cast<int>(scene.meshes.size()) - 1, glm::mat4(1.0f)});
  }
  return scene;
}

int addMaterial(Scene& scene, const glm::vec3& color) {
  Material material;
  material.baseColorFactor = glm::vec4(color, 1.0f);
  scene.materials.push_back(material);
  return static_cast<int>(scene.materials.size()) - 1;
}

void addStill(Scene& scene, Mesh mesh, const glm::vec3& color) {
  mesh.material = addMaterial(scene, color);
  scene.meshes.push_back(std::move(mesh));
  scene.instances.push_back({static_cast<int>(scene.meshes.size()) - 1, glm::mat4(1.0f), -1, -1});
}

int addSlidingInstance(Scene& scene, int mesh, const glm::vec3& from, const glm::vec3& to, float seconds) {
  scene.nodes.push_back(Node{});
  const int node = static_cast<int>(scene.nodes.size()) - 1;
  if (scene.animations.empty()) scene.animations.emplace_back();
  Animation& animation = scene.animations.front();
  AnimationSampler sampler;
  sampler.times = {0.0f, seconds};
  sampler.values = {from.x, from.y, from.z, to.x, to.y, to.z};
  sampler.components = 3;
  animation.channels.push_back({static_cast<int>(animation.samplers.size()), node, AnimationPath::Translation});
  animation.samplers.push_back(std::move(sampler));
  scene.instances.push_back(Instance{mesh, glm::mat4(1.0f), node, -1});
  return static_cast<int>(scene.instances.size()) - 1;
}

Mesh makeRectangle(const glm::vec3& origin, const glm::vec3& u, const glm::vec3& v) {
  Mesh mesh;
  const glm::vec3 n = glm::normalize(glm::cross(u, v));
  mesh.positions = {origin, origin + u, origin + u + v, origin + v};
  mesh.normals = {n, n, n, n};
  mesh.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

Scene cutOutQuadOnAFloor(AlphaMode mode) {
  Scene scene = sceneOf({makeRectangle({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}),  // floor, normal +y
                         makeRectangle({-3, 0, 0}, {6, 0, 0}, {0, 2, 0})});     // quad, normal +z
  // Texel 0 (u < 0.5, the quad's left half) has alpha 0.6, texel 1 alpha 1; with the factor's 0.8 only the left
  // half falls below the cutoff (0.48 < 0.5 <= 0.8), so a pass that ignored either factor would draw it.
  Image image;
  image.width = 2;
  image.height = 1;
  image.rgba = {200, 60, 60, 153, 200, 60, 60, 255};
  scene.images.push_back(image);
  Texture texture;
  texture.image = 0;
  texture.sampler = {0x2600, 0x2600, 0x812F, 0x812F};  // GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE twice
  scene.textures.push_back(texture);
  Material material;
  material.baseColorFactor = glm::vec4(1.0f, 1.0f, 1.0f, 0.8f);
  material.baseColorTexture = 0;
  material.alphaMode = mode;
  material.alphaCutoff = 0.5f;
  scene.materials.push_back(material);
  scene.meshes[1].material = 0;
  return scene;
}

FramedScene framedBuiltinScene(int width, int height) {
  return {"builtin", makeBuiltinScene(), builtinSceneCamera(width, height)};
}

FramedScene framedScene(std::string name, Scene scene, int width, int height) {
  const Camera camera = Camera::fit(scene.worldBounds(), width, height);
  return {std::move(name), std::move(scene), camera};
}

FramedScene framedFile(std::string name, const std::string& path, int width, int height) {
  return framedScene(std::move(name), loadGltfFile(path), width, height);
}

Camera makeCamera(const glm::vec3& eye, const glm::vec3& target, int width, int height, float near, float far,
                  float fovyDegrees) {
  Camera camera;
  camera.eye = eye;
  camera.target = target;
  camera.width = width;
  camera.height = height;
  camera.near = near;
  camera.far = far;
  camera.fovyDegrees = fovyDegrees;
  return camera;
}

namespace {
std::string slurp(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}
}  // namespace

ProcessResult runProcess(const std::string& binary, const std::string& args) {
  const std::string stem = tempPath(std::string("process-") +
                                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
  const std::string out = stem + ".out", err = stem + ".err";
  const std::string command = binary + " " + args + " >" + out + " 2>" + err;
  const int raw = std::system(command.c_str());
  ProcessResult result;
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  result.out = slurp(out);
  result.err = slurp(err);
  return result;
}

std::string tempPath(const std::string& name) {
  return ::testing::TempDir() + "obscura-" + std::to_string(getpid()) + "-" + name;
}

std::string writeTempFile(const std::string& name, const std::string& text) {
  const std::string path = tempPath(name);
  std::ofstream(path) << text;
  return path;
}

std::string sourceDir() { return OBSCURA_SOURCE_DIR; }

bool backendTested(const std::string& backend) {
  const char* list = std::getenv("OBSCURA_TEST_BACKENDS");
  if (!list || !*list) return true;
  const std::string padded = "," + std::string(list) + ",";
  return padded.find("," + backend + ",") != std::string::npos;
}
std::string assimpModels() { return "/usr/share/assimp/models/glTF2"; }

}  // namespace obscura::test
