#include "effects/ao/AoEffect.h"

#include "effects/ao/AoTemporal.h"
#include "frame/GBufferSettings.h"
#include "frame/PassContext.h"

namespace obscura {
namespace {

constexpr const char* kAoEncoding = "R: ambient visibility (1 open, 0 occluded); GB: the pixel's 16-bit depth code";
// What the estimators, the blur and the upsample write where nothing was drawn: open, the background's depth code
// 65535, A 1. Their passes draw only over the scene's bounds on screen (PassContext::limitToScene) and clear the rest
// to it: the same image, and on SwiftShader at 1280x720 (2CylinderEngine, the page's default view) GTAO 106 -> 55 ms
// and each blur 26 -> 14 (docs/benchmarks.md, "The scene's bounds").
constexpr glm::vec4 kOpenSky(1.0f);

}  // namespace

EffectInfo AoEffect::info() {
  EffectInfo info{
      "ao",
      "Ambient obscurance",
      true,
      false,
      {"peel", "hierarchy", "sao", "ao-temporal", "blur-h", "blur-v", "upsample"},
      {{"depth-hierarchy",
        "SAO's depth levels 1 .. 5 (one picked pixel's depth per 2^m block, and where it lies in the block); kept "
        "by the effect as an atlas or a mip chain, not pooled",
        GL_NEAREST,
        {}},
       {"second-layer",
        "BA: the second depth layer's 16-bit linear depth (ao.layers 2: the nearest surface at least the layer "
        "separation behind the G-buffer's; 65535: none)",
        GL_NEAREST,
        {{"second-layer", ViewDecoding::Depth}}},
       {"ao-raw", kAoEncoding, GL_NEAREST, {{"ao-raw", ViewDecoding::Grey}}},
       {"ao-temporal",
        std::string(kAoEncoding) + "; A: the frames its running mean holds (effects/ao/AoTemporal.h)",
        GL_NEAREST,
        {{"ao-temporal", ViewDecoding::Grey}}},
       {"ao-blur-h", kAoEncoding, GL_NEAREST, {{"ao-blur-h", ViewDecoding::Grey}}},
       {"ao", kAoEncoding, GL_NEAREST, {{"ao", ViewDecoding::Grey}}}}};
  info.waitsForFullFrame = true;
  return info;
}

std::vector<ProgramSpec> AoEffect::programSpecs() {
  std::vector<ProgramSpec> specs = DepthHierarchyPass::programSpecs();
  for (const auto& list : {DepthPeelPass::programSpecs(), SaoPass::programSpecs(), AoTemporalPass::programSpecs(),
                           BilateralBlurPass::programSpecs(),
                           AoUpsamplePass::programSpecs()})
    specs.insert(specs.end(), list.begin(), list.end());
  return specs;
}

AoEffect::AoEffect(const EffectResources& resources)
    : hierarchy_(resources.triangle, resources.caps,
                 DepthHierarchyPass::storageFor(resources.caps, resources.options.hierarchyStorage), resources),
      peel_(resources),
      sao_(resources),
      temporal_(resources),
      blur_(resources),
      upsample_(resources) {}

void AoEffect::plan(FramePlanner& planner) {
  const AoSettings& settings = planner.settings().of<AoSettings>();
  if (!settings.enabled && !planner.showsTargetOf(info())) return;
  // What shapes the passes: the resolution, the hierarchy, the temporal accumulation and the blur. Everything else
  // (the estimator, its samples, the radius, ...) each pass reads from this frame's settings.
  // Half resolution: AO at floor(size / 2), AO pixel p standing for G-buffer pixel 2p.
  const bool half = settings.halfResolution;
  const TargetSize aoSize = half ? TargetSize::half() : TargetSize::full();
  const int aoScale = half ? 2 : 1;
  auto ao = [](const PassContext& context) -> const AoSettings& { return context.settings().of<AoSettings>(); };

  const bool depthHierarchy = settings.usesDepthHierarchy();
  // ao.layers 2: the second depth layer, for an estimator that reads it (or its view).
  const bool twoLayers = settings.layersRead() == 2 || planner.viewTarget() == "second-layer";
  if (twoLayers) {
    PassDecl peel;
    peel.name = "peel";
    peel.reads = {"gbuffer"};
    peel.writes = {{"second-layer", TargetSize::full(), PassDecl::Write::Depth::Own, ""}};
    peel.run = [this, ao](PassContext& context) {
      context.bindForWriting("second-layer");
      peel_.render(context, context.texture("gbuffer"), ao(context));
    };
    planner.add(std::move(peel));
  }
  if (depthHierarchy) {
    PassDecl hierarchy;
    hierarchy.name = "hierarchy";
    hierarchy.reads = {"gbuffer"};
    if (twoLayers) hierarchy.reads.push_back("second-layer");
    hierarchy.writes = {{"depth-hierarchy", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
    hierarchy.run = [this, twoLayers](PassContext& context) {
      const glm::ivec2 size = context.size("gbuffer");
      hierarchy_.resize(size.x, size.y);
      hierarchy_.render(context.texture("gbuffer"), twoLayers ? &context.texture("second-layer") : nullptr);
    };
    planner.add(std::move(hierarchy));
    planner.markExternal("depth-hierarchy");
  }

  PassDecl sao;
  sao.name = "sao";
  sao.reads = {"gbuffer"};
  if (depthHierarchy) sao.reads.push_back("depth-hierarchy");
  if (twoLayers) sao.reads.push_back("second-layer");
  sao.writes = {{"ao-raw", aoSize, PassDecl::Write::Depth::None, ""}};
  // With ao.temporal, each frame's taps turn to new directions and distances (AoTemporal::frameOffset).
  const bool temporal = settings.temporal || planner.viewTarget() == "ao-temporal";
  const bool normalsFromDepth = planner.settings().of<GBufferSettings>().normals == GBufferNormals::Reconstructed;
  sao.run = [this, ao, depthHierarchy, aoScale, temporal, twoLayers, normalsFromDepth](PassContext& context) {
    context.bindForWriting("ao-raw");
    context.limitToScene("ao-raw", kOpenSky);
    // (With the atlas, the estimator reads both layers from the hierarchy's texels and not this target.)
    const gl::Texture2D* secondLayer = twoLayers ? &context.texture("second-layer") : nullptr;
    sao_.render(context.texture("gbuffer"), depthHierarchy ? &hierarchy_ : nullptr, secondLayer, context.camera(),
                ao(context), normalsFromDepth, aoScale, context.size("ao-raw"),
                temporal ? AoTemporal::frameOffset(context.frame().index) : glm::vec2(0.0f));
  };
  planner.add(std::move(sao));

  // The raw AO is accumulated before the blur: the blur then averages converged values. After the blur (the
  // blurred AO accumulated, its history rectified against the blurred frame) was as accurate on the still room and
  // trailed more behind a moving object (docs/temporal-effects.md, "Temporal AO").
  const char* unblurred = "ao-raw";
  if (temporal) {
    PassDecl accumulate;
    accumulate.name = "ao-temporal";
    accumulate.reads = {"ao-raw", "velocity", "gbuffer"};
    accumulate.writes = {{"ao-temporal", aoSize, PassDecl::Write::Depth::None, ""}};
    accumulate.run = [this, ao, aoScale, aoSize](PassContext& context) {
      // One history per AO size: switching to half resolution does not read a full-size history. Asked for before
      // binding: making its targets (the first time) binds their framebuffers.
      RenderTargetPool::History& history = context.history("ao-temporal " + aoSize.name(), aoSize, GL_NEAREST);
      context.bindForWriting("ao-temporal");
      temporal_.render(context.texture("ao-raw"), context.texture("velocity"), context.texture("gbuffer"), history,
                       context.frame(), ao(context), aoScale, context.size("ao-temporal"),
                       context.scene().anyMoving());
    };
    planner.add(std::move(accumulate));
    unblurred = "ao-temporal";
  }

  if (settings.blur && settings.blurRadius > 0) {
    for (const auto direction : {BilateralBlurPass::Direction::Horizontal, BilateralBlurPass::Direction::Vertical}) {
      const bool horizontal = direction == BilateralBlurPass::Direction::Horizontal;
      const char* input = horizontal ? unblurred : "ao-blur-h";
      const char* output = horizontal ? "ao-blur-h" : "ao";
      PassDecl blur;
      blur.name = horizontal ? "blur-h" : "blur-v";
      blur.reads = {input, "gbuffer"};
      blur.writes = {{output, aoSize, PassDecl::Write::Depth::None, ""}};
      blur.run = [this, ao, aoScale, direction, input, output](PassContext& context) {
        context.bindForWriting(output);
        context.limitToScene(output, kOpenSky);
        blur_.render(direction, context.texture(input), context.texture("gbuffer"), context.camera(), ao(context),
                     aoScale);
      };
      planner.add(std::move(blur));
    }
  } else {
    planner.alias("ao", unblurred);
  }

  if (half) {
    PassDecl upsample;
    upsample.name = "upsample";
    upsample.reads = {"ao", "gbuffer"};
    upsample.writes = {{"ao", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
    upsample.run = [this, ao](PassContext& context) {
      // Reads the half-size AO, writes the full-size one: two versions of "ao", two targets.
      const gl::Texture2D& halfAo = context.texture("ao");
      context.bindForWriting("ao");
      context.limitToScene("ao", kOpenSky);
      upsample_.render(halfAo, context.texture("gbuffer"), context.camera(), ao(context));
    };
    planner.add(std::move(upsample));
  }
}

}  // namespace obscura
