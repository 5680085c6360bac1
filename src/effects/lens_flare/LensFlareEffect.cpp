#include "effects/lens_flare/LensFlareEffect.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "encoding/ToneMapping.h"
#include "frame/FullscreenPass.h"
#include "frame/PassContext.h"
#include "scene/ImageIo.h"

namespace obscura {
namespace {

constexpr int kMaxGhosts = 8;  // MAX_GHOSTS in lens_flare.frag

ProgramSpec spec(bool dirt) {
  return ProgramSpec{std::string("lens-flare[") + (dirt ? "dirt" : "clean") + "]",
                     "lib/fullscreen.vert",
                     "lens_flare/lens_flare.frag",
                     {{"LENS_DIRT", dirt ? "1" : "0"}, {"FAR_RAY", "0"}}};
}

// A dirt image as the shader reads it: its sRGB bytes decoded to linear bytes (it multiplies light), rows bottom to top
// (the texture's first row is uv y = 0, the bottom of the frame).
std::vector<std::uint8_t> linearBytes(const Image& image) {
  std::vector<std::uint8_t> out(image.rgba.size());
  const size_t row = static_cast<size_t>(image.width) * 4;
  for (size_t i = 0; i < image.rgba.size(); ++i) {
    const size_t flipped = (static_cast<size_t>(image.height) - 1 - i / row) * row + i % row;
    out[flipped] = (i % 4 == 3) ? 255
                                : static_cast<std::uint8_t>(std::lround(srgbToLinear(image.rgba[i] / 255.0f) * 255.0f));
  }
  return out;
}

std::shared_ptr<const Image> readDirt(const std::string& name) {
  if (name == "none" || name == "builtin") return nullptr;
  return std::make_shared<const Image>(readPng(name));
}

}  // namespace

const std::vector<Parameter<LensFlareSettings>>& LensFlareSettings::parameters() {
  using S = LensFlareSettings;
  static const std::vector<Parameter<S>> table = [] {
    Parameter<S> dirtParameter = textParameter<S>("dirt", "none | builtin | a PNG file",
                                         "lens dirt the flare shines through: none, the built-in smudges, or an "
                                         "image (sRGB, stretched over the frame)",
                                         &S::dirt, {"none", "builtin"});
    // A file is read now, so a bad one is refused when it is set and the dirt in use stays.
    dirtParameter.set = [](S& s, const std::string& v) {
      if (v.empty()) throw InputError("dirt: expected none, builtin or a PNG file, got nothing");
      std::shared_ptr<const Image> image = readDirt(v);
      s.dirt = v;
      s.dirtImage = std::move(image);
    };
    return std::vector<Parameter<S>>{
        switchParameter<S>("lens-flare", "lens flare on or off (ghosts and a halo of the light above "
                           "bloom.threshold, mirrored through the centre; fed from bloom's bright pass)",
                           &S::enabled)
            .primary(),
        numberParameter<S>("intensity", 0, 16, "", "the flare's light per unit of the bright light", &S::intensity)
            .primary(),
        integerParameter<S>("ghosts", 0, kMaxGhosts, "", "", "ghosts along the line through the centre",
                            &S::ghosts)
            .primary(),
        numberParameter<S>("dispersal", 0, 2, "", "the spacing of the ghosts along the line through the centre",
                           &S::dispersal)
            .primary(),
        numberParameter<S>("halo-width", 0, 2, "frame heights", "the halo's radius (0: no halo offset)",
                           &S::haloWidth),
        numberParameter<S>("distortion", 0, 0.2, "frame heights",
                           "chromatic dispersion: how far apart red and blue are sampled", &S::distortion),
        std::move(dirtParameter)};
  }();
  return table;
}

glm::vec2 lensFlareGhostSample(glm::vec2 uv, int ghost, float dispersal) {
  const glm::vec2 t = 1.0f - uv;
  return glm::fract(t + (0.5f - t) * dispersal * static_cast<float>(ghost));
}

glm::vec2 lensFlareGhostPosition(glm::vec2 source, int ghost, float dispersal) {
  // source = t (1 - i d) + i d / 2 with t = 1 - uv.
  const float id = dispersal * static_cast<float>(ghost);
  return 1.0f - (source - 0.5f * id) / (1.0f - id);
}

float lensFlareFalloff(glm::vec2 sample, float power) {
  return std::pow(std::max(1.0f - glm::length(0.5f - sample) * 1.4142135f, 0.0f), power);
}

glm::vec3 lensFlareAt(glm::vec2 uv, const std::vector<glm::vec3>& bright, glm::ivec2 size, float aspect,
                      const LensFlareSettings& s) {
  auto at = [&](glm::vec2 p) {
    const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor(p * glm::vec2(size))), glm::ivec2(0), size - 1);
    return bright[static_cast<size_t>(texel.y) * size.x + texel.x];
  };
  const glm::vec2 t = 1.0f - uv;
  const glm::vec2 ghostStep = (0.5f - t) * s.dispersal;
  const glm::vec2 scale(aspect, 1.0f);
  const glm::vec2 along = ghostStep * scale;
  const float lengthAlong = glm::length(along);
  const glm::vec2 direction = lengthAlong > 1e-6f ? along / (lengthAlong * scale) : glm::vec2(0.0f);
  auto dispersed = [&](glm::vec2 p) {
    return glm::vec3(at(p - direction * s.distortion).r, at(p).g, at(p + direction * s.distortion).b);
  };
  glm::vec3 flare(0.0f);
  for (int i = 0; i < s.ghosts; ++i) {
    const glm::vec2 source = glm::fract(t + ghostStep * static_cast<float>(i));
    flare += dispersed(source) * lensFlareFalloff(source, 10.0f);
  }
  const glm::vec2 halo = glm::fract(t + direction * s.haloWidth);
  flare += dispersed(halo) * lensFlareFalloff(halo, 5.0f);
  return flare * s.intensity;
}

Image builtinLensDirt(int side) {
  // A small linear congruential generator (Numerical Recipes' constants): the same dirt on every platform.
  std::uint32_t state = 20130914u;
  auto random = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / 16777216.0f;
  };
  std::vector<float> dirt(static_cast<size_t>(side) * side, 0.18f);
  auto spot = [&](float cx, float cy, float radius, float amount) {
    const int r = static_cast<int>(std::ceil(2.0f * radius));
    for (int y = std::max(0, static_cast<int>(cy) - r); y < std::min(side, static_cast<int>(cy) + r + 1); ++y)
      for (int x = std::max(0, static_cast<int>(cx) - r); x < std::min(side, static_cast<int>(cx) + r + 1); ++x) {
        const float dx = static_cast<float>(x) + 0.5f - cx, dy = static_cast<float>(y) + 0.5f - cy;
        dirt[static_cast<size_t>(y) * side + x] += amount * std::exp(-(dx * dx + dy * dy) / (radius * radius));
      }
  };
  const float s = static_cast<float>(side);
  for (int i = 0; i < 40; ++i) spot(random() * s, random() * s, s * (0.02f + 0.08f * random()), 0.1f + 0.3f * random());
  for (int i = 0; i < 300; ++i) spot(random() * s, random() * s, s * (0.002f + 0.006f * random()), 0.3f + random());
  Image image;
  image.width = image.height = side;
  image.rgba.resize(static_cast<size_t>(side) * side * 4);
  for (size_t i = 0; i < dirt.size(); ++i) {
    const auto v = static_cast<std::uint8_t>(std::lround(std::min(linearToSrgb(dirt[i]), 1.0f) * 255.0f));
    image.rgba[4 * i] = image.rgba[4 * i + 1] = image.rgba[4 * i + 2] = v;
    image.rgba[4 * i + 3] = 255;
  }
  return image;
}

EffectInfo LensFlareEffect::info() {
  EffectInfo info{"lens-flare",
                  "Lens flare",
                  true,
                  false,
                  {"lens-flare"},
                  {{"lens-light",
                    "RGB9E5 (as scene-color): the light the lens adds (the flare, the glare's streaks) at 1/4 of "
                    "the frame, added by the tone mapping",
                    GL_NEAREST,
                    {}}}};
  info.waitsForFullFrame = true;
  return info;
}

std::vector<ProgramSpec> LensFlareEffect::programSpecs() { return {spec(false), spec(true)}; }

const gl::Texture2D* LensFlareEffect::dirtTexture(const LensFlareSettings& settings) {
  if (settings.dirt == "none") return nullptr;
  const bool builtin = settings.dirt == "builtin";
  if (settings.dirt != dirtName_ || (!builtin && settings.dirtImage && settings.dirtImage != dirtImage_)) {
    std::shared_ptr<const Image> image = builtin ? std::make_shared<const Image>(builtinLensDirt())
                                                 : settings.dirtImage ? settings.dirtImage : readDirt(settings.dirt);
    dirt_ = gl::Texture2D(image->width, image->height, GL_LINEAR, linearBytes(*image).data());
    dirtName_ = settings.dirt;
    dirtImage_ = builtin ? nullptr : image;
  }
  return &dirt_;
}

// The dirt image is read here, before the plan (which is cached, and neither loads nor frees).
void LensFlareEffect::prepare(const FrameSettings& frameSettings) {
  const LensFlareSettings& settings = frameSettings.of<LensFlareSettings>();
  if (settings.enabled) dirtTexture(settings);  // reads a file where one is named and not read yet
}

void LensFlareEffect::plan(FramePlanner& planner) {
  const LensFlareSettings& planned = planner.settings().of<LensFlareSettings>();
  if (!planned.enabled) return;
  const bool withDirt = planned.dirt != "none";
  planner.add(fullscreenPass("lens-flare", spec(withDirt), {{"u_bright", "bloom-bright"}},
                             {"lens-light", TargetSize::quarter()},
                             [this, withDirt](FullscreenDraw& draw, const PassContext& context) {
                               const LensFlareSettings& settings = context.settings().of<LensFlareSettings>();
                               const glm::vec2 frame(context.camera().width, context.camera().height);
                               draw.set("u_brightSize", glm::vec2(context.size("bloom-bright")));
                               draw.set("u_ghosts", static_cast<float>(settings.ghosts));
                               draw.set("u_dispersal", settings.dispersal);
                               draw.set("u_haloWidth", settings.haloWidth);
                               draw.set("u_aspect", glm::vec2(frame.x / frame.y, 1.0f));
                               draw.set("u_distortion", settings.distortion);
                               draw.set("u_intensity", settings.intensity);
                               if (withDirt) draw.texture("u_dirt", dirt_);
                             }));
}

}  // namespace obscura
