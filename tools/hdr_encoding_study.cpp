// Measures the candidate HDR-in-RGBA8 encodings (src/encoding/HdrEncoding.h) and prints one table: range, round-trip
// error, banding after tone mapping and 8-bit sRGB display encoding, what bilinear filtering does to them, and the
// GPU cost of encode + decode on this machine's GL (llvmpipe here). The lighting pass uses the winner; the table and
// the reasons are recorded in HdrEncoding.h and README.md ("HDR colour in RGBA8").
//
//   obscura-hdr-study [--frames N] [--backend osmesa|egl] [--no-gpu]
//   obscura-hdr-study --glsl-constants      the literals lib/hdr.glsl and lib/tonemap.glsl share with the CPU
//   obscura-hdr-study --dump DIR            writes an encode pass per encoding and a tone-mapping pass per encoding
//                                           and operator, composed as the renderer composes its programs, for
//                                           tests/check_shaders_glslang.sh (ctest shaders.glslang_hdr)
//
// Definitions (the same words as the table's header):
//   largest       the largest value a channel (the luminance for LogLuv) holds; beyond it the encoding clamps.
//   smallest 1%   the smallest grey from which every grey up to `largest` round-trips within 1 % (200 per octave).
//   max/mean err  over colours of 64 hues x 5 saturations (0 .. 1), luminance log-spaced (100 per decade) from 1e-4
//                 to min(largest, 65536), skipping colours with a channel above `largest`: |decoded - c| per
//                 channel over c's brightest channel.
//   banding       along smooth ramps, luminance log-spaced at 1000 per decade from 1e-4 to the range plus a linear
//                 dark ramp 0 .. 0.05 in 4000 steps: the largest |display(decoded) - display(c)| in 8-bit LSBs,
//                 display = 255 * linearToSrgb(toneMap(op, c, ev)), over all five operators, at EV 0 and at the worst
//                 EV of -4 .. +4. Two sets of ramps: grey and pastel (grey, 12 hues at saturation 0.25 and 0.5), and
//                 saturated (12 hues at saturation 0.9 and 1: the dimmer channels are 10 % of the brightest, or 0).
//                 The display's own rounding is 0.5 LSB: more than that from the encoding means its steps are
//                 coarser than the display's, which shows as banding a float target would not have.
//   filtering     what a bilinear fetch halfway between two texels decodes to (bytes averaged, as the hardware
//                 does), against the average of the two decoded colours, relative to the brighter channel: for
//                 neighbours on a smooth gradient (2 % apart) and across edges (any two colours of the set).
//   cost          a 1280x720 full-screen pass that builds a colour per pixel (hue across, 1e-4 .. 64 up), encodes
//                 and decodes it, minus the same pass writing the colour plainly; each draw bounded by glFinish,
//                 median of N frames, the programs interleaved frame by frame.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "base/Error.h"
#include "encoding/ColorSpaces.h"
#include "encoding/HdrEncoding.h"
#include "encoding/ToneMapping.h"
#include "frame/FrameContext.h"
#include "frame/FullscreenTriangle.h"
#include "gl/PipelineState.h"
#include "gl/RenderTarget.h"
#include "gl/ShaderLibrary.h"
#include "platform/HeadlessContext.h"

using namespace obscura;

namespace {

constexpr float kMeasureCeiling = 65536.0f;

glm::vec3 luminanceWeights() {
  const glm::dmat3 m = ColorSpaces::rgbToXyz(ColorSpaces::kBt709);
  return glm::vec3(m[0][1], m[1][1], m[2][1]);
}

glm::vec3 withLuminance(const glm::vec3& color, float luminance) {
  return color * (luminance / glm::dot(color, luminanceWeights()));
}

float measureTop(const HdrEncoding& e) { return std::min(hdrLargestValue(e), kMeasureCeiling); }

// The largest value the encoding range check uses: per channel, or the luminance for LogLuv.
bool inRange(const HdrEncoding& e, const glm::vec3& c) {
  if (e.kind == HdrEncodingKind::LogLuv) return glm::dot(c, luminanceWeights()) <= hdrLargestValue(e);
  return std::max(c.r, std::max(c.g, c.b)) <= hdrLargestValue(e);
}

float relativeError(const glm::vec3& c, const glm::vec3& decoded) {
  const float peak = std::max(c.r, std::max(c.g, c.b));
  const glm::vec3 d = glm::abs(decoded - c);
  return std::max(d.r, std::max(d.g, d.b)) / peak;
}

glm::vec3 roundTrip(const glm::vec3& c, const HdrEncoding& e) { return decodeHdr(encodeHdr(c, e), e); }

struct Banding {
  float ev0 = 0, worst = 0, worstEv = 0;
  glm::vec3 worstColour{0.0f};
  const char* worstOperator = "";
};

struct Row {
  HdrEncoding encoding;
  float largest = 0, smallest = 0;
  double maxError = 0, meanError = 0;
  size_t colours = 0;
  Banding pastel, saturated;  // ramps of saturation 0 .. 0.5, and 0.9 .. 1
  float gradientFilterError = 0, edgeFilterError = 0;
  double costMs = -1, passMs = -1;
};

float smallestOnePercent(const HdrEncoding& e) {
  const float top = hdrLargestValue(e);
  float smallest = top;
  for (int k = 0; k < 200 * 80; ++k) {
    const float g = top * std::exp2(-static_cast<float>(k) / 200.0f);
    if (g < 1e-12f) break;
    if (relativeError(glm::vec3(g), roundTrip(glm::vec3(g), e)) > 0.01f) break;
    smallest = g;
  }
  return smallest;
}

std::vector<glm::vec3> colourSet(const HdrEncoding& e) {
  std::vector<glm::vec3> colours;
  const float top = measureTop(e);
  const int steps = static_cast<int>(std::ceil(std::log10(top / 1e-4f) * 100.0f));
  for (int h = 0; h < 64; ++h)
    for (float s : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
      if (s == 0.0f && h > 0) continue;  // grey once
      const glm::vec3 base = ColorSpaces::hsvColor(static_cast<float>(h) / 64.0f, s);
      for (int i = 0; i <= steps; ++i) {
        const float luminance = 1e-4f * std::pow(10.0f, static_cast<float>(i) / 100.0f);
        const glm::vec3 c = withLuminance(base, std::min(luminance, top));
        if (inRange(e, c)) colours.push_back(c);
      }
    }
  return colours;
}

void measureBanding(const HdrEncoding& e, const std::vector<float>& saturations, Banding& result) {
  const float top = measureTop(e);
  std::vector<glm::vec3> ramps;
  for (float s : saturations) {
    if (s == 0.0f) ramps.push_back(glm::vec3(1.0f));
    else
      for (int h = 0; h < 12; ++h) ramps.push_back(ColorSpaces::hsvColor(static_cast<float>(h) / 12.0f, s));
  }
  std::vector<float> luminances;
  const int logSteps = static_cast<int>(std::ceil(std::log10(top / 1e-4f) * 1000.0f));
  for (int i = 0; i <= logSteps; ++i) luminances.push_back(1e-4f * std::pow(10.0f, static_cast<float>(i) / 1000.0f));
  for (int i = 0; i <= 4000; ++i) luminances.push_back(0.05f * static_cast<float>(i) / 4000.0f);
  for (const glm::vec3& base : ramps) {
    for (float luminance : luminances) {
      const glm::vec3 c = withLuminance(base, std::min(luminance, top));
      if (!inRange(e, c)) continue;
      const glm::vec3 decoded = roundTrip(c, e);
      for (int ev = -4; ev <= 4; ++ev) {
        const float scale = exposureScale(static_cast<float>(ev));
        for (ToneMapOperator op : kToneMapOperators) {
          const glm::vec3 a = linearToSrgb(toneMap(op, c * scale));
          const glm::vec3 b = linearToSrgb(toneMap(op, decoded * scale));
          const glm::vec3 d = glm::abs(a - b) * 255.0f;
          const float lsb = std::max(d.r, std::max(d.g, d.b));
          if (ev == 0) result.ev0 = std::max(result.ev0, lsb);
          if (lsb > result.worst) {
            result.worst = lsb;
            result.worstEv = static_cast<float>(ev);
            result.worstOperator = toneMapOperatorName(op);
            result.worstColour = c;
          }
        }
      }
    }
  }
}

// A bilinear fetch halfway between two texels: the stored bytes averaged, read back as the decoder's nearest byte.
glm::vec3 filteredMidpoint(const HdrTexel& a, const HdrTexel& b, const HdrEncoding& e) {
  HdrTexel mid;
  for (int i = 0; i < 4; ++i)
    mid[i] = static_cast<std::uint8_t>(std::floor((static_cast<float>(a[i]) + static_cast<float>(b[i])) * 0.5f + 0.5f));
  return decodeHdr(mid, e);
}

void measureFiltering(Row& row, const std::vector<glm::vec3>& colours) {
  const HdrEncoding& e = row.encoding;
  std::mt19937 rng(11);
  std::uniform_int_distribution<size_t> pick(0, colours.size() - 1);
  for (size_t i = 0; i < colours.size(); ++i) {
    const glm::vec3 a = colours[i];
    for (const bool edge : {false, true}) {
      const glm::vec3 b = edge ? colours[pick(rng)] : a * 1.02f;
      if (!inRange(e, b)) continue;
      const HdrTexel ta = encodeHdr(a, e), tb = encodeHdr(b, e);
      const glm::vec3 expected = (decodeHdr(ta, e) + decodeHdr(tb, e)) * 0.5f;
      const glm::vec3 got = filteredMidpoint(ta, tb, e);
      const float peak = std::max(expected.r, std::max(expected.g, expected.b));
      if (peak <= 0.0f) continue;
      const glm::vec3 d = glm::abs(got - expected);
      const float error = std::max(d.r, std::max(d.g, d.b)) / peak;
      float& worst = edge ? row.edgeFilterError : row.gradientFilterError;
      worst = std::max(worst, error);
    }
  }
}

Row measure(const HdrEncoding& e) {
  Row row;
  row.encoding = e;
  row.largest = hdrLargestValue(e);
  row.smallest = smallestOnePercent(e);
  const std::vector<glm::vec3> colours = colourSet(e);
  row.colours = colours.size();
  for (const glm::vec3& c : colours) {
    const double error = relativeError(c, roundTrip(c, e));
    row.maxError = std::max(row.maxError, error);
    row.meanError += error;
  }
  row.meanError /= static_cast<double>(colours.size());
  measureBanding(e, {0.0f, 0.25f, 0.5f}, row.pastel);
  measureBanding(e, {0.9f, 1.0f}, row.saturated);
  measureFiltering(row, colours);
  return row;
}

// ---- GPU cost ----

const char* kVertex = R"(
attribute vec2 a_position;
varying vec2 v_uv;
void main() {
  v_uv = a_position * 0.5 + 0.5;
  gl_Position = vec4(a_position, 0.0, 1.0);
}
)";

const char* kFragment = R"(
#include "lib/precision.glsl"
#include "lib/hdr.glsl"
varying vec2 v_uv;
// Hue across the screen, luminance 2^-13 (1e-4) .. 2^6 (64) up it.
vec3 testColor(vec2 uv) {
  vec3 hue = clamp(abs(fract(uv.x + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
  return hue * exp2(uv.y * 19.0 - 13.0);
}
void main() {
#ifdef PLAIN
  gl_FragColor = vec4(testColor(v_uv), 1.0);
#else
  gl_FragColor = vec4(decodeHdr(encodeHdr(testColor(v_uv))), 1.0);
#endif
}
)";

// What the pipeline's two passes will look like: the lighting pass ends with encodeHdr; the tone-mapping pass fetches
// the encoded texel (NEAREST), decodes, exposes, tone-maps, encodes sRGB and puts FXAA's luma in alpha.
const char* kEncodePass = R"(
#include "lib/precision.glsl"
#include "lib/hdr.glsl"
varying vec2 v_uv;
uniform vec3 u_colour;
void main() { gl_FragColor = encodeHdr(u_colour * v_uv.x); }
)";

const char* kToneMapPass = R"(
#include "lib/precision.glsl"
#include "lib/hdr.glsl"
#include "lib/tonemap.glsl"
uniform sampler2D u_hdr;  // NEAREST: an encoded texel must not be filtered
varying vec2 v_uv;
void main() {
  vec3 srgb = linearToSrgb(toneMap(decodeHdr(texture2D(u_hdr, v_uv))));
  gl_FragColor = vec4(srgb, fxaaLuma(srgb));
}
)";

int dumpShaders(const std::string& dir) {
  auto write = [&](const std::string& name, const std::vector<std::pair<std::string, std::string>>& defines,
                   const char* fragment) {
    const std::string base = dir + "/" + name;
    std::FILE* vert = std::fopen((base + ".vert").c_str(), "w");
    std::FILE* frag = std::fopen((base + ".frag").c_str(), "w");
    if (!vert || !frag) throw InputError("cannot write " + base + ".vert/.frag");
    const std::string v = ShaderLibrary::compose("lib/fullscreen.vert", defines, {});
    const std::string f = ShaderLibrary::composeText(fragment, defines, {});
    std::fwrite(v.data(), 1, v.size(), vert);
    std::fwrite(f.data(), 1, f.size(), frag);
    std::fclose(vert);
    std::fclose(frag);
  };
  for (const HdrEncoding& e : hdrEncodingCandidates()) {
    write("hdr_encode_" + e.name(), hdrShaderDefines(e), kEncodePass);
    for (ToneMapOperator op : kToneMapOperators) {
      auto defines = hdrShaderDefines(e);
      defines.push_back(toneMapShaderDefine(op));
      write("hdr_tonemap_" + e.name() + "_" + toneMapOperatorName(op), defines, kToneMapPass);
    }
  }
  return 0;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

void measureCost(std::vector<Row>& rows, HeadlessBackend backend, int frames) {
  HeadlessContext context(backend);
  std::vector<gl::Program> programs;
  programs.emplace_back("plain", ShaderLibrary::composeText(kVertex, {}, {}),
                        ShaderLibrary::composeText(kFragment, {{"PLAIN", "1"}}, {}));
  for (const Row& row : rows)
    programs.emplace_back(row.encoding.name(), ShaderLibrary::composeText(kVertex, {}, {}),
                          ShaderLibrary::composeText(kFragment, hdrShaderDefines(row.encoding), {}));
  const gl::RenderTarget target("cost", 1280, 720, GL_NEAREST, gl::RenderTarget::Depth::None, false);
  const FullscreenTriangle triangle;
  std::vector<std::vector<double>> samples(programs.size());
  for (int frame = -5; frame < frames; ++frame) {  // five warm-up frames
    for (size_t p = 0; p < programs.size(); ++p) {
      target.bindForDrawing();
      programs[p].use();
      glFinish();
      const auto start = std::chrono::steady_clock::now();
      triangle.draw();
      glFinish();
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      if (frame >= 0) samples[p].push_back(ms);
    }
  }
  gl::restoreBaselineState();
  const double plain = median(samples[0]);
  std::printf("GPU: %s, %s; 1280x720, median of %d frames; plain pass %.3f ms\n",
              reinterpret_cast<const char*>(glGetString(GL_RENDERER)), backendName(backend), frames, plain);
  for (size_t i = 0; i < rows.size(); ++i) {
    rows[i].passMs = median(samples[i + 1]);
    rows[i].costMs = rows[i].passMs - plain;
  }
}

// %g without the padded exponent: 65408, 0.00574, 2.7e-6, 4.3e9.
std::string number(float v, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, static_cast<double>(v));
  std::string s = buffer;
  const size_t e = s.find('e');
  if (e != std::string::npos) {
    std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
    const bool negative = exponent[0] == '-';
    exponent = exponent.substr(1);
    while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
    s = mantissa + "e" + (negative ? "-" : "") + exponent;
  }
  return s;
}

std::string percent(double v) {
  char buffer[32];
  if (v >= 10.0) std::snprintf(buffer, sizeof buffer, "%.0f %%", v * 100.0 > 1e4 ? 1e4 : v * 100.0);
  else std::snprintf(buffer, sizeof buffer, "%.3g %%", v * 100.0);
  return buffer;
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 40;
  bool gpu = true;
  HeadlessBackend backend = HeadlessBackend::OSMesa;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--glsl-constants") {
        std::printf("// lib/tonemap.glsl\n%s\n// lib/hdr.glsl\n%s",
                    formatGlslConstants(toneMapShaderConstants()).c_str(),
                    formatGlslConstants(hdrShaderConstants()).c_str());
        return 0;
      } else if (arg == "--dump" && i + 1 < argc) {
        return dumpShaders(argv[i + 1]);
      } else if (arg == "--frames" && i + 1 < argc) {
        frames = std::max(1, std::atoi(argv[++i]));
      } else if (arg == "--backend" && i + 1 < argc) {
        backend = parseBackend(argv[++i]);
      } else if (arg == "--no-gpu") {
        gpu = false;
      } else {
        throw InputError("unknown option '" + arg + "' (obscura-hdr-study [--frames N] [--backend osmesa|egl] "
                         "[--no-gpu] | --glsl-constants | --dump DIR)");
      }
    }
    std::vector<Row> rows;
    for (const HdrEncoding& e : hdrEncodingCandidates()) rows.push_back(measure(e));
    if (gpu) measureCost(rows, backend, frames);

    std::printf("\n| encoding | largest | smallest (1 %%) | error, max / mean | banding, grey and pastel ramps "
                "(EV 0 / -4..+4) | banding, saturated ramps (EV 0 / -4..+4) | bilinear midpoint (gradient / edge) | "
                "encode + decode (x plain pass) |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    for (const Row& r : rows) {
      const bool chosen = r.encoding.kind == kHdrColorEncoding.kind && r.encoding.range == kHdrColorEncoding.range;
      char cost[48] = "-";
      if (r.passMs >= 0.0)
        std::snprintf(cost, sizeof cost, "%+.2f ms (x %.2f)", r.costMs, r.passMs / (r.passMs - r.costMs));
      std::printf("| %s%s%s | %s | %s | %s / %s | %.2f / %.2f LSB | %.2f / %.2f LSB | no: %s / %s | %s |\n",
                  chosen ? "**" : "", r.encoding.name().c_str(), chosen ? " (chosen)**" : "",
                  number(r.largest, r.largest < 1e6f ? 5 : 2).c_str(), number(r.smallest, 2).c_str(),
                  percent(r.maxError).c_str(), percent(r.meanError).c_str(),
                  static_cast<double>(r.pastel.ev0), static_cast<double>(r.pastel.worst),
                  static_cast<double>(r.saturated.ev0), static_cast<double>(r.saturated.worst),
                  percent(r.gradientFilterError).c_str(), percent(r.edgeFilterError).c_str(), cost);
    }
    std::printf("\nWhere the worst banding is (colour, operator, exposure), and the pass times:\n");
    for (const Row& r : rows) {
      std::printf("  %-8s %zu colours; pass %.3f ms\n", r.encoding.name().c_str(), r.colours, r.passMs);
      for (const auto& [label, b] : {std::pair<const char*, const Banding&>{"pastel", r.pastel},
                                     std::pair<const char*, const Banding&>{"saturated", r.saturated}})
        std::printf("           %-9s %.3f LSB: (%.4g, %.4g, %.4g), %s, EV %+.0f\n", label,
                    static_cast<double>(b.worst), static_cast<double>(b.worstColour.r),
                    static_cast<double>(b.worstColour.g), static_cast<double>(b.worstColour.b), b.worstOperator,
                    static_cast<double>(b.worstEv));
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "obscura-hdr-study: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "obscura-hdr-study: %s\n", e.what());
    return 1;
  }
  return 0;
}
