#include "effects/edges/EdgesEffect.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "encoding/LinearDepthPacking.h"
#include "encoding/NormalEncoding.h"
#include "encoding/ToneMapping.h"
#include "frame/PassContext.h"

namespace obscura {
namespace {

constexpr EdgeStyle kEdgeStyles[] = {EdgeStyle::Lines, EdgeStyle::Toon, EdgeStyle::Hatching};
constexpr float kMinWidth = 1.0f, kMaxWidth = 8.0f;
constexpr float kRadiansPerDegree = 0.017453292519943295f;

ProgramSpec detectSpec(bool colorEdges) {
  return ProgramSpec{std::string("edges[detect") + (colorEdges ? ",color" : "") + "]",
                     "lib/fullscreen.vert",
                     "edges/edges.frag",
                     {{"EDGES_PASS", "1"}, {"COLOR_EDGES", colorEdges ? "1" : "0"}, {"FAR_RAY", "0"}},
                     {}};
}

ProgramSpec distanceSpec(int radius) {
  return ProgramSpec{"edges[distance,radius=" + std::to_string(radius) + "]",
                     "lib/fullscreen.vert",
                     "edges/edges.frag",
                     {{"EDGES_PASS", "2"}, {"EDGE_RADIUS", std::to_string(radius)}, {"FAR_RAY", "0"}},
                     {}};
}

ProgramSpec drawSpec(int radius, EdgeStyle style) {
  const bool toon = style == EdgeStyle::Toon, hatching = style == EdgeStyle::Hatching;
  return ProgramSpec{"edges[draw,radius=" + std::to_string(radius) + (toon ? ",toon" : hatching ? ",hatching" : "") +
                         "]",
                     "lib/fullscreen.vert",
                     "edges/edges.frag",
                     {{"EDGES_PASS", "3"},
                      {"EDGE_RADIUS", std::to_string(radius)},
                      {"TOON", toon ? "1" : "0"},
                      {"HATCHING", hatching ? "1" : "0"},
                      {"FAR_RAY", hatching ? "1" : "0"}},
                     {}};
}

const char* kMaskEncoding = "R profile (depth), G crease (normals), B colour edge: 1 on the pixel that carries the "
                            "line (the nearer side; the darker for colour), else 0; A 1";
const char* kDistanceEncoding = "R the distance in pixels to the nearest edge pixel of the row within the line's "
                                "reach R, R + 1 where none, as a byte";

}  // namespace

const char* edgeStyleName(EdgeStyle style) {
  switch (style) {
    case EdgeStyle::Lines: return "lines";
    case EdgeStyle::Toon: return "toon";
    case EdgeStyle::Hatching: return "hatching";
  }
  return "?";
}

const std::vector<Parameter<EdgesSettings>>& EdgesSettings::parameters() {
  using S = EdgesSettings;
  static const std::vector<Parameter<S>> table = [] {
    std::vector<std::pair<std::string, EdgeStyle>> styles;
    for (EdgeStyle choice : kEdgeStyles) styles.emplace_back(edgeStyleName(choice), choice);
    return std::vector<Parameter<S>>{
        switchParameter<S>("edges", "lines on the G-buffer's profiles and creases on or off", &S::enabled).primary(),
        choiceParameter<S, EdgeStyle>("style",
                                      "lines: over the shading; toon: the shading in flat bands, and lines; hatching: "
                                      "strokes on white paper, denser where darker, and lines",
                                      &S::style, styles)
            .primary(),
        numberParameter<S>("width", kMinWidth, kMaxWidth, "px", "the lines' width in output pixels", &S::width)
            .primary()
            .shapesPlan(),  // the line's reach R, the passes' loop bound
        colorParameter<S>("color", 0, 1, "the lines' colour", &S::color).primary(),
        numberParameter<S>("strength", 0, 1, "", "the lines' opacity", &S::strength),
        numberParameter<S>("depth-threshold", 0.001, 1, "",
                           "least relative depth jump that is a profile (second difference of 1/z, times z)",
                           &S::depthThreshold),
        numberParameter<S>("normal-threshold", 1, 179, "degrees", "least angle between neighbouring normals that is "
                           "a crease", &S::normalThreshold),
        numberParameter<S>("color-threshold", 0, 1, "", "least step of display luma that is an edge; 0: none",
                           &S::colorThreshold)
            .shapesPlan(),  // above 0 the detection reads the display colour
        integerParameter<S>("bands", 2, 16, "", "", "toon and hatching: the shading's levels", &S::bands),
        numberParameter<S>("hatch-spacing", 2, 32, "px", "hatching: the pixels between strokes", &S::hatchSpacing)};
  }();
  return table;
}

EdgeDetector EdgeDetector::of(const EdgesSettings& settings, float near, float far, float orthographicDepth) {
  EdgeDetector d;
  d.depthThreshold = settings.depthThreshold;
  d.normalCos = std::cos(settings.normalThreshold * kRadiansPerDegree);
  d.colorThreshold = settings.colorThreshold;
  d.near = near;
  d.depthRange = far - near;
  d.orthographicDepth = orthographicDepth;
  return d;
}

float EdgeDetector::viewDepth(const std::uint8_t* texel) const {
  const std::uint16_t code = LinearDepthPacking::codeFromBytes(texel[2], texel[3]);
  if (code == 65535) return 0.0f;
  return near + static_cast<float>(code) * (depthRange / 65535.0f);
}

float EdgeDetector::relativeSecondDifference(float zc, float za, float zb) const {
  if (orthographicDepth > 0.0f) {
    if (za == 0.0f || zb == 0.0f) return -std::numeric_limits<float>::infinity();
    return (2.0f * zc - za - zb) / orthographicDepth;
  }
  const float wa = za > 0.0f ? 1.0f / za : 0.0f, wb = zb > 0.0f ? 1.0f / zb : 0.0f;
  return zc * (wa + wb) - 2.0f;
}

std::vector<EdgeFlags> EdgeDetector::detect(const std::vector<std::uint8_t>& gbuffer, int width, int height,
                                            const std::vector<float>& luma) const {
  std::vector<EdgeFlags> out(static_cast<size_t>(width) * height);
  auto at = [&](int x, int y) {
    x = std::clamp(x, 0, width - 1);
    y = std::clamp(y, 0, height - 1);
    return static_cast<size_t>(y) * width + x;
  };
  const bool colorEdges = colorThreshold > 0.0f && !luma.empty();
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t c = at(x, y);
      const std::uint8_t* texel = &gbuffer[c * 4];
      const float zc = viewDepth(texel);
      if (zc == 0.0f) continue;  // the background carries no line
      const size_t n[4] = {at(x - 1, y), at(x + 1, y), at(x, y - 1), at(x, y + 1)};
      EdgeFlags& f = out[c];
      const float dx = relativeSecondDifference(zc, viewDepth(&gbuffer[n[0] * 4]), viewDepth(&gbuffer[n[1] * 4]));
      const float dy = relativeSecondDifference(zc, viewDepth(&gbuffer[n[2] * 4]), viewDepth(&gbuffer[n[3] * 4]));
      f.profile = std::min(dx, dy) < -depthThreshold;
      const glm::vec3 normal = decodeNormal(texel[0], texel[1]);
      const std::uint16_t code = LinearDepthPacking::codeFromBytes(texel[2], texel[3]);
      for (size_t i : n) {
        const std::uint8_t* other = &gbuffer[i * 4];
        const std::uint16_t otherCode = LinearDepthPacking::codeFromBytes(other[2], other[3]);
        if (otherCode == 65535 || otherCode < code) continue;
        if (glm::dot(normal, decodeNormal(other[0], other[1])) < normalCos) f.crease = true;
      }
      if (colorEdges)
        for (size_t i : n)
          if (luma[i] - luma[c] > colorThreshold) f.color = true;
    }
  }
  return out;
}

int lineRadius(float width) {
  return std::clamp(static_cast<int>(std::ceil(width * 0.5f - 0.5f)), 0, EdgesEffect::kMaxRadius);
}

std::vector<float> edgeDistances(const std::vector<EdgeFlags>& edges, int width, int height, int radius) {
  std::vector<float> out(static_cast<size_t>(width) * height, static_cast<float>(radius + 1));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float best = static_cast<float>((radius + 1) * (radius + 1));
      for (int j = -radius; j <= radius; ++j)
        for (int i = -radius; i <= radius; ++i) {
          const int sx = std::clamp(x + i, 0, width - 1), sy = std::clamp(y + j, 0, height - 1);
          if (!edges[static_cast<size_t>(sy) * width + sx].any()) continue;
          // Clamped taps repeat the border pixel, which is nearer than the tap: the minimum is unaffected.
          best = std::min(best, static_cast<float>((sx - x) * (sx - x) + (sy - y) * (sy - y)));
        }
      out[static_cast<size_t>(y) * width + x] = std::sqrt(best);
    }
  return out;
}

float lineCoverage(float distance, float width, float strength) {
  return strength * std::clamp(width * 0.5f + 0.5f - distance, 0.0f, 1.0f);
}

glm::vec3 toonShade(const glm::vec3& srgb, int bands) {
  const float y = fxaaLuma(srgb);
  if (y < 1e-4f) return srgb;
  const float n = static_cast<float>(bands);
  const float level = (std::min(std::floor(y * n), n - 1.0f) + 0.5f) / n;
  return glm::min(srgb * (level / y), glm::vec3(1.0f));
}

EffectInfo EdgesEffect::info() {
  EffectInfo info{"edges",
                  "Edges",
                  true,
                  false,
                  {"edges-detect", "edges-h", "edges"},
                  {{"edges-mask", kMaskEncoding, GL_NEAREST, {{"edges-mask", ViewDecoding::Color}}},
                   {"edges-distance", kDistanceEncoding, GL_NEAREST, {}}}};
  info.waitsForFullFrame = true;
  return info;
}

std::vector<ProgramSpec> EdgesEffect::programSpecs() {
  std::vector<ProgramSpec> specs = {detectSpec(false), detectSpec(true)};
  for (int radius = 0; radius <= kMaxRadius; ++radius) specs.push_back(distanceSpec(radius));
  for (int radius = 0; radius <= kMaxRadius; ++radius)
    for (EdgeStyle style : kEdgeStyles) specs.push_back(drawSpec(radius, style));
  return specs;
}

EdgesEffect::EdgesEffect(const EffectResources&) {}

void EdgesEffect::plan(FramePlanner& planner) {
  const EdgesSettings& settings = planner.settings().of<EdgesSettings>();
  if (!settings.enabled && !planner.showsTargetOf(info())) return;
  // What shapes the passes: colour edges (a read of the display colour), the line's reach R (the loops' bound), the
  // style.
  const bool colorEdges = settings.colorThreshold > 0.0f;
  std::vector<TextureInput> detectInputs = {{"u_gbuffer", "gbuffer"}};
  if (colorEdges) detectInputs.push_back({"u_color", "display-color"});
  planner.add(fullscreenPass(
      "edges-detect", detectSpec(colorEdges), std::move(detectInputs), {"edges-mask"},
      [colorEdges](FullscreenDraw& draw, const PassContext& context) {
        const FrameCamera& camera = context.camera();
        const EdgeDetector detector =
            EdgeDetector::of(context.settings().of<EdgesSettings>(), camera.near, camera.far,
                             camera.orthographic ? 2.0f * camera.halfExtent.y : 0.0f);
        draw.set("u_texel", context.texelSize("edges-mask"));
        draw.set("u_near", detector.near);
        draw.set("u_depthScale", detector.depthRange / 65535.0f);
        draw.set("u_inverseOrthographicDepth",
                 detector.orthographicDepth > 0.0f ? 1.0f / detector.orthographicDepth : 0.0f);
        draw.set("u_depthThreshold", detector.depthThreshold);
        draw.set("u_normalCos", detector.normalCos);
        if (colorEdges) draw.set("u_colorThreshold", detector.colorThreshold);
      }));
  if (!settings.enabled) return;  // a debug view of the mask

  // At radius 0 the passes fetch the pixel itself: the compiler drops u_texel.
  const int radius = lineRadius(settings.width);
  planner.add(fullscreenPass("edges-h", distanceSpec(radius), {{"u_mask", "edges-mask"}}, {"edges-distance"},
                             [radius](FullscreenDraw& draw, const PassContext& context) {
                               if (radius > 0) draw.set("u_texel", context.texelSize("edges-distance"));
                             }));

  const EdgeStyle style = settings.style;
  std::vector<TextureInput> drawInputs = {{"u_distance", "edges-distance"}, {"u_color", "display-color"}};
  if (style == EdgeStyle::Hatching) drawInputs.push_back({"u_gbuffer", "gbuffer"});
  planner.add(fullscreenPass(
      "edges", drawSpec(radius, style), std::move(drawInputs), {"display-color"},
      [radius, style](FullscreenDraw& draw, const PassContext& context) {
        const EdgesSettings& edges = context.settings().of<EdgesSettings>();
        if (radius > 0) draw.set("u_texel", context.texelSize("display-color"));
        draw.set("u_halfWidth", edges.width * 0.5f + 0.5f);
        draw.set("u_lineColor", linearToSrgb(edges.color));  // the shader mixes display colours
        draw.set("u_strength", edges.strength);
        draw.set("u_alphaIsOne", context.writesOutput("display-color") ? 1.0f : 0.0f);
        if (style == EdgeStyle::Toon) draw.set("u_bands", static_cast<float>(edges.bands));
        if (style == EdgeStyle::Hatching)
          setHatching(draw.program(), context.camera(), edges.hatchSpacing, edges.bands, draw.unit("u_gbuffer"));
      }));
}

}  // namespace obscura
