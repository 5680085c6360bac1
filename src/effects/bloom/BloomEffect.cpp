#include "effects/bloom/BloomEffect.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "frame/PassContext.h"
#include "gl/PipelineState.h"

namespace obscura {
namespace {

const char* const kStageNames[] = {"prefilter", "down", "tent-x", "up", "composite"};

ProgramSpec spec(int stage) {
  return ProgramSpec{std::string("bloom[") + kStageNames[stage] + "]",
                     "lib/fullscreen.vert",
                     "bloom/bloom.frag",
                     {{"BLOOM_STAGE", std::to_string(stage)}, {"FAR_RAY", "0"}}};
}

// Level k's size: floor(frame / 2^k), at least 1 (TargetSize's halving).
glm::ivec2 levelSize(glm::ivec2 frame, int k) { return glm::max(frame / (1 << k), glm::ivec2(1)); }

}  // namespace

float bloomThresholdScale(const glm::vec3& color, float threshold, float knee) {
  const float m = std::max(color.r, std::max(color.g, color.b));
  if (m <= 0.0f) return 0.0f;
  const float k = knee * threshold;
  const float x = std::max(m - threshold, 0.0f);
  const float kept = x < 2.0f * k ? x * x / (4.0f * k) : x - k;
  return kept / m;
}

float bloomDownsampleWeight(int i, int j) {
  auto a = [](int n) { return (n == 2 || n == 3) ? 0.25f : 0.125f; };
  auto b = [](int n) { return (n == 0 || n == 5) ? 0.0f : 0.25f; };
  return 0.5f * (a(i) * a(j) + b(i) * b(j));
}

float bloomUpsampleWeight(int k, float f) {
  switch (k) {
    case 0: return 0.25f - 0.25f * f;
    case 1: return 0.5f - 0.25f * f;
    case 2: return 0.25f + 0.25f * f;
    case 3: return 0.25f * f;
  }
  return 0.0f;
}

int bloomLevels(glm::ivec2 frame) {
  int levels = 1;
  while (levels < BloomEffect::kMaxLevels && std::min(frame.x, frame.y) >> (levels + 1) >= 2) ++levels;
  return levels;
}

const std::vector<Parameter<BloomSettings>>& BloomSettings::parameters() {
  using S = BloomSettings;
  static const std::vector<Parameter<S>> table = {
      switchParameter<S>("bloom", "bloom on or off (the light above the threshold, blurred to 1/64 of the frame, "
                         "added)", &S::enabled)
          .primary(),
      numberParameter<S>("threshold", 0, 65408, "linear HDR",
                         "the brightness (largest channel) above which light blooms; nothing at or below it does",
                         &S::threshold)
          .primary(),
      numberParameter<S>("knee", 0, 1, "fraction of the threshold",
                         "the soft knee: light blooms gradually over 2 x knee x threshold above the threshold",
                         &S::knee),
      numberParameter<S>("intensity", 0, 16, "", "the fraction of the light above the threshold added as glow",
                         &S::intensity)
          .primary(),
      numberParameter<S>("radius", 0, 1, "",
                         "the glow's width: the weight of the wider levels in each upsample (0: 1/2 only, 1: 1/64 "
                         "only)",
                         &S::radius)
          .primary()};
  return table;
}

EffectInfo BloomEffect::info() {
  return {"bloom",
          "Bloom",
          true,
          false,
          {"bloom", "bloom-bright"},
          {{"bloom-bright", "RGB9E5 (as scene-color): the light above bloom's threshold at 1/4 of the frame (bloom's "
            "level 2), for the lens flare and the glare", GL_NEAREST, {}}}};
}

std::vector<ProgramSpec> BloomEffect::programSpecs() { return {spec(0), spec(1), spec(2), spec(3), spec(4)}; }

BloomEffect::BloomEffect(const EffectResources& resources) : resources_(resources) {
  Stage* stages[] = {&prefilter_, &down_, &tentX_, &up_, &composite_};
  for (int s = 0; s < 5; ++s) {
    Stage& stage = *stages[s];
    stage.program = resources_.build(spec(s));
    stage.source = stage.program.uniform("u_source");
    stage.sourceSize = stage.program.uniform("u_sourceSize");
    if (s == 0) stage.threshold = stage.program.uniform("u_threshold");
    if (s >= 3) stage.level = stage.program.uniform("u_level");
    if (s == 3) stage.radius = stage.program.uniform("u_radius");
    if (s == 4) stage.intensity = stage.program.uniform("u_intensity");
  }
}

void BloomEffect::plan(FramePlanner& planner) {
  using Write = PassDecl::Write;
  const BloomSettings settings = planner.settings().of<BloomSettings>();
  auto bright = [](PassContext& context) {
    return Bright{[&context] { context.bindForWriting("bloom-bright"); }, &context.writtenTexture("bloom-bright")};
  };
  if (!settings.enabled) {
    // The chain's targets go once bloom has been off for as long as the pool keeps an unused target.
    if (++plansOff_ >= 8 && !levels_.empty()) {
      levels_.clear();
      ups_.clear();
      alongX_.clear();
      size_ = glm::ivec2(0);
    }
    // The bright pass alone, which runs only when a later effect reads it.
    PassDecl pass;
    pass.name = "bloom-bright";
    pass.reads = {"scene-color"};
    pass.writes = {{"bloom-bright", TargetSize::quarter(), Write::Depth::None, ""}};
    pass.run = [this, settings, bright](PassContext& context) {
      plansOff_ = 0;
      renderBright(settings, context.texture("scene-color"), context.size("scene-color"), bright(context));
    };
    planner.add(std::move(pass));
    return;
  }
  plansOff_ = 0;
  PassDecl pass;
  pass.name = "bloom";
  pass.reads = {"scene-color"};
  pass.writes = {{"scene-color", TargetSize::full(), Write::Depth::None, ""},
                 {"bloom-bright", TargetSize::quarter(), Write::Depth::None, ""}};
  pass.run = [this, settings, bright](PassContext& context) {
    render(settings, context.texture("scene-color"), context.size("scene-color"),
           [&context] { context.bindForWriting("scene-color"); }, bright(context));
  };
  planner.add(std::move(pass));
}

void BloomEffect::resize(glm::ivec2 size) {
  if (size == size_ && !levels_.empty()) return;
  size_ = size;
  levels_.clear();
  ups_.clear();
  alongX_.clear();
  const int levels = bloomLevels(size);
  for (int k = 1; k <= levels; ++k) {
    const glm::ivec2 s = levelSize(size, k);
    levels_.emplace_back("bloom level " + std::to_string(k), s.x, s.y, GL_NEAREST, gl::RenderTarget::Depth::None,
                         false);
    if (k < levels)
      ups_.emplace_back("bloom up " + std::to_string(k), s.x, s.y, GL_NEAREST, gl::RenderTarget::Depth::None, false);
  }
  // The tent's first half for up k (and the composite, k = 0): level k's width, level k + 1's height.
  for (int k = 0; k < levels; ++k) {
    const glm::ivec2 s(k == 0 ? size.x : levelSize(size, k).x, levelSize(size, k + 1).y);
    alongX_.emplace_back("bloom tent " + std::to_string(k), s.x, s.y, GL_NEAREST, gl::RenderTarget::Depth::None,
                         false);
  }
}

const gl::Texture2D& BloomEffect::level(int k, const Bright& bright) const {
  if (k == 2 && bright.texture) return *bright.texture;
  return levels_[static_cast<size_t>(k - 1)].color();
}

void BloomEffect::downChain(const BloomSettings& settings, const gl::Texture2D& sceneColor, glm::ivec2 size,
                            int last, const Bright& bright) {
  using gl::Program;
  resize(size);
  auto sourceSize = [](const gl::Texture2D& t) { return glm::vec2(t.width(), t.height()); };

  // Prefilter: the thresholded scene colour into level 1.
  levels_[0].bindForDrawing();
  prefilter_.program.use();
  sceneColor.bind(0);
  Program::set(prefilter_.source, 0);
  Program::set(prefilter_.sourceSize, glm::vec2(size));
  const float knee = settings.knee * settings.threshold;
  Program::set(prefilter_.threshold, glm::vec3(settings.threshold, knee, knee > 0.0f ? 0.25f / knee : 0.0f));
  resources_.triangle.draw();

  // Down the chain; level 2 into the bright target where there is one (made even where the chain stops at level 1:
  // frames under 8 pixels).
  down_.program.use();
  Program::set(down_.source, 0);
  for (int k = 2; k <= (bright.texture ? std::max(last, 2) : last); ++k) {
    if (k == 2 && bright.texture) bright.bind();
    else levels_[static_cast<size_t>(k - 1)].bindForDrawing();
    const gl::Texture2D& source = level(k - 1, bright);
    source.bind(0);
    Program::set(down_.sourceSize, sourceSize(source));
    resources_.triangle.draw();
  }
}

void BloomEffect::renderBright(const BloomSettings& settings, const gl::Texture2D& sceneColor, glm::ivec2 size,
                               const Bright& bright) {
  downChain(settings, sceneColor, size, 2, bright);
  gl::restoreBaselineState();
}

void BloomEffect::render(const BloomSettings& settings, const gl::Texture2D& sceneColor, glm::ivec2 size,
                         const std::function<void()>& bindOutput, const Bright& bright) {
  using gl::Program;
  resize(size);
  const int levels = static_cast<int>(levels_.size());
  auto sourceSize = [](const gl::Texture2D& t) { return glm::vec2(t.width(), t.height()); };
  downChain(settings, sceneColor, size, levels, bright);

  // The tent's first half: `coarser` filtered along x into alongX_[k] (level k's width, its own height).
  auto tentAlongX = [&](int k, const gl::Texture2D& coarser) {
    alongX_[static_cast<size_t>(k)].bindForDrawing();
    tentX_.program.use();
    coarser.bind(0);
    Program::set(tentX_.source, 0);
    Program::set(tentX_.sourceSize, sourceSize(coarser));
    resources_.triangle.draw();
    return &alongX_[static_cast<size_t>(k)].color();
  };

  // Up again: up_k = mix(level_k, tent(up_k+1), radius), from the coarsest level.
  for (int k = levels - 1; k >= 1; --k) {
    const gl::Texture2D* half =
        tentAlongX(k, k + 1 == levels ? level(k + 1, bright) : ups_[static_cast<size_t>(k)].color());
    ups_[static_cast<size_t>(k - 1)].bindForDrawing();
    up_.program.use();
    half->bind(0);
    level(k, bright).bind(1);
    Program::set(up_.source, 0);
    Program::set(up_.level, 1);
    Program::set(up_.radius, settings.radius);
    Program::set(up_.sourceSize, sourceSize(*half));
    resources_.triangle.draw();
  }

  // The frame with its glow.
  const gl::Texture2D* half = tentAlongX(0, levels == 1 ? levels_[0].color() : ups_[0].color());
  bindOutput();
  composite_.program.use();
  half->bind(0);
  sceneColor.bind(1);
  Program::set(composite_.source, 0);
  Program::set(composite_.level, 1);
  Program::set(composite_.sourceSize, sourceSize(*half));
  Program::set(composite_.intensity, settings.intensity);
  resources_.triangle.draw();
  gl::restoreBaselineState();
}

}  // namespace obscura
