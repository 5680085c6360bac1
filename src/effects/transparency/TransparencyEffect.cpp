#include "effects/transparency/TransparencyEffect.h"

#include <algorithm>

#include "environment/Environment.h"
#include "frame/PassContext.h"
#include "gl/PipelineState.h"
#include "gpu/TextureUnits.h"

namespace obscura {

const std::vector<Parameter<TransparencySettings>>& TransparencySettings::parameters() {
  using S = TransparencySettings;
  static const std::vector<Parameter<S>> table = {
      switchParameter<S>("transparency",
                         "draw the transparent layer (alphaMode BLEND, transmission) over the opaque frame; off "
                         "leaves it out",
                         &S::enabled)};
  return table;
}

EffectInfo TransparencyEffect::info() {
  return {"transparency",
          "Transparency",
          true,
          false,
          {"transmission-levels", "transparency"},
          {{"transmission-levels",
            "the opaque frame halved 6 times (RGB9E5, box filtered), beside the copy of what lies behind the "
            "transparent surfaces (the effect's own texture)",
            GL_NEAREST,
            {}}}};
}

TransparentBudget TransparencyEffect::budget(int fragmentVectors) {
  TransparentBudget b;
  int left = fragmentVectors - kTransparentVectors;
  b.fog = left >= kTransparentFogVectors;
  if (b.fog) left -= kTransparentFogVectors;
  b.layers = left >= kTransparentLayerVectors;
  if (b.layers) left -= kTransparentLayerVectors;
  // The fog's last row has a free component, which then holds the filtered levels' scale.
  b.filtered = b.fog || left >= kTransparentFilteredVectors;
  if (b.filtered && !b.fog) left -= kTransparentFilteredVectors;
  b.lights = std::clamp(left / 3, 0, 4);
  return b;
}

ProgramSpec TransparencyEffect::spec(MaterialKind kind, VertexKind vertex, FogKey fog, ShadingKey shading,
                                     EnvironmentLayout layout, int lights) {
  // An unlit surface reads neither tier nor environment: one program for all.
  if (kind.unlit) shading = {};
  // The low tier reads no prefiltered level (LightingEffect::programForm).
  if (shading.quality == 0) shading.filteredFrom = kEnvironmentLevels;
  std::string name = "transparency[" + kind.nameSuffix().substr(1) + vertex.nameSuffix();
  if (fog.on) name += std::string(",fog") + std::to_string(fog.mode) + (fog.height ? "h" : "");
  if (shading.quality != 1) name += shading.quality == 0 ? ",low" : ",high";
  if (shading.filteredFrom < kEnvironmentLevels) name += ",filtered";
  name += std::string(",") + environmentLayoutName(layout) + ",lights" + std::to_string(lights) + "]";
  ProgramSpec s{name, "lib/geometry.vert", "lighting/lighting.frag",
                {{"DEFERRED", "0"},
                 {"BACKGROUND", "0"},
                 {"AT_FAR_PLANE", "0"},
                 {"LIGHTING_QUALITY", std::to_string(shading.quality)},
                 {"COUNT_SHADING", "0"},
                 {"TONEMAP_INLINE", "0"},
                 {"FAR_RAY", "0"},
                 {"MAX_PUNCTUAL_LIGHTS", std::to_string(kind.unlit ? 0 : lights)},
                 {"BLENDED", "1"},
                 {"BLENDED_FOG", fog.on ? "1" : "0"},
                 {"FOG_MODE", std::to_string(fog.mode)},
                 {"FOG_HEIGHT", fog.height ? "1" : "0"},
                 {"TRANSMISSION_LEVELS", std::to_string(kTransmissionLevels)}}};
  for (auto& define : GpuEnvironment::shaderDefines(layout, shading.filteredFrom)) s.defines.push_back(define);
  if (layout == EnvironmentLayout::MipChain) s.extensions.push_back("GL_EXT_shader_texture_lod");
  for (auto& define : kind.defines()) s.defines.push_back(define);
  for (auto& define : vertex.defines()) s.defines.push_back(define);
  return s;
}

namespace {

ProgramSpec levelsSpec() {
  return ProgramSpec{"transparency[levels]", "lib/fullscreen.vert", "transparency/levels.frag", {{"FAR_RAY", "0"}},
                     {}};
}

}  // namespace

std::vector<ProgramSpec> TransparencyEffect::programSpecs(int fragmentVectors) {
  const TransparentBudget b = budget(fragmentVectors);
  std::vector<ProgramSpec> specs = {levelsSpec()};
  const ShadingKey medium{};
  for (MaterialKind kind : MaterialKind::transparentKinds())
    if (b.layers || !kind.layered) specs.push_back(spec(kind, {}, {}, medium, EnvironmentLayout::Atlas, b.lights));
  const MaterialKind heaviest{false, true, true, false, b.layers, true};
  // The heaviest shading the budget allows: the filtered levels where it has room for them.
  const int filteredFrom = b.filtered ? kEnvironmentFilteredLevel : kEnvironmentLevels;
  if (b.fog)
    for (int mode = 0; mode < 3; ++mode)
      for (bool height : {false, true})
        specs.push_back(
            spec(heaviest, {}, {true, mode, height}, {1, filteredFrom}, EnvironmentLayout::Atlas, b.lights));
  // The other tiers, and the filtered levels, for the heaviest material in either layout; the half-float atlas
  // reads no RGBM level.
  for (EnvironmentLayout layout : {EnvironmentLayout::Atlas, EnvironmentLayout::MipChain})
    for (ShadingKey shading : {ShadingKey{0, kEnvironmentLevels}, ShadingKey{1, filteredFrom},
                               ShadingKey{2, kEnvironmentLevels}, ShadingKey{2, filteredFrom}})
      specs.push_back(spec(heaviest, {}, {}, shading, layout, b.lights));
  for (int quality = 0; quality < 3; ++quality)
    specs.push_back(
        spec(heaviest, {}, {}, {quality, kEnvironmentLevels}, EnvironmentLayout::HalfFloatAtlas, b.lights));
  for (VertexKind vertex : VertexKind::validated())
    specs.push_back(
        spec({false, true, true}, vertex.forCurrentFrame(), {}, medium, EnvironmentLayout::Atlas, b.lights));
  specs.push_back(spec(heaviest, {}, {}, medium, EnvironmentLayout::MipChain, b.lights));
  return specs;
}

const gl::Program& TransparencyEffect::program(MaterialKind kind, VertexKind vertex, FogKey fog,
                                               ShadingKey shading) const {
  kind.layered = kind.layered && budget_.layers;  // a context too small for the layers draws the core material
  if (kind.unlit) shading = {};
  if (shading.quality == 0) shading.filteredFrom = kEnvironmentLevels;
  const VertexKind stage = vertex.forCurrentFrame();
  return programs_({kind, stage, fog, shading},
                   [&] { return spec(kind, stage, fog, shading, layout_, budget_.lights); });
}

TransparencyEffect::TransparencyEffect(const EffectResources& resources)
    : resources_(resources),
      budget_(budget(resources.caps.maxFragmentUniformVectors)),
      layout_(GpuEnvironment::layoutFor(resources.caps, resources.options.environmentLayout)),
      programs_(resources.programs) {
  sourceFramebuffer_ = gl::FramebufferHandle::create();
}

void TransparencyEffect::plan(FramePlanner& planner) {
  if (!planner.frame().transparent || !planner.settings().of<TransparencySettings>().enabled) return;
  using Write = PassDecl::Write;
  if (planner.frame().transmission) {
    PassDecl levels;
    levels.name = "transmission-levels";
    levels.reads = {"scene-color"};
    levels.writes = {{"transmission-levels", TargetSize::full(), Write::Depth::None, ""}};
    levels.run = [this](PassContext& context) { renderLevels(context); };
    planner.add(std::move(levels));
    planner.markExternal("transmission-levels");
  }
  PassDecl pass;
  pass.name = "transparency";
  pass.reads = {"scene-color", "gbuffer"};  // the G-buffer pass's depth: the opaque layer the surfaces test against
  if (planner.frame().transmission) pass.reads.push_back("transmission-levels");
  pass.writes = {{"scene-color", TargetSize::full(), Write::Depth::Shared, "gbuffer"}};
  pass.run = [this](PassContext& context) { renderLayer(context); };
  planner.add(std::move(pass));
}

void TransparencyEffect::fitBehind(glm::ivec2 size) {
  if (size == frameSize_ && behind_.id() != 0) return;
  frameSize_ = size;
  constexpr int kStep = 1 << kTransmissionLevels;
  padded_ = (size + (kStep - 1)) / kStep * kStep;
  // The levels sit beside the copy where the texture can be that large; else there are none (the copy alone: a
  // transmissive surface then shows what is behind it unblurred; composite.glsl tells by the texture's width).
  const int limit = resources_.caps.maxTextureSize;
  const bool room = padded_.x + padded_.x / 2 <= limit && padded_.y <= limit;
  behind_ = room ? gl::Texture2D(padded_.x + padded_.x / 2, padded_.y, GL_NEAREST)
                 : gl::Texture2D(size.x, size.y, GL_NEAREST);
  levels_.clear();
}

// The opaque frame halved kTransmissionLevels times, each level drawn into a target of its own (a level reads the
// one before: drawing into the texture it reads would be a feedback loop), then copied beside the frame's copy.
void TransparencyEffect::renderLevels(const PassContext& context) {
  const glm::ivec2 size = context.size("scene-color");
  fitBehind(size);
  if (behind_.width() < padded_.x + padded_.x / 2 || behind_.height() < padded_.y) return;
  if (levels_.empty())
    for (int k = 1; k <= kTransmissionLevels; ++k)
      levels_.emplace_back("transmission level " + std::to_string(k), padded_.x >> k, padded_.y >> k, GL_NEAREST,
                           gl::RenderTarget::Depth::None, false);
  for (int k = 1; k <= kTransmissionLevels; ++k) {
    const gl::RenderTarget& level = levels_[static_cast<size_t>(k - 1)];
    level.bindForDrawing();
    {
      FullscreenDraw draw = context.draw(levelsSpec());
      draw.set("u_targetOrigin", glm::vec2(0.0f));
      if (k == 1) {
        draw.read("u_source", "scene-color");
        draw.set("u_sourceRect", glm::vec4(0.0f, 0.0f, size));
        draw.set("u_sourceSize", glm::vec2(size));
      } else {
        const gl::RenderTarget& source = levels_[static_cast<size_t>(k - 2)];
        draw.texture("u_source", source.color());
        // The texels of the level before that hold the frame: ceil(size / 2^(k - 1)).
        const glm::ivec2 held = (size + ((1 << (k - 1)) - 1)) >> (k - 1);
        draw.set("u_sourceRect", glm::vec4(0.0f, 0.0f, held));
        draw.set("u_sourceSize", glm::vec2(source.width(), source.height()));
      }
      draw.draw();
    }
    // Into the behind texture: level 1 at (W', 0), level k >= 2 at (W' (1.5 - 2^(1 - k)), H' / 2).
    const glm::ivec2 origin = k == 1 ? glm::ivec2(padded_.x, 0)
                                     : glm::ivec2(padded_.x + padded_.x / 2 - (padded_.x >> (k - 1)), padded_.y / 2);
    glBindTexture(GL_TEXTURE_2D, behind_.id());
    glCopyTexSubImage2D(GL_TEXTURE_2D, 0, origin.x, origin.y, 0, 0, level.width(), level.height());
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  gl::restoreBaselineState();
}

void TransparencyEffect::renderLayer(const PassContext& context) {
  const glm::ivec2 size = context.size("scene-color");
  fitBehind(size);
  const FrameCamera& camera = context.camera();
  const SurfaceLight& light = resources_.surfaces.light;
  const SurfaceFog& fog = resources_.surfaces.fog;

  // The opaque frame, copied byte for byte into this pass's target (glCopyTexSubImage2D from a framebuffer holding
  // it): no full-screen draw.
  context.bindForWriting("scene-color");
  GLint target = 0;
  glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME,
                                        &target);
  glBindFramebuffer(GL_FRAMEBUFFER, sourceFramebuffer_.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, context.texture("scene-color").id(), 0);
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(target));
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, size.x, size.y);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
  context.bindForWriting("scene-color");
  if (!light.published) {  // the lighting did not run (nothing to composite over)
    gl::restoreBaselineState();
    return;
  }

  // Tested against the opaque layer's depth, writing none: a surface behind a wall is hidden, and transparent
  // surfaces never hide each other (they composite in order).
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  if (!context.sharesDepth("scene-color")) glClear(GL_DEPTH_BUFFER_BIT);
  glActiveTexture(GL_TEXTURE0 + light.environmentFilteredUnit);
  glBindTexture(GL_TEXTURE_2D, light.environment->filteredTexture());
  glActiveTexture(GL_TEXTURE0 + TextureUnits::kEnvironment);
  glBindTexture(GL_TEXTURE_2D, light.environment->texture());
  behind_.bind(TextureUnits::kAo);  // the AO's unit: the transparent layer reads no AO

  const FogKey fogKey{fog.enabled && budget_.fog, fog.mode, fog.height};
  const ShadingKey shadingKey{light.quality,
                              budget_.filtered ? light.environment->filteredFrom() : kEnvironmentLevels};
  const float filteredScale = light.environment->filteredScale() * light.environmentIntensity;
  const int lights = std::min(budget_.lights, static_cast<int>(light.positionRange.size()));
  std::vector<glm::vec4> positionRange(static_cast<size_t>(budget_.lights)), colorSpot(positionRange.size()),
      spot(positionRange.size());
  std::copy_n(light.positionRange.begin(), lights, positionRange.begin());
  std::copy_n(light.colorSpot.begin(), lights, colorSpot.begin());
  std::copy_n(light.spot.begin(), lights, spot.begin());
  const glm::vec4 layout(size, behind_.width(), behind_.height());
  const float perspective = camera.reconstruction.perspective ? 1.0f : 0.0f;
  auto choose = [&](MaterialKind kind, VertexKind vertex) -> const gl::Program& {
    const gl::Program& p = program(kind, vertex, fogKey, shadingKey);
    p.use();
    p.set("u_projection", camera.projection);
    // Lit surfaces read the eye's rays (lib/reconstruct.glsl); an unlit one does not.
    if (p.has("u_perspective")) p.set("u_perspective", perspective);
    if (!kind.unlit) {
      p.set("u_lightDirection", light.lightDirection);
      p.set("u_lightColor", light.lightColor);
      p.set("u_viewToEnvironment", light.viewToEnvironment);
      p.set("u_shIrradiance", light.environment->irradianceUniform().data(), 7);
      p.set("u_environmentIntensity", light.environmentIntensity);
      // The medium and high tiers read the environment's levels (a smooth surface level 0, by hand) and the (A, B)
      // table in the filtered texture; the low tier neither.
      if (shadingKey.quality != 0) {
        p.set("u_environment", TextureUnits::kEnvironment);
        p.set("u_environmentFiltered", light.environmentFilteredUnit);
        if (shadingKey.filteredFrom < kEnvironmentLevels) p.set("u_environmentFilteredScale", filteredScale);
      }
    }
    // As many lights as the program takes (the budget's; none unlit).
    if (const int count = p.arraySize("u_lightPositionRange"); count > 0) {
      p.set("u_lightPositionRange", positionRange.data(), count);
      p.set("u_lightColorSpot", colorSpot.data(), count);
      p.set("u_lightSpot", spot.data(), count);
    }
    p.set("u_behind", TextureUnits::kAo);
    p.set("u_behindLayout", layout);
    if (fogKey.on) {
      p.set("u_fogColor", fog.color);
      p.set("u_fogFactor", fog.factor);
      if (fogKey.height) {  // FOG_HEIGHT
        p.set("u_fogFalloff", fog.falloff);
        p.set("u_fogHeightScale", fog.heightScale);
        p.set("u_fogUpInView", fog.upInView);
      }
    }
    return p;  // the scene sets its per-draw uniforms
  };
  const GpuScene& scene = context.scene();
  for (const GpuScene::TransparentBatch& batch : scene.transparentBatches(camera.view, camera.projection, size)) {
    // What lies behind the batch, the frame so far (farther transparent surfaces included), into the copy.
    const glm::ivec4& r = batch.rect;
    behind_.bind(TextureUnits::kAo);
    glCopyTexSubImage2D(GL_TEXTURE_2D, 0, r.x, r.y, r.x, r.y, r.z, r.w);
    scene.drawTransparent(camera.view, choose, batch);
  }
  gl::restoreBaselineState();
}

}  // namespace obscura
