// The real shaders_es2/lib/packing.glsl on the GPU against its CPU mirror, through RGBA8 render targets:
// shader writes -> read back -> CPU decode (bit-exact), and CPU-packed texture -> shader decode.
#include <gtest/gtest.h>

#include <random>

#include "TestSupport.h"
#include "encoding/LinearDepthPacking.h"
#include "encoding/NormalEncoding.h"

using namespace obscura;
namespace ldp = obscura::LinearDepthPacking;

namespace {

constexpr int kSide = test::kPointSide;  // 65536 pixels: one per depth code

const char* kPointVertex = R"(
attribute vec2 a_position;
attribute vec3 a_normal;   // the value under test: a normal, (depth, 0, 0) or (byte, byte, 0)
varying vec3 v_value;
void main() {
  v_value = a_normal;
  gl_Position = vec4(a_position, 0.0, 1.0);
  gl_PointSize = 1.0;
}
)";

// One point per value at pixel i (row-major from the bottom), the value in a_normal.
std::vector<std::uint8_t> drawPoints(const gl::Program& program, const std::vector<glm::vec3>& values) {
  std::vector<glm::vec4> normal;
  normal.reserve(values.size());
  for (const glm::vec3& v : values) normal.emplace_back(v, 0.0f);
  return test::drawPoints(program, normal);
}

}  // namespace

TEST(GpuPacking, EveryDepthCodeWrittenByTheShaderDecodesExactlyOnTheCpu) {
  test::context();
  const gl::Program program = test::composedProgram("pack all codes", test::kFullscreenVertex, R"(
#include "lib/precision.glsl"
#include "lib/packing.glsl"
void main() {
  // gl_FragCoord is mediump in GLSL ES 1.00: copy it into highp variables before doing 16-bit arithmetic.
  float x = floor(gl_FragCoord.x);
  float y = floor(gl_FragCoord.y);
  float code = y * 256.0 + x;
  gl_FragColor = vec4(0.0, 0.0, packLinearDepth(code / 65535.0));
}
)");
  const std::vector<std::uint8_t> pixels = test::drawFullscreen(program);
  int mismatches = 0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const auto code = static_cast<std::uint16_t>(y * kSide + x);
      const std::uint8_t* p = &pixels[(static_cast<size_t>(y) * kSide + x) * 4];
      const auto expected = ldp::bytesFromCode(code);
      if (p[2] != expected[0] || p[3] != expected[1] || ldp::codeFromBytes(p[2], p[3]) != code) {
        if (++mismatches <= 5 || (mismatches % 5000) == 0)
          ADD_FAILURE() << "code " << code << ": GPU bytes " << int(p[2]) << "," << int(p[3]) << ", CPU "
                        << int(expected[0]) << "," << int(expected[1]);
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(GpuPacking, ArbitraryDepthsPackLikeTheCpuMirror) {
  test::context();
  std::vector<glm::vec3> values;
  for (float d : {0.0f, 1.0f, 1e-9f, 1.0f - 1e-7f, 0.5f, 0.25f, 0.75f, 1.0f / 3.0f}) values.emplace_back(d, 0, 0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  while (values.size() < kSide * kSide) {
    const float d = uniform(rng);
    // Skip values within a hair of a rounding boundary, where float evaluation order may legitimately differ.
    const float scaled = d * 65535.0f;
    if (std::abs(scaled - std::floor(scaled) - 0.5f) < 1e-3f) continue;
    values.emplace_back(d, 0, 0);
  }
  const gl::Program program = test::composedProgram("pack depths", kPointVertex, R"(
#include "lib/precision.glsl"
#include "lib/packing.glsl"
varying vec3 v_value;
void main() { gl_FragColor = vec4(0.0, 0.0, packLinearDepth(v_value.x)); }
)");
  const std::vector<std::uint8_t> pixels = drawPoints(program, values);
  int mismatches = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    const auto expected = ldp::bytesFromCode(ldp::codeFromDepth(values[i].x));
    if (pixels[i * 4 + 2] != expected[0] || pixels[i * 4 + 3] != expected[1]) {
      if (++mismatches < 5) ADD_FAILURE() << "depth " << values[i].x << ": GPU " << int(pixels[i * 4 + 2]) << ","
                                          << int(pixels[i * 4 + 3]) << " CPU " << int(expected[0]) << ","
                                          << int(expected[1]);
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(GpuPacking, NormalsEncodedByTheShaderMatchTheCpuMirror) {
  test::context();
  std::vector<glm::vec3> dirs = encodingTestDirections(50000);
  dirs.resize(std::min<size_t>(dirs.size(), kSide * kSide));
  const gl::Program program = test::composedProgram("encode normals", kPointVertex, R"(
#include "lib/precision.glsl"
#include "lib/packing.glsl"
varying vec3 v_value;
void main() { gl_FragColor = vec4(encodeNormal(v_value), 0.0, 0.0); }
)");
  const std::vector<std::uint8_t> pixels = drawPoints(program, dirs);
  int exact = 0, offByOne = 0, worse = 0;
  double maxError = 0.0;
  for (size_t i = 0; i < dirs.size(); ++i) {
    const auto cpu = encodeNormal(dirs[i]);
    const int dx = std::abs(pixels[i * 4] - cpu[0]), dy = std::abs(pixels[i * 4 + 1] - cpu[1]);
    if (dx == 0 && dy == 0) ++exact;
    else if (dx <= 1 && dy <= 1) ++offByOne;
    else ++worse;
    maxError = std::max(maxError, angleBetweenDegrees(dirs[i], decodeNormal(pixels[i * 4], pixels[i * 4 + 1])));
  }
  // Bit-exact on Mesa (both backends: all 62,506 directions). A GPU whose division rounds differently lands a value
  // sitting on a quantisation boundary in the neighbouring code (NVIDIA's driver, which multiplies by a reciprocal:
  // 1 of 62,506 on the H200, 2026-11-29): at most 1 in 10,000, and the decoded error bound holds regardless.
  EXPECT_EQ(worse, 0);
  EXPECT_LE(offByOne, static_cast<int>(dirs.size()) / 10000);
  EXPECT_EQ(exact + offByOne, static_cast<int>(dirs.size()));
  EXPECT_LT(maxError, 0.95);
  RecordProperty("exact", exact);
  RecordProperty("off_by_one", offByOne);
}

// Every code pair the encoder writes (0..254 per channel), decoded by the shader's decodeNormal and by the CPU mirror:
// the same unit vector, to the 8-bit precision the comparison can read back (n * 0.5 + 0.5 in RGB).
TEST(GpuPacking, NormalsDecodedByTheShaderMatchTheCpuMirror) {
  test::context();
  std::vector<glm::vec3> codes;
  for (int y = 0; y < 255; ++y)
    for (int x = 0; x < 255; ++x) codes.emplace_back(x, y, 0);
  const gl::Program program = test::composedProgram("decode normals", kPointVertex, R"(
#include "lib/precision.glsl"
#include "lib/packing.glsl"
varying vec3 v_value;
void main() { gl_FragColor = vec4(decodeNormal(bytesToChannels(v_value.xy)) * 0.5 + 0.5, 1.0); }
)");
  const std::vector<std::uint8_t> pixels = drawPoints(program, codes);
  int mismatches = 0;
  for (size_t i = 0; i < codes.size(); ++i) {
    const glm::vec3 cpu = decodeNormal(static_cast<std::uint8_t>(codes[i].x), static_cast<std::uint8_t>(codes[i].y));
    for (int c = 0; c < 3; ++c) {
      const float expected = (cpu[c] * 0.5f + 0.5f) * 255.0f;
      if (std::abs(static_cast<float>(pixels[i * 4 + c]) - expected) > 1.0f && ++mismatches < 5)
        ADD_FAILURE() << "code " << codes[i].x << "," << codes[i].y << " channel " << c << ": GPU "
                      << int(pixels[i * 4 + c]) << ", CPU " << expected;
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(GpuPacking, CpuPackedTexelsDecodeInTheShader) {
  test::context();
  // Texel (x, y): depth code y * 256 + x in BA; normal bytes (x, y) clamped to the encoder's 0..254 range in RG.
  std::vector<std::uint8_t> texels(kSide * kSide * 4);
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      std::uint8_t* t = &texels[(static_cast<size_t>(y) * kSide + x) * 4];
      const auto code = static_cast<std::uint16_t>(y * kSide + x);
      const auto bytes = ldp::bytesFromCode(code);
      t[0] = static_cast<std::uint8_t>(std::min(x, 254));
      t[1] = static_cast<std::uint8_t>(std::min(y, 254));
      t[2] = bytes[0];
      t[3] = bytes[1];
    }
  }
  const gl::Texture2D input(kSide, kSide, GL_NEAREST, texels.data());
  const gl::Program program = test::composedProgram("decode", test::kFullscreenVertex, R"(
#include "lib/precision.glsl"
#include "lib/packing.glsl"
uniform sampler2D u_input;
void main() {
  vec4 texel = texture2D(u_input, gl_FragCoord.xy / 256.0);
  float x = floor(gl_FragCoord.x);
  float y = floor(gl_FragCoord.y);
  float expectedCode = y * 256.0 + x;
  float decoded = unpackLinearDepth(texel.ba);
  // R: the code decodes exactly; GB: the decoded depth re-packed; A: unused.
  float exact = unpackDepthCode(texel.ba) == expectedCode && floor(decoded * 65535.0 + 0.5) == expectedCode ? 1.0 : 0.0;
  vec2 normalBytes = encodeNormal(decodeNormal(texel.rg));
  gl_FragColor = vec4(exact, normalBytes, 1.0);
}
)");
  const std::vector<std::uint8_t> pixels = test::drawFullscreen(program, &input);
  int depthFailures = 0, normalMismatches = 0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const std::uint8_t* p = &pixels[(static_cast<size_t>(y) * kSide + x) * 4];
      if (p[0] != 255) ++depthFailures;
      const std::uint8_t* t = &texels[(static_cast<size_t>(y) * kSide + x) * 4];
      const auto cpu = encodeNormal(decodeNormal(t[0], t[1]));
      if (p[1] != cpu[0] || p[2] != cpu[1]) ++normalMismatches;  // decode then re-encode: the same code, as on the CPU
    }
  }
  EXPECT_EQ(depthFailures, 0);
  EXPECT_EQ(normalMismatches, 0);
}
