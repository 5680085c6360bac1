#include "effects/bloom/BloomEffect.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "frame/PassContext.h"


namespace obscura {
namespace {

const char* const kStageNames[] = {"prefilter-blocks", "prefilter", "down", "tent-x", "up", "composite"};
constexpr int kBlocks = 0, kPrefilter = 1, kDown = 2, kTentX = 3, kUp = 4, kComposite = 5;

ProgramSpec spec(int stage) {
  return ProgramSpec{std::string("bloom[") + kStageNames[stage] + "]",
                     "lib/fullscreen.vert",
                     "bloom/bloom.frag",
                     {{"BLOOM_STAGE", std::to_string(stage)}, {"FAR_RAY", "0"}}};
}

// The composite's program as it runs: a stage head's, here with no stage fused (its colour HDR-encoded).
ProgramSpec compositeSpec() { return fusedProgram(spec(kComposite), {}, ColorSpace::Hdr); }

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

namespace {

const char* kLevelEncoding = "linear HDR colour, RGB9E5 as scene-color (lib/hdr.glsl)";

// Level 2 is also the frame's `bloom-bright`, the light above the threshold at 1/4 of the frame that the lens flare and
// the glare read (its passes run without the rest of the chain when they read it with bloom off).
std::string level(int k) { return k == 2 ? "bloom-bright" : "bloom-" + std::to_string(k); }
std::string up(int k) { return "bloom-up-" + std::to_string(k); }
std::string tent(int k) { return "bloom-tent-" + std::to_string(k); }
// Level k's size (floor(frame / 2^k), at least 1), and the tent's first half towards up k (up 0: the frame): level
// k's width, level k + 1's height.
TargetSize levelSize(int k) { return TargetSize::scaled(k, k); }
TargetSize tentSize(int k) { return TargetSize::scaled(k, k + 1); }
// The prefilter's 2 x 2 blocks (bloom.frag, stage 0): the even grid's floor(w / 2) + 2 columns (blocks -1 ..
// floor(w / 2)) beside the odd grid's floor(w / 2) + 1 (blocks 0 .. floor(w / 2)), floor(h / 2) + 2 rows.
const std::string kBlocksTarget = "bloom-blocks";
TargetSize blocksSize() { return TargetSize::scaled(1, 1).widened(2, 3, 2); }
float evenColumns(glm::ivec2 level1) { return static_cast<float>(level1.x + 2); }

// The chain's draws, into the framebuffer bound, from the textures given: the passes run them on pooled targets,
// BloomEffect::render on targets of its own.
// The prefilter in two draws: the thresholded frame's 2 x 2 blocks into the bound target (blocksSize), then, from
// them, level 1 (of size `level1`).
void prefilterBlocks(const EffectResources& r, const gl::Texture2D& scene, glm::ivec2 level1,
                     const BloomSettings& settings) {
  FullscreenDraw draw(r.program(spec(kBlocks)), r.triangle);
  draw.texture("u_source", scene);
  draw.set("u_sourceSize", glm::vec2(scene.width(), scene.height()));
  draw.set("u_evenColumns", evenColumns(level1));
  const float knee = settings.knee * settings.threshold;
  draw.set("u_threshold", glm::vec3(settings.threshold, knee, knee > 0.0f ? 0.25f / knee : 0.0f));
  draw.draw();
}
void prefilter(const EffectResources& r, const gl::Texture2D& blocks, glm::ivec2 level1) {
  FullscreenDraw draw(r.program(spec(kPrefilter)), r.triangle);
  draw.texture("u_source", blocks).set("u_sourceSize", glm::vec2(blocks.width(), blocks.height()));
  draw.set("u_evenColumns", evenColumns(level1));
  draw.draw();
}
void down(const EffectResources& r, const gl::Texture2D& finer) {
  FullscreenDraw draw(r.program(spec(kDown)), r.triangle);
  draw.texture("u_source", finer).set("u_sourceSize", glm::vec2(finer.width(), finer.height()));
  draw.draw();
}
void tentAlongX(const EffectResources& r, const gl::Texture2D& coarser) {
  FullscreenDraw draw(r.program(spec(kTentX)), r.triangle);
  draw.texture("u_source", coarser).set("u_sourceSize", glm::vec2(coarser.width(), coarser.height()));
  draw.draw();
}
// up k = mix(level k, tent(up k+1), radius) (stage 4), or the frame plus intensity x tent(up 1) (stage 5).
void upOrComposite(const EffectResources& r, bool composite, const gl::Texture2D& half, const gl::Texture2D& level,
                   const BloomSettings& settings) {
  FullscreenDraw draw(r.program(composite ? compositeSpec() : spec(kUp)), r.triangle);
  draw.texture("u_source", half).texture("u_level", level);
  draw.set("u_sourceSize", glm::vec2(half.width(), half.height()));
  if (composite) draw.set("u_intensity", settings.intensity);
  else draw.set("u_radius", settings.radius);
  draw.draw();
}

}  // namespace

EffectInfo BloomEffect::info() {
  EffectInfo info{"bloom", "Bloom", true, false, {"bloom-prefilter-blocks", "bloom-prefilter"}, {}};
  for (int k = 2; k <= kMaxLevels; ++k) info.passes.push_back("bloom-down-" + std::to_string(k));
  for (int k = kMaxLevels - 1; k >= 1; --k) {
    info.passes.push_back(tent(k));
    info.passes.push_back(up(k));
  }
  info.passes.push_back(tent(0));
  info.passes.push_back("bloom");
  info.targets.push_back({kBlocksTarget,
                          std::string("the thresholded frame's 2 x 2 blocks on the even grid beside those on the odd "
                                      "grid (the prefilter's first half): ") + kLevelEncoding,
                          GL_NEAREST, {}});
  for (int k = 1; k <= kMaxLevels; ++k) {
    info.targets.push_back({level(k),
                            k == 2 ? std::string("level 2 (1/4): the light above bloom's threshold, for the lens flare "
                                                 "and the glare too: ") + kLevelEncoding
                                   : std::string("level ") + std::to_string(k) + " (1/" + std::to_string(1 << k) +
                                         "): " + kLevelEncoding,
                            GL_NEAREST, {}});
    if (k < kMaxLevels)
      info.targets.push_back({up(k), std::string("up ") + std::to_string(k) + ", level k and the tent of up k + 1 " +
                                         "mixed by the radius: " + kLevelEncoding, GL_NEAREST, {}});
  }
  for (int k = 0; k < kMaxLevels; ++k)
    info.targets.push_back({tent(k), std::string("the tent along x towards up ") + std::to_string(k) +
                                         " (level k's width, level k + 1's height): " + kLevelEncoding,
                            GL_NEAREST, {}});
  info.waitsForFullFrame = true;
  return info;
}

std::vector<ProgramSpec> BloomEffect::programSpecs() {
  return {spec(kBlocks), spec(kPrefilter), spec(kDown), spec(kTentX), spec(kUp), compositeSpec()};
}

std::vector<StageHeadSpec> BloomEffect::stageHeads() {
  return {{spec(kComposite), ColorSpace::Hdr, kCompositeUniformVectors}};
}

BloomEffect::BloomEffect(const EffectResources& resources) : resources_(resources) {}

void BloomEffect::plan(FramePlanner& planner) {
  // Off, the prefilter and the first downsample still run when a later effect reads `bloom-bright` (level 2).
  const bool enabled = planner.settings().of<BloomSettings>().enabled;
  using Write = PassDecl::Write;
  const FrameCamera& camera = planner.frame().camera;
  const int levels = enabled ? bloomLevels({camera.width, camera.height}) : 2;
  auto bloom = [](const PassContext& context) -> const BloomSettings& {
    return context.settings().of<BloomSettings>();
  };
  auto add = [&](const std::string& name, std::vector<std::string> reads, const std::string& target, TargetSize size,
                 std::function<void(PassContext&)> run, std::vector<std::string> programs) {
    PassDecl pass;
    pass.name = name;
    pass.reads = std::move(reads);
    pass.writes = {{target, size, Write::Depth::None, ""}};
    pass.programs = std::move(programs);
    pass.run = [target, run = std::move(run)](PassContext& context) {
      context.bindForWriting(target);
      run(context);
    };
    planner.add(std::move(pass));
  };

  // The thresholded frame into level 1 (its 2 x 2 blocks, then the 13 taps from them), then down the chain.
  add("bloom-prefilter-blocks", {"scene-color"}, kBlocksTarget, blocksSize(),
      [this, bloom](PassContext& context) {
        prefilterBlocks(resources_, context.texture("scene-color"), levelSize(1).of(context.size("scene-color")),
                        bloom(context));
      },
      {spec(kBlocks).name});
  add("bloom-prefilter", {kBlocksTarget}, level(1), levelSize(1),
      [this](PassContext& context) {
        prefilter(resources_, context.texture(kBlocksTarget), context.size(level(1)));
      },
      {spec(kPrefilter).name});
  // Level 2 even where the chain stops at level 1 (frames under 8 pixels): it is `bloom-bright`.
  for (int k = 2; k <= std::max(levels, 2); ++k)
    add("bloom-down-" + std::to_string(k), {level(k - 1)}, level(k), levelSize(k),
        [this, finer = level(k - 1)](PassContext& context) { down(resources_, context.texture(finer)); },
        {spec(kDown).name});
  if (!enabled) return;
  // Up again from the coarsest level: each up k mixes level k with the tent of the coarser up (level L itself at
  // the bottom), the tent taken in two passes (along x, then along y in the up's own draw).
  for (int k = levels - 1; k >= 0; --k) {
    const std::string coarser = k + 1 == levels ? level(levels) : up(k + 1);
    add(tent(k), {coarser}, tent(k), tentSize(k),
        [this, coarser](PassContext& context) { tentAlongX(resources_, context.texture(coarser)); },
        {spec(kTentX).name});
    if (k == 0) break;
    add(up(k), {tent(k), level(k)}, up(k), levelSize(k),
        [this, bloom, k](PassContext& context) {
          upOrComposite(resources_, false, context.texture(tent(k)), context.texture(level(k)), bloom(context));
        },
        {spec(kUp).name});
  }
  // The frame with its glow, and the stages fused after it (the tone curve, ...).
  planner.add(fullscreenStageHead(resources_, "bloom", spec(kComposite),
                                  {{"u_source", tent(0)}, {"u_level", "scene-color"}}, {"scene-color"},
                                  ColorSpace::Hdr, kCompositeUniformVectors,
                                  [bloom](FullscreenDraw& draw, const PassContext& context) {
                                    draw.set("u_sourceSize", glm::vec2(context.size(tent(0))));
                                    draw.set("u_intensity", bloom(context).intensity);
                                  }));
}

void BloomEffect::render(const BloomSettings& settings, const gl::Texture2D& sceneColor, glm::ivec2 size,
                         const std::function<void()>& bindOutput) const {
  const int levels = bloomLevels(size);
  auto target = [&](const std::string& name, TargetSize s) {
    const glm::ivec2 pixels = s.of(size);
    return gl::RenderTarget("bloom " + name, pixels.x, pixels.y, GL_NEAREST, gl::RenderTarget::Depth::None, false);
  };
  std::vector<gl::RenderTarget> levelTargets, ups(static_cast<size_t>(levels));
  const glm::ivec2 level1 = levelSize(1).of(size);
  const gl::RenderTarget blocks = target(kBlocksTarget, blocksSize());
  blocks.bindForDrawing();
  prefilterBlocks(resources_, sceneColor, level1, settings);
  for (int k = 1; k <= levels; ++k) {
    levelTargets.push_back(target(level(k), levelSize(k)));
    levelTargets.back().bindForDrawing();
    if (k == 1) prefilter(resources_, blocks.color(), level1);
    else down(resources_, levelTargets[static_cast<size_t>(k - 2)].color());
  }
  for (int k = levels - 1; k >= 0; --k) {
    const gl::Texture2D& coarser =
        k + 1 == levels ? levelTargets.back().color() : ups[static_cast<size_t>(k + 1)].color();
    const gl::RenderTarget half = target(tent(k), tentSize(k));
    half.bindForDrawing();
    tentAlongX(resources_, coarser);
    if (k == 0) {
      bindOutput();
      upOrComposite(resources_, true, half.color(), sceneColor, settings);
    } else {
      ups[static_cast<size_t>(k)] = target(up(k), levelSize(k));
      ups[static_cast<size_t>(k)].bindForDrawing();
      upOrComposite(resources_, false, half.color(), levelTargets[static_cast<size_t>(k - 1)].color(), settings);
    }
  }
}

}  // namespace obscura
