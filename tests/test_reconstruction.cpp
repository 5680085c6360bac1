// View-space positions rebuilt from the packed G-buffer of a known plane match the true ones within the depth
// quantisation and the rasteriser's sub-pixel placement of the plane: by the CPU mirror (frame/ViewReconstruction.h)
// over the G-buffer the GPU wrote, and by the shaders' own lib/reconstruct.glsl, with the far-plane ray interpolated by
// fullscreen.vert as the passes use it; through perspective and orthographic cameras.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "TestSupport.h"
#include "encoding/LinearDepthPacking.h"
#include "frame/FrameContext.h"
#include "gl/PipelineState.h"
#include "gl/ShaderLibrary.h"

using namespace obscura;

namespace {

struct Case {
  const char* name;
  glm::vec3 eye, target;
  float near, far;
  float ymag = 0.0f;  // > 0: an orthographic camera of this half height
};

// The same check in the shader: for each G-buffer pixel, R = 1 where geometry was drawn, G = (error / bound) / 2 of
// the position lib/reconstruct.glsl rebuilds from the interpolated far-plane ray and the packed depth.
const char* kShaderCheck = R"(
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/reconstruct.glsl"
uniform sampler2D u_gbuffer;
uniform vec2 u_size;
uniform vec3 u_planeNormal;    // view space
uniform float u_planeOffset;   // dot(point on the plane, normal)
uniform float u_halfDepthStep; // half a depth code, metres
uniform float u_subpixel;      // the rasteriser's sub-pixel step, pixels
varying vec2 v_uv;
varying vec3 v_farRay;
// Where the pixel ray of far-plane point p (from the eye, or from the eye's plane along the axis) meets the plane.
vec3 onPlane(vec3 p) {
  vec3 origin = eyeRayOrigin(p), ray = eyeRay(p);
  return origin + ray * ((u_planeOffset - dot(origin, u_planeNormal)) / dot(ray, u_planeNormal));
}
void main() {
  vec4 g = texture2D(u_gbuffer, (floor(v_uv * u_size) + 0.5) / u_size);
  if (isBackgroundCode(unpackDepthCode(g.ba))) {
    gl_FragColor = vec4(0.0);
    return;
  }
  vec3 rebuilt = viewPositionOnRay(v_farRay, unpackLinearDepth(g.ba));
  vec3 truth = onPlane(v_farRay);
  // The far-plane ray moves 2 u_farHalfExtent / u_size per pixel: the plane's depth slope over one pixel each way.
  vec2 rayStep = 2.0 * u_farHalfExtent / u_size;
  float slope = abs(onPlane(v_farRay + vec3(rayStep.x, 0.0, 0.0)).z - truth.z) +
                abs(onPlane(v_farRay + vec3(0.0, rayStep.y, 0.0)).z - truth.z);
  float bound = (u_halfDepthStep + u_subpixel * slope) * length(eyeRay(v_farRay)) / u_farPlane + 1e-5 * length(truth);
  gl_FragColor = vec4(1.0, clamp(length(rebuilt - truth) / bound, 0.0, 2.0) * 0.5, 0.0, 1.0);
}
)";

// The rasteriser's sub-pixel step in pixels: it places each vertex on a grid of 2^-GL_SUBPIXEL_BITS pixels, which
// tilts a triangle's interpolated depth at a pixel by up to the depth's slope over that step (8 bits on Mesa and on
// NVIDIA's driver: on a plane seen at a grazing angle, 400 m deep, the H200's G-buffer was 5.3 times the quantisation
// bound alone off, 2026-11-30).
float subpixelStep() {
  GLint bits = 0;
  glGetIntegerv(GL_SUBPIXEL_BITS, &bits);
  return std::ldexp(1.0f, -std::max(bits, 4));  // GLES 2.0 requires at least 4
}

void checkPlaneInTheShader(const Case& c, const gl::RenderTarget& gbuffer, const FrameCamera& frame,
                           const glm::vec3& nv, const glm::vec3& pv) {
  const gl::Program program("reconstruction check", ShaderLibrary::compose("lib/fullscreen.vert", {}, {}),
                            ShaderLibrary::composeText(kShaderCheck, {}, {}));
  const gl::RenderTarget target("reconstruction check", gbuffer.width(), gbuffer.height(), GL_NEAREST,
                                gl::RenderTarget::Depth::None, false);
  target.bindForDrawing();
  program.use();
  setReconstruction(program, frame.reconstruction);
  gbuffer.color().bind(0);
  program.set(program.uniform("u_gbuffer"), 0);
  program.set(program.uniform("u_size"), glm::vec2(gbuffer.width(), gbuffer.height()));
  program.set(program.uniform("u_planeNormal"), nv);
  program.set(program.uniform("u_planeOffset"), glm::dot(pv, nv));
  program.set(program.uniform("u_halfDepthStep"), 0.5f * (c.far - c.near) / 65535.0f);
  program.set(program.uniform("u_subpixel"), subpixelStep());
  test::effectResources().triangle.draw();
  gl::restoreBaselineState();
  const std::vector<std::uint8_t> pixels = target.readRgba();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  int checked = 0, worst = 0;
  for (size_t i = 0; i < pixels.size(); i += 4) {
    if (pixels[i] != 255) continue;
    ++checked;
    worst = std::max(worst, int(pixels[i + 1]));
  }
  EXPECT_GT(checked, gbuffer.width() * gbuffer.height() / 2) << c.name;
  // 128 is a ratio of 1.0; one more step of slack for the 8-bit write.
  EXPECT_LE(worst, 129) << c.name << ": the shader's worst error is " << worst / 127.5 << " x the quantisation bound";
}

void checkPlane(const Case& c) {
  // A large tilted plane through (0, 0, 0) with normal n (world space).
  const glm::vec3 n = glm::normalize(glm::vec3(0.2f, 1.0f, 0.35f));
  const glm::vec3 u = glm::normalize(glm::cross(n, glm::vec3(0, 0, 1))) * 200.0f;
  const glm::vec3 v = glm::normalize(glm::cross(n, u)) * 200.0f;  // u x v points along n
  Renderer renderer = test::makeRenderer();
  renderer.setScene(test::sceneOf({test::makeRectangle(-0.5f * (u + v), u, v)}));
  Camera camera = test::makeCamera(c.eye, c.target, 160, 120, c.near, c.far);
  camera.orthographic = c.ymag > 0.0f;
  camera.ymag = c.ymag;
  AoSettings settings;
  settings.enabled = false;
  test::render(renderer, camera, settings, View::Final, test::retaining({"gbuffer"}));
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();

  const FrameCamera frame = FrameCamera::from(camera, camera.width, camera.height);
  // The plane in view space: normal nv, through point pv.
  const glm::vec3 nv = glm::normalize(glm::mat3(frame.view) * n);
  const glm::vec3 pv = glm::vec3(frame.view * glm::vec4(0, 0, 0, 1));
  // Pixel centre (x, y) in uv, with v up (the read-back rows are top to bottom).
  const auto uvOf = [&camera](int x, int y) {
    return glm::vec2((static_cast<float>(x) + 0.5f) / static_cast<float>(camera.width),
                     1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(camera.height));
  };
  // Where the pixel's ray meets the plane.
  const auto truthAt = [&](int x, int y) {
    const glm::vec3 farPoint = frame.reconstruction.farPlaneRay(uvOf(x, y));
    const glm::vec3 origin = frame.reconstruction.eyeRayOrigin(farPoint), ray = farPoint - origin;
    return origin + ray * (glm::dot(pv - origin, nv) / glm::dot(ray, nv));
  };
  const double subpixel = subpixelStep();
  int checked = 0;
  double worstRatio = 0.0;
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      const std::uint8_t* g = &gbuffer[(static_cast<size_t>(y) * camera.width + x) * 4];
      const std::uint16_t code = LinearDepthPacking::codeFromBytes(g[2], g[3]);
      if (code == LinearDepthPacking::kBackgroundCode) continue;
      const glm::vec2 uv = uvOf(x, y);
      const glm::vec3 rebuilt = frame.reconstruction.viewPosition(uv, LinearDepthPacking::depthFromCode(code));
      const glm::vec3 farPoint = frame.reconstruction.farPlaneRay(uv);
      const glm::vec3 ray = farPoint - frame.reconstruction.eyeRayOrigin(farPoint);
      const glm::vec3 truth = truthAt(x, y);
      // Half a depth code in metres along z, and the depth's slope over the rasteriser's sub-pixel step, scaled to
      // the ray's length, plus float slack.
      const double zStep = 0.5 * (c.far - c.near) / 65535.0;
      const double slope = std::abs(truthAt(x + 1, y).z - truth.z) + std::abs(truthAt(x, y + 1).z - truth.z);
      const double bound = (zStep + subpixel * slope) * glm::length(ray) / c.far + 1e-5 * glm::length(truth);
      const double error = glm::length(rebuilt - truth);
      worstRatio = std::max(worstRatio, error / bound);
      ++checked;
    }
  }
  EXPECT_GT(checked, camera.width * camera.height / 2) << c.name;
  EXPECT_LE(worstRatio, 1.0) << c.name << ": worst error is " << worstRatio << " x the quantisation bound";
  checkPlaneInTheShader(c, renderer.retained("gbuffer"), frame, nv, pv);
}

}  // namespace

TEST(Reconstruction, TiltedPlaneMatchesWithinDepthQuantisation) {
  checkPlane({"oblique", glm::vec3(3.0f, 4.0f, 6.0f), glm::vec3(0.0f, 0.0f, -1.0f), 0.1f, 60.0f});
}

TEST(Reconstruction, GrazingPlaneWithWideDepthRangeMatches) {
  checkPlane({"grazing", glm::vec3(0.0f, 1.2f, 8.0f), glm::vec3(0.0f, 0.6f, -20.0f), 0.05f, 400.0f});
}

TEST(Reconstruction, OrthographicPlanesMatchWithinDepthQuantisation) {
  checkPlane({"orthographic oblique", glm::vec3(3.0f, 4.0f, 6.0f), glm::vec3(0.0f, 0.0f, -1.0f), 0.0f, 60.0f, 6.0f});
  checkPlane({"orthographic grazing", glm::vec3(0.0f, 1.2f, 8.0f), glm::vec3(0.0f, 0.6f, -20.0f), 0.5f, 400.0f,
              3.0f});
}
