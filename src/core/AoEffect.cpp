#include "core/AoEffect.h"

#include "core/PassContext.h"

namespace obscura {
namespace {

constexpr const char* kAoEncoding = "R: ambient visibility (1 open, 0 occluded); GB: the pixel's 16-bit depth code";

}  // namespace

EffectInfo AoEffect::info() {
  return {"ao",
          "Ambient obscurance",
          true,
          false,
          {"hierarchy", "sao", "blur-h", "blur-v", "upsample"},
          {{"depth-hierarchy",
            "SAO's depth levels 1 .. 5 (one picked pixel's depth per 2^m block, and where it lies in the block); kept "
            "by the effect as an atlas or a mip chain, not pooled",
            GL_NEAREST,
            {}},
           {"ao-raw", kAoEncoding, GL_NEAREST, {{"ao-raw", ViewDecoding::Grey}}},
           {"ao-blur-h", kAoEncoding, GL_NEAREST, {{"ao-blur-h", ViewDecoding::Grey}}},
           {"ao", kAoEncoding, GL_NEAREST, {{"ao", ViewDecoding::Grey}}}}};
}

std::vector<ProgramSpec> AoEffect::programSpecs() {
  std::vector<ProgramSpec> specs = DepthHierarchyPass::programSpecs();
  for (const auto& list : {SaoPass::programSpecs(), BilateralBlurPass::programSpecs(), AoUpsamplePass::programSpecs()})
    specs.insert(specs.end(), list.begin(), list.end());
  return specs;
}

AoEffect::AoEffect(const EffectResources& resources)
    : hierarchy_(resources.triangle, resources.caps,
                 DepthHierarchyPass::storageFor(resources.caps, resources.options.hierarchyStorage),
                 resources.build(DepthHierarchyPass::programSpecs().front())),
      sao_(resources),
      blur_(resources),
      upsample_(resources) {}

void AoEffect::plan(FramePlanner& planner) {
  const AoSettings& settings = planner.settings().ao();
  if (!settings.enabled && !planner.showsTargetOf(info())) return;
  // Half resolution: AO at floor(size / 2), AO pixel p standing for G-buffer pixel 2p.
  const bool half = settings.halfResolution;
  const TargetSize aoSize = half ? TargetSize::half() : TargetSize::full();
  const int aoScale = half ? 2 : 1;

  if (settings.depthHierarchy) {
    PassDecl hierarchy;
    hierarchy.name = "hierarchy";
    hierarchy.reads = {"gbuffer"};
    hierarchy.writes = {{"depth-hierarchy", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
    hierarchy.run = [this](PassContext& context) {
      const glm::ivec2 size = context.size("gbuffer");
      hierarchy_.resize(size.x, size.y);
      hierarchy_.render(context.texture("gbuffer"));
    };
    planner.add(std::move(hierarchy));
    planner.markExternal("depth-hierarchy");
  }

  PassDecl sao;
  sao.name = "sao";
  sao.reads = {"gbuffer"};
  if (settings.depthHierarchy) sao.reads.push_back("depth-hierarchy");
  sao.writes = {{"ao-raw", aoSize, PassDecl::Write::Depth::None, ""}};
  sao.run = [this, settings, aoScale](PassContext& context) {
    context.bindForWriting("ao-raw");
    sao_.render(context.texture("gbuffer"), settings.depthHierarchy ? &hierarchy_ : nullptr, context.camera(),
                settings, aoScale, context.size("ao-raw"));
  };
  planner.add(std::move(sao));

  if (settings.blur && settings.blurRadius > 0) {
    for (const auto direction : {BilateralBlurPass::Direction::Horizontal, BilateralBlurPass::Direction::Vertical}) {
      const bool horizontal = direction == BilateralBlurPass::Direction::Horizontal;
      const char* input = horizontal ? "ao-raw" : "ao-blur-h";
      const char* output = horizontal ? "ao-blur-h" : "ao";
      PassDecl blur;
      blur.name = horizontal ? "blur-h" : "blur-v";
      blur.reads = {input, "gbuffer"};
      blur.writes = {{output, aoSize, PassDecl::Write::Depth::None, ""}};
      blur.run = [this, settings, aoScale, direction, input, output](PassContext& context) {
        context.bindForWriting(output);
        blur_.render(direction, context.texture(input), context.texture("gbuffer"), context.camera(), settings,
                     aoScale);
      };
      planner.add(std::move(blur));
    }
  } else {
    planner.alias("ao", "ao-raw");
  }

  if (half) {
    PassDecl upsample;
    upsample.name = "upsample";
    upsample.reads = {"ao", "gbuffer"};
    upsample.writes = {{"ao", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
    upsample.run = [this, settings](PassContext& context) {
      // Reads the half-size AO, writes the full-size one: two versions of "ao", two targets.
      const gl::Texture2D& halfAo = context.texture("ao");
      context.bindForWriting("ao");
      upsample_.render(halfAo, context.texture("gbuffer"), context.camera(), settings);
    };
    planner.add(std::move(upsample));
  }
}

}  // namespace obscura
