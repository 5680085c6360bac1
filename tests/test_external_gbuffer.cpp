// AO on the caller's own geometry (FrameOptions::externalGBuffer, shaders_es2/lib/obscura_gbuffer.glsl, docs/api.md):
//   - Obscura's own G-buffer handed back as the caller's gives exactly the AO of Obscura's own frame;
//   - the same geometry drawn by the caller's own program with the public GLSL chunk gives the same G-buffer bytes
//     (up to rounding on a few pixels) and the same AO;
//   - the chunk's packing is the CPU mirrors' (NormalEncoding, LinearDepthPacking), bit for bit.
#include <cmath>
#include <fstream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "TestSupport.h"
#include "encoding/LinearDepthPacking.h"
#include "encoding/NormalEncoding.h"
#include "gl/PipelineState.h"
#include "gl/Program.h"
#include "gl/RenderTarget.h"
#include "scene/Primitives.h"

using namespace obscura;

namespace {

constexpr int kWidth = 192, kHeight = 128;

std::string publicChunk() {
  std::ifstream in(test::sourceDir() + "/shaders_es2/lib/obscura_gbuffer.glsl");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A caller's G-buffer program: its own vertex shader, the public chunk and one line of main().
gl::Program callerProgram() {
  const char* vertex = R"(#version 100
attribute vec3 a_position;
attribute vec3 a_normal;
uniform mat4 u_modelView;
uniform mat4 u_projection;
uniform mat3 u_normalMatrix;
varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
void main() {
  vec4 viewPosition = u_modelView * vec4(a_position, 1.0);
  v_viewPosition = viewPosition.xyz;
  v_viewNormal = u_normalMatrix * a_normal;
  gl_Position = u_projection * viewPosition;
}
)";
  const std::string fragment = "#version 100\nprecision highp float;\n" + publicChunk() + R"(
uniform float u_near;
uniform float u_far;
varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
void main() { gl_FragColor = obscuraGBuffer(normalize(v_viewNormal), -v_viewPosition.z, u_near, u_far); }
)";
  return gl::Program("caller gbuffer", vertex, fragment, true);
}

// A floor, boxes, a sphere placed by its instance's matrix: corners and contacts for the AO.
Scene testScene() {
  Scene scene = test::sceneOf({makeBox({-4.0f, -0.2f, -4.0f}, {4.0f, 0.0f, 4.0f}), makeBox({-1.2f, 0.0f, -1.0f},
                                                                                           {-0.2f, 1.2f, 0.0f}),
                               makeBox({0.3f, 0.0f, -1.6f}, {1.5f, 0.7f, -0.4f}), makeSphere(0.5f, 24, 12)});
  scene.instances[3].world = glm::translate(glm::mat4(1.0f), glm::vec3(0.4f, 0.5f, 0.7f));
  scene.designedAoRadius = 0.8f;
  return scene;
}

// Draws the scene's meshes with the caller's program into `target` (cleared to the background first), as a caller's
// engine would: its own buffers, 16-bit indices.
void drawAsCaller(const Scene& scene, const Camera& camera, const gl::RenderTarget& target) {
  target.bindForDrawing();
  const auto normal = encodeNormal(glm::vec3(0.0f, 0.0f, 1.0f));
  glClearColor(LinearDepthPacking::channelFromByte(normal[0]), LinearDepthPacking::channelFromByte(normal[1]), 1.0f,
               1.0f);
  glClearDepthf(1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  const gl::Program program = callerProgram();
  program.use();
  gl::Program::set(program.uniform("u_projection"), camera.projection());
  gl::Program::set(program.uniform("u_near"), camera.near);
  gl::Program::set(program.uniform("u_far"), camera.far);
  for (const Instance& instance : scene.instances) {
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    const glm::mat4 modelView = camera.view() * instance.world;
    gl::Program::set(program.uniform("u_modelView"), modelView);
    gl::Program::set(program.uniform("u_normalMatrix"), glm::mat3(glm::transpose(glm::inverse(glm::mat3(modelView)))));
    std::vector<float> vertices;
    for (size_t i = 0; i < mesh.positions.size(); ++i)
      vertices.insert(vertices.end(), {mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z,
                                       mesh.normals[i].x, mesh.normals[i].y, mesh.normals[i].z});
    const std::vector<std::uint16_t> indices(mesh.indices.begin(), mesh.indices.end());
    const gl::BufferHandle vertexBuffer = gl::BufferHandle::create(), indexBuffer = gl::BufferHandle::create();
    glBindBuffer(GL_ARRAY_BUFFER, vertexBuffer.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)), vertices.data(),
                 GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indexBuffer.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * 2), indices.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(gl::kAttribPosition);
    glEnableVertexAttribArray(gl::kAttribNormal);
    glVertexAttribPointer(gl::kAttribPosition, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glVertexAttribPointer(gl::kAttribNormal, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<const void*>(3 * sizeof(float)));
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(indices.size()), GL_UNSIGNED_SHORT, nullptr);
  }
  gl::restoreBaselineState();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

// An RGBA8 texture holding `rgba` (rows top to bottom, as readRgba gives them).
gl::Texture2D textureOf(const std::vector<std::uint8_t>& rgba, int width, int height) {
  std::vector<std::uint8_t> bottomUp(rgba.size());
  const size_t row = static_cast<size_t>(width) * 4;
  for (int y = 0; y < height; ++y)
    std::copy_n(rgba.begin() + static_cast<long>(row * static_cast<size_t>(y)), row,
                bottomUp.begin() + static_cast<long>(row * static_cast<size_t>(height - 1 - y)));
  return gl::Texture2D(width, height, GL_NEAREST, bottomUp.data());
}

struct Difference {
  int worst = 0;
  double mean = 0.0;
  double fractionExact = 0.0;
};
Difference redDifference(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  Difference d;
  int exact = 0;
  const size_t pixels = a.size() / 4;
  for (size_t i = 0; i < a.size(); i += 4) {
    const int delta = std::abs(int(a[i]) - int(b[i]));
    d.worst = std::max(d.worst, delta);
    d.mean += delta;
    exact += delta == 0;
  }
  d.mean /= double(pixels);
  d.fractionExact = double(exact) / double(pixels);
  return d;
}

class ExternalGBuffer : public ::testing::Test {
 protected:
  Renderer renderer = test::makeRenderer();
  Scene scene = testScene();
  Camera camera = test::makeCamera({2.6f, 2.4f, 3.4f}, {0.0f, 0.3f, -0.4f}, kWidth, kHeight, 0.1f, 20.0f);
  RenderSettings settings;
  void SetUp() override { settings.set("ao.radius", "0.8"); }
};

TEST_F(ExternalGBuffer, ObscurasOwnGBufferHandedBackGivesTheSameAoExactly) {
  renderer.setScene(scene);
  const test::RenderedImage own = test::render(renderer, camera, settings, View::Ao, test::retaining({"gbuffer"}));
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  const gl::Texture2D handed = textureOf(gbuffer, kWidth, kHeight);

  // The caller's frame: no scene of Obscura's at all.
  Renderer caller = test::makeRenderer();
  FrameOptions options = test::retaining({"gbuffer"});
  options.externalGBuffer = handed.id();
  const test::RenderedImage external = test::render(caller, camera, settings, View::Ao, options);
  EXPECT_EQ(caller.retained("gbuffer").readRgba(), gbuffer) << "the gbuffer pass copies the caller's bytes";
  EXPECT_EQ(external.rgba, own.rgba);
  // The AO did something: contacts and corners are darker than open floor.
  const Difference fromWhite = redDifference(own.rgba, std::vector<std::uint8_t>(own.rgba.size(), 255));
  EXPECT_GT(fromWhite.mean, 5.0);
  // The frame ran the AO's passes on the copied G-buffer and drew no scene.
  std::vector<std::string> ran;
  for (const PlannedPass& pass : caller.lastPlan().passes())
    if (pass.live) ran.push_back(pass.decl.name);
  EXPECT_EQ(ran.front(), "gbuffer");
  EXPECT_EQ(std::count(ran.begin(), ran.end(), "sao"), 1);
  EXPECT_EQ(std::count(ran.begin(), ran.end(), "lighting"), 0);
}

TEST_F(ExternalGBuffer, TheCallersOwnGeometryDrawnWithThePublicChunkGivesTheSameAo) {
  renderer.setScene(scene);
  const test::RenderedImage own = test::render(renderer, camera, settings, View::Ao, test::retaining({"gbuffer"}));
  const std::vector<std::uint8_t> ownGBuffer = renderer.retained("gbuffer").readRgba();

  const gl::RenderTarget drawn("caller's gbuffer", kWidth, kHeight, GL_NEAREST, gl::RenderTarget::Depth::Renderbuffer,
                               test::context().caps().depth24);
  drawAsCaller(scene, camera, drawn);
  const std::vector<std::uint8_t> callerGBuffer = drawn.readRgba();
  // The same bytes but where the two vertex stages round differently (a depth code's last bit, an edge pixel).
  int samePixels = 0;
  for (size_t i = 0; i < ownGBuffer.size(); i += 4)
    samePixels +=
        std::equal(ownGBuffer.begin() + long(i), ownGBuffer.begin() + long(i) + 4, callerGBuffer.begin() + long(i));
  const double sameFraction = double(samePixels) / (kWidth * kHeight);
  EXPECT_GT(sameFraction, 0.99) << "G-buffer pixels identical: " << sameFraction;

  Renderer caller = test::makeRenderer();
  FrameOptions options;
  options.externalGBuffer = drawn.color().id();
  const test::RenderedImage external = test::render(caller, camera, settings, View::Ao, options);
  const Difference d = redDifference(external.rgba, own.rgba);
  RecordProperty("ao_worst", d.worst);
  EXPECT_LE(d.mean, 0.1) << "mean AO difference in 1/255";
  EXPECT_GT(d.fractionExact, 0.99);
  EXPECT_LE(d.worst, 24) << "worst AO difference in 1/255 (an edge pixel)";
  std::printf("G-buffer identical at %.4f of pixels; AO: identical at %.4f, mean |diff| %.4f/255, worst %d/255\n",
              sameFraction, d.fractionExact, d.mean, d.worst);
}

TEST_F(ExternalGBuffer, ThePublicChunkPacksAsTheCpuMirrors) {
  // One point per value: the chunk's obscuraGBuffer against encodeNormal and LinearDepthPacking.
  const std::string fragment = "#version 100\nprecision highp float;\n" + publicChunk() + R"(
varying vec4 v_first;
varying vec3 v_second;
void main() { gl_FragColor = obscuraGBuffer(normalize(v_first.xyz), v_second.x, v_second.y, v_second.z); }
)";
  const gl::Program program("chunk", std::string("#version 100\n") + test::kTwoValuePointVertex, fragment, true);
  std::vector<glm::vec4> normals;
  std::vector<glm::vec3> depths;
  const float near = 0.25f, far = 60.0f;
  for (int i = 0; i < 4096; ++i) {
    const float theta = std::acos(1.0f - 2.0f * (float(i) + 0.5f) / 4096.0f), phi = 2.399963f * float(i);
    normals.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta), 0.0f);
    depths.emplace_back(near + (far - near) * float(i % 1021) / 1020.0f, near, far);
  }
  const std::vector<std::uint8_t> bytes = test::drawPoints(program, normals, depths);
  int normalMismatches = 0, depthTies = 0, depthMismatches = 0;
  for (size_t i = 0; i < normals.size(); ++i) {
    const auto n = encodeNormal(glm::normalize(glm::vec3(normals[i])));
    normalMismatches += bytes[4 * i] != n[0] || bytes[4 * i + 1] != n[1];
    const int code = LinearDepthPacking::codeFromDepth((depths[i].x - near) / (far - near));
    const int drawn = LinearDepthPacking::codeFromBytes(bytes[4 * i + 2], bytes[4 * i + 3]);
    // A quarter of these depths sit on a tie between two codes (k / 1020 of the range is 64.25 k codes). The
    // division by far - near happens on the GPU here, which may round it by an ulp (NVIDIA's driver multiplies by a
    // reciprocal: 227 of the 4096 went the other way on the H200), so a depth within a twentieth of a step of a tie
    // may take either code; any other difference is a packing error.
    const double steps = (double(depths[i].x) - near) / (double(far) - near) * 65535.0;
    const bool nearTie = std::abs(steps - std::floor(steps) - 0.5) < 0.05;
    if (drawn != code && !(nearTie && std::abs(drawn - code) == 1)) ++depthMismatches;
    depthTies += nearTie;
  }
  EXPECT_EQ(normalMismatches, 0);
  EXPECT_EQ(depthMismatches, 0);
  EXPECT_GT(depthTies, 0) << "the depths include ties";
}

}  // namespace
