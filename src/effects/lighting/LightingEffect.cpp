#include "effects/lighting/LightingEffect.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "base/Error.h"
#include "encoding/HdrEncoding.h"
#include "encoding/LinearDepthPacking.h"
#include "frame/FrameSettings.h"
#include "frame/PassContext.h"
#include "frame/Stage.h"
#include "gl/PipelineState.h"
#include "gpu/TextureUnits.h"

namespace obscura {

const std::vector<Parameter<LightingSettings>>& LightingSettings::parameters() {
  using S = LightingSettings;
  static const std::vector<Parameter<S>> table = [] {
    return std::vector<Parameter<S>>{
      presetParameter<S>("quality preset: the shading tier (low: low, medium: medium, high and ultra: high)"),
      choiceParameter<S, LightingQuality>(
          "quality",
          "shading tier: low (the ambient from spherical harmonics alone, no environment fetch), medium (the "
          "prefiltered environment), high (with multiple scattering and horizon occlusion); the preset sets it",
          &S::quality,
          {{"low", LightingQuality::Low}, {"medium", LightingQuality::Medium}, {"high", LightingQuality::High}})
          .primary(),
      choiceParameter<S, LightingDepth>(
          "depth",
          "where the lighting finds each pixel's visible surface when nothing else draws the G-buffer (the AO off): "
          "the G-buffer pass, a depth pre-pass, or its own depth test shading overdrawn fragments; auto: the "
          "G-buffer where the deferred form shades the scene, else the cheapest measured for the tier",
          &S::depth,
          {{"auto", LightingDepth::Auto}, {"gbuffer", LightingDepth::GBuffer}, {"prepass", LightingDepth::Prepass},
           {"overdraw", LightingDepth::Overdraw}}),
      choiceParameter<S>("sun",
                         "settings: the sun of lighting.sun-*; file: the file's first directional light "
                         "(KHR_lights_punctual), where it has one",
                         &S::sun, {{"settings", SunSource::Settings}, {"file", SunSource::File}}),
      numberParameter<S>("sun-elevation", -90, 90, "degrees",
                         "the sun's height above the horizon (with the sky: the sky is made again, about a second)",
                         &S::sunElevation)
          .primary()
          .slow(),
      numberParameter<S>("sun-azimuth", -360, 360, "degrees", "the sun's direction, from +z towards +x",
                         &S::sunAzimuth)
          .primary(),
      colorParameter<S>("sun-color", 0, 1, "the sun's colour (its illuminance is colour x intensity)", &S::sunColor),
      numberParameter<S>("sun-intensity", 0, 100000, "lux",
                         "the sun's illuminance per unit of colour (pi: a white matte surface facing the sun shows "
                         "its colour)",
                         &S::sunIntensity),
      textParameter<S>("environment", "sky | uniform | a file path",
                       "the ambient light and background: the built-in sky, a uniform white furnace (radiance 1), or "
                       "an equirectangular .hdr (or RGBE .png) file",
                       &S::environment, {"sky", "uniform"})
          .primary(),
      numberParameter<S>("environment-intensity", 0, 1000, "", "scales the environment's radiance (ambient light and "
                         "background)", &S::environmentIntensity)
          .primary()};
  }();
  return table;
}

namespace {

// The background's cube map on its unit (gpu/TextureUnits.h: kSky) for the pass, unbound when the pass returns: the
// baseline state holds no cube map, and restoreBaselineState unbinds 2D textures only. Leaves unit 0 active.
class SkyCubeBinding {
 public:
  explicit SkyCubeBinding(GLuint cube) : bound_(cube != 0) {
    if (bound_) bind(cube);
  }
  ~SkyCubeBinding() {
    if (bound_) bind(0);
  }
  SkyCubeBinding(const SkyCubeBinding&) = delete;
  SkyCubeBinding& operator=(const SkyCubeBinding&) = delete;

 private:
  static void bind(GLuint cube) {
    glActiveTexture(GL_TEXTURE0 + TextureUnits::kSky);
    glBindTexture(GL_TEXTURE_CUBE_MAP, cube);
    glActiveTexture(GL_TEXTURE0);
  }
  bool bound_;
};

LightingQuality qualityOf(QualityPreset preset) {
  switch (preset) {
    case QualityPreset::Low: return LightingQuality::Low;
    case QualityPreset::Medium: return LightingQuality::Medium;
    default: return LightingQuality::High;
  }
}
}  // namespace

void LightingSettings::applyPreset(QualityPreset which) {
  preset = which;
  quality = qualityOf(which);
}

bool LightingSettings::matchesPreset(QualityPreset which) const { return quality == qualityOf(which); }

LightingDepth LightingSettings::depthInUse(bool deferredForm) const {
  if (depth != LightingDepth::Auto) return depth;
  if (deferredForm) return LightingDepth::GBuffer;
  return quality == LightingQuality::Low ? LightingDepth::Overdraw : LightingDepth::Prepass;
}

glm::vec3 LightingSettings::directionToSun() const { return sunDirection(sunElevation, sunAzimuth); }

Sun Sun::of(const LightingSettings& settings, const std::vector<PunctualLight>& lights) {
  Sun sun;
  sun.directionToSun = settings.directionToSun();
  sun.illuminance = settings.sunColor * settings.sunIntensity;
  if (settings.sun != SunSource::File) return sun;
  for (size_t i = 0; i < lights.size(); ++i) {
    if (lights[i].type != LightType::Directional) continue;
    // KHR_lights_punctual: a directional light shines along its node's -z.
    const glm::vec3 towards = glm::vec3(lights[i].world * glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));
    if (!(glm::dot(towards, towards) > 0.0f)) continue;
    sun.directionToSun = glm::normalize(towards);
    sun.illuminance = lights[i].color * lights[i].intensity;
    sun.fileLight = static_cast<int>(i);
    break;
  }
  return sun;
}

PunctualLightUniforms PunctualLightUniforms::of(const std::vector<PunctualLight>& lights, const glm::mat4& view,
                                                int maxCount, int skip) {
  maxCount = std::clamp(maxCount, 0, kMaxPunctualLights);
  PunctualLightUniforms out;
  // The lights that light the camera's surroundings most: intensity / distance^2 at the camera (view-space origin);
  // a directional light's intensity is the illuminance it gives everywhere.
  std::vector<std::pair<float, size_t>> order;
  for (size_t i = 0; i < lights.size(); ++i) {
    if (static_cast<int>(i) == skip) continue;
    const glm::vec3 p(view * lights[i].world[3]);
    const glm::vec3& c = lights[i].color;
    const float d2 = lights[i].type == LightType::Directional ? 1.0f : std::max(glm::dot(p, p), 1e-6f);
    order.emplace_back(-lights[i].intensity * std::max(c.r, std::max(c.g, c.b)) / d2, i);
  }
  std::stable_sort(order.begin(), order.end());
  for (const auto& [key, index] : order) {
    if (out.count == maxCount) break;
    const PunctualLight& light = lights[index];
    const auto k = static_cast<size_t>(out.count++);
    const glm::mat4 toView = view * light.world;
    const float range4 = light.range > 0.0f ? std::pow(light.range, 4.0f) : 0.0f;
    out.positionRange[k] = glm::vec4(glm::vec3(toView[3]), range4 > 0.0f ? 1.0f / range4 : 0.0f);
    if (light.type == LightType::Directional)  // w -1 marks it: xyz the direction towards it (+z of its node)
      out.positionRange[k] =
          glm::vec4(glm::normalize(glm::vec3(toView * glm::vec4(0.0f, 0.0f, 1.0f, 0.0f))), -1.0f);
    // KHR_lights_punctual's cone: clamp(cos * scale + offset, 0, 1)^2, scale = 1 / max(cos inner - cos outer,
    // 0.001), offset = -cos outer * scale. A point light: scale 0, offset 1 (cone 1 everywhere).
    float scale = 0.0f, offset = 1.0f;
    if (light.type == LightType::Spot) {
      const float cosOuter = std::cos(light.outerConeAngle), cosInner = std::cos(light.innerConeAngle);
      scale = 1.0f / std::max(cosInner - cosOuter, 0.001f);
      offset = -cosOuter * scale;
    }
    out.colorSpot[k] = glm::vec4(light.color * light.intensity, scale);
    // The light shines along its node's -z.
    const glm::vec3 axis = glm::normalize(glm::vec3(toView * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f)));
    out.spot[k] = glm::vec4(axis, offset);
  }
  return out;
}

// The sky was made with its sun at the default azimuth: turning it about +y by (default - wanted) puts its sun at the
// wanted azimuth (a turn by t about +y adds t to a direction's azimuth, measured from +z towards +x).
glm::mat3 LightingEffect::environmentRotation(const LightingSettings& settings) {
  if (settings.environment != "sky") return glm::mat3(1.0f);
  const float turn = glm::radians(LightingSettings{}.sunAzimuth - settings.sunAzimuth);
  return glm::mat3(glm::rotate(glm::mat4(1.0f), turn, glm::vec3(0.0f, 1.0f, 0.0f)));
}

int LightingEffect::punctualLightsPerDraw(int maxFragmentUniformVectors, bool layered) {
  const int base = kForwardLightingVectorsWithoutLights + (layered ? kMaterialLayerVectors : 0);
  if (maxFragmentUniformVectors < base) return -1;
  return std::clamp((maxFragmentUniformVectors - base) / kVectorsPerPunctualLight, 0, kMaxPunctualLights);
}

EffectInfo LightingEffect::info() {
  return {"lighting",
          "Lighting",
          false,
          false,
          {"lighting", "shading-count"},
          {{"scene-color",
            "linear HDR colour in the RGBA8 encoding of lib/hdr.glsl (" + kHdrColorEncoding.name() +
                ", encoding/HdrEncoding.h): fetch NEAREST, decode, then filter",
            GL_NEAREST,
            {{"scene-color", ViewDecoding::HdrColor}}},
           {"shading-count", "R: fragments the lighting pass shaded at this pixel, / 255 (diagnostic)", GL_NEAREST,
            {{"shading-count", ViewDecoding::Count}}}}};
}

// The material as a form's fragment stage sees it: a full-screen pass has none, the shading count reads the base
// colour only for the alpha test.
MaterialKind LightingEffect::readKind(const Form& form, MaterialKind kind) {
  if (form.deferred) return {};
  return form.counting ? kind.forAlphaOnly() : kind;
}

LightingEffect::Form LightingEffect::programForm(Form form) {
  // The counting forms shade nothing; the background reads the environment's level 0 only (by hand).
  if (form.counting || form.background) {
    form.quality = LightingQuality::Medium;
    form.filteredFrom = kEnvironmentLevels;
  }
  // The low tier reads no prefiltered level.
  if (form.quality == LightingQuality::Low) form.filteredFrom = kEnvironmentLevels;
  return form;
}


// The forms' programs. The background form is the deferred program's background alone, drawn over fullscreen.vert
// at the far plane (AT_FAR_PLANE).
ProgramSpec LightingEffect::spec(const Form& shown, MaterialKind kind, VertexKind vertex, EnvironmentLayout layout,
                                 int lightsPerDraw) {
  const Form form = programForm(shown);
  // The low tier's shading reads no level (only the deferred form's background branch does): one program for both
  // layouts.
  if (form.quality == LightingQuality::Low && !form.counting && !form.background && !form.deferred)
    layout = EnvironmentLayout::Atlas;
  const bool fullscreen = form.deferred || form.background;
  std::string name = "lighting[";
  if (form.background) name += "background";
  else if (form.deferred) name += "deferred";
  else name += "forward" + kind.nameSuffix() + vertex.nameSuffix();
  if (form.counting) name += ",count-shading";
  const bool shading = !form.counting && !form.background;
  if (shading && form.quality != LightingQuality::Medium)
    name += form.quality == LightingQuality::Low ? ",low" : ",high";
  if (shading && form.filteredFrom < kEnvironmentLevels) name += ",filtered";
  if (!form.counting) name += std::string(",") + environmentLayoutName(layout);
  ProgramSpec s{name + "]", fullscreen ? "lib/fullscreen.vert" : "lib/geometry.vert", "lighting/lighting.frag",
                {{"DEFERRED", fullscreen ? "1" : "0"},
                 {"BACKGROUND", form.background ? "1" : "0"},
                 {"AT_FAR_PLANE", form.background ? "1" : "0"},
                 {"COUNT_SHADING", form.counting ? "1" : "0"},
                 {"LIGHTING_QUALITY", std::to_string(static_cast<int>(form.quality))},
                 {"MAX_PUNCTUAL_LIGHTS", std::to_string(fullscreen ? 0 : lightsPerDraw)},
                 // The deferred forms' view direction is the far-plane ray's.
                 {"FAR_RAY", fullscreen && !form.counting ? "1" : "0"},
                 {"ENVIRONMENT_RAY", fullscreen && !form.counting ? "1" : "0"}}};
  for (auto& define : GpuEnvironment::shaderDefines(layout, form.filteredFrom)) s.defines.push_back(define);
  if (layout == EnvironmentLayout::MipChain && !form.counting) s.extensions.push_back("GL_EXT_shader_texture_lod");
  for (auto& define : kind.defines()) s.defines.push_back(define);
  if (!fullscreen)
    for (auto& define : vertex.defines()) s.defines.push_back(define);
  // The shading forms call finishPixel: they take per-pixel stages (frame/Stage.h), none at least.
  return form.counting ? s : fusedProgram(s, {}, ColorSpace::Hdr);
}

std::vector<StageHeadSpec> LightingEffect::stageHeads(int lightsPerDraw) {
  const MaterialKind heaviest{true, true, true};
  const int forward = kForwardLightingVectorsWithoutStages + lightsPerDraw * kVectorsPerPunctualLight;
  std::vector<StageHeadSpec> heads;
  for (const Form& form : {Form{true, false, false}, Form{false, false, true}})
    heads.push_back({spec(form, {}, {}, EnvironmentLayout::Atlas, 0), ColorSpace::Hdr,
                     kDeferredLightingVectorsWithoutStages});
  for (MaterialKind kind : {MaterialKind{}, heaviest})
    heads.push_back({spec({false, false, false}, kind, {}, EnvironmentLayout::Atlas, lightsPerDraw), ColorSpace::Hdr,
                     forward});
  // The layered materials' heaviest, with as many lights.
  const MaterialKind layered{true, true, true, false, true, false};
  heads.push_back({spec({false, false, false}, layered, {}, EnvironmentLayout::Atlas, lightsPerDraw), ColorSpace::Hdr,
                   forward + kMaterialLayerVectors});
  for (StageHeadSpec& head : heads) head.program = withoutStages(head.program);
  return heads;
}

// A shading form's program as fusedProgram takes it: the head, without the (empty) chain spec() gives it.
ProgramSpec LightingEffect::withoutStages(ProgramSpec head) {
  head.fragmentText.clear();
  head.name = head.name.substr(0, head.name.find('+'));
  head.defines.erase(std::remove_if(head.defines.begin(), head.defines.end(),
                                    [](const auto& d) { return d.first.rfind("STAGE_", 0) == 0; }),
                     head.defines.end());
  return head;
}

// Every form with the atlas (any GLES 2 context), and the shading forms again with the mip chain and with the
// half-float atlas; the shading forms in each tier, the medium and high ones with and without the filtered RGBM
// levels (which the half-float atlas never reads); no stage fused (frameProgramSpecs adds the chains).
std::vector<ProgramSpec> LightingEffect::programSpecs(int lightsPerDraw, std::optional<int> layeredLights) {
  const int layeredLightsPerDraw = layeredLights.value_or(lightsPerDraw);
  std::vector<ProgramSpec> specs;
  struct Shading {
    LightingQuality quality;
    int filteredFrom;
  };
  const std::vector<Shading> shadings = {{LightingQuality::Low, kEnvironmentLevels},
                                         {LightingQuality::Medium, kEnvironmentLevels},
                                         {LightingQuality::Medium, kEnvironmentFilteredLevel},
                                         {LightingQuality::High, kEnvironmentLevels},
                                         {LightingQuality::High, kEnvironmentFilteredLevel}};
  for (EnvironmentLayout layout :
       {EnvironmentLayout::Atlas, EnvironmentLayout::MipChain, EnvironmentLayout::HalfFloatAtlas})
    for (bool deferred : {false, true})
      for (bool counting : {true, false}) {
        if (counting && layout != EnvironmentLayout::Atlas) continue;
        for (const Shading& shading : counting ? std::vector<Shading>{shadings[1]} : shadings) {
          // The low tier's shading reads no level: its forms differ by layout only in the deferred background.
          if (shading.quality == LightingQuality::Low && layout != EnvironmentLayout::Atlas && !deferred) continue;
          if (layout == EnvironmentLayout::HalfFloatAtlas && shading.filteredFrom < kEnvironmentLevels) continue;
          for (MaterialKind kind : MaterialKind::all()) {
            // The extended kinds (unlit, layered) take the forward forms only (Material::needsForwardLighting), with
            // the atlas, in every tier: enough for the shader checks to compile every #if of them.
            if (kind.extended() && (deferred || layout != EnvironmentLayout::Atlas)) continue;
            if (kind.layered && layeredLightsPerDraw < 0) continue;
            const Form form{deferred, counting, false, shading.quality, shading.filteredFrom};
            if (readKind(form, kind) == kind)
              specs.push_back(spec(form, kind, {}, layout, kind.layered ? layeredLightsPerDraw : lightsPerDraw));
          }
        }
        if (!deferred && !counting) specs.push_back(spec({false, false, true}, {}, {}, layout, 0));
      }
  for (VertexKind vertex : VertexKind::validated())
    specs.push_back(spec({false, false, false}, {}, vertex, EnvironmentLayout::Atlas, lightsPerDraw));
  return specs;
}

const gl::Program& LightingEffect::program(const Form& asked, MaterialKind kind, VertexKind vertex,
                                           const std::vector<StageDecl>& stages, const std::string& chain) const {
  const Form form = programForm(asked);
  const bool fullscreen = form.deferred || form.background;
  MaterialKind read = readKind(form, kind);
  // A context whose fragment uniform vectors do not hold the layers draws the core material (kMaterialLayerVectors).
  read.layered = read.layered && layeredLightsPerDraw_ >= 0;
  const VertexKind stage = fullscreen ? VertexKind{} : vertex.forCurrentFrame();
  return programs_({form, read, stage, chain}, [&] {
    const ProgramSpec head = spec(form, read, stage, layout_, read.layered ? layeredLightsPerDraw_ : lightsPerDraw_);
    if (form.counting || stages.empty()) return head;
    return fusedProgram(withoutStages(head), stages, ColorSpace::Hdr);
  });
}

// The sky is made with its sun at the default azimuth and turned to the wanted one (environmentRotation): only the
// elevation changes the sky itself.
void LightingEffect::prepare(const FrameSettings& frameSettings) {
  const LightingSettings& settings = frameSettings.of<LightingSettings>();
  LightingSettings sky;
  sky.sunElevation = settings.sunElevation;
  environments_.use(settings.environment, sky.directionToSun());
}

LightingEffect::LightingEffect(const EffectResources& resources)
    : resources_(resources),
      programs_(resources.programs),
      white_(1, 1, GL_NEAREST, std::vector<std::uint8_t>{255, 255, 255, 255}.data()),
      stencil_(resources.caps.packedDepthStencil),
      layout_(GpuEnvironment::layoutFor(resources.caps, resources.options.environmentLayout)),
      lightsPerDraw_(punctualLightsPerDraw(resources.caps.maxFragmentUniformVectors)),
      layeredLightsPerDraw_(punctualLightsPerDraw(resources.caps.maxFragmentUniformVectors, true)),
      environmentFilteredUnit_(TextureUnits::environmentFiltered(resources.caps)),
      drawBuffers_(resources.caps.drawBuffers && resources.options.allowDrawBuffers),
      environments_(layout_, resources.options.environmentFiltering, resources.caps.desktopGl) {
  // The variants are built on first use, as the G-buffer's are (GBufferEffect.cpp): building every material's here
  // cost the page's start-up a program each (docs/resolution.md, "Start-up").
  environments_.use("sky", LightingSettings{}.directionToSun());
}

void LightingEffect::plan(FramePlanner& planner) {
  using Write = PassDecl::Write;
  using Alternative = PassDecl::Alternative;
  std::vector<std::string> reads;
  if (planner.declares("ao")) reads.push_back("ao");
  // The G-buffer's depth also when nothing else needs the G-buffer, where that is the cheaper (LightingDepth).
  const LightingSettings& lighting = planner.settings().of<LightingSettings>();
  const bool deferredForm = drawBuffers_ && !planner.frame().forwardLighting;
  if (lighting.depthInUse(deferredForm) == LightingDepth::GBuffer) reads.push_back("gbuffer");
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> all = reads;
    for (std::string& target : more)
      if (std::find(all.begin(), all.end(), target) == all.end()) all.push_back(std::move(target));
    return all;
  };
  auto runAs = [this](Form form) {
    return [this, form](PassContext& context) { render(context, form); };
  };
  // What each shading form offers the per-pixel stages after it (fog, the tone curve): the fragment uniform vectors
  // its heaviest program leaves, and whether it may draw into the output framebuffer: the forward form depth-tests,
  // so only where the output has a depth buffer, and only where the G-buffer pass does not run (then the output's own
  // depth, cleared: a pass of the frame's fewer where nothing reads the lit image, as in `preset low` with the AO off;
  // over the G-buffer's depth it shades each pixel once, and keeps that); the deferred form always (it then shades
  // without the G-buffer's depth: render()).
  const int vectors = resources_.caps.maxFragmentUniformVectors;
  // The forward form's heaviest program: the most lights, or a layered material's layers and its lights (the layers'
  // kMaterialLayerVectors leave no spare column for a stage's floats, Shaders.EveryProgramFitsTheGles2...).
  const int forwardOwn = std::max(kForwardLightingVectorsWithoutStages + lightsPerDraw_ * kVectorsPerPunctualLight,
                                  kForwardLightingVectorsWithoutStages + kMaterialLayerVectors +
                                      layeredLightsPerDraw_ * kVectorsPerPunctualLight);
  const int units = TextureUnits::stageUnits(resources_.caps);
  const StageHead forward{"scene-color", ColorSpace::Hdr, vectors - forwardOwn, planner.frame().outputDepth, false,
                          units, TextureUnits::kStages, true};
  const StageHead deferred{"scene-color", ColorSpace::Hdr, vectors - kDeferredLightingVectorsWithoutStages, true,
                           false, units, TextureUnits::kStages};

  for (const char* output : {"scene-color", "shading-count"}) {
    const bool counting = std::string(output) == "shading-count";
    // The counting pass is planned only for its view, beside the lit pass (which that view's plan then drops). It
    // has the lit pass's reads and alternatives, so the plan, and with it the depth set-up, is the one the lit
    // pass would have.
    if (counting && planner.viewTarget() != output) continue;
    PassDecl pass;
    pass.name = counting ? "shading-count" : "lighting";
    pass.reads = reads;
    pass.optionalReads = {"gbuffer"};  // its depth, when the G-buffer pass runs anyway
    pass.writes = {{output, TargetSize::full(), Write::Depth::Shared, "gbuffer"}};
    pass.run = runAs({false, counting, false});
    if (!counting) pass.stageHead = forward;
    // Deferred where the G-buffer pass writes the base colour beside the G-buffer: one full-screen program, the
    // shading or the background at each pixel; the G-buffer's depth stays with the image for the passes after it
    // (the transparent layer).
    if (counting) {
      pass.alternatives = {Alternative{{"base-color"}, {"gbuffer"},
                                       {{output, TargetSize::full(), Write::Depth::None, ""}},
                                       runAs({true, true, false}), std::nullopt, "", false}};
    } else {
      pass.alternatives = {Alternative{{"base-color"}, with({"gbuffer", "base-color"}),
                                       {{output, TargetSize::full(), Write::Depth::Shared, "gbuffer"}},
                                       runAs({true, false, false}), deferred, "", false}};
    }
    planner.add(std::move(pass));
  }
}

// The light this pass shades with, for the surfaces drawn after it (frame/SurfaceShading.h: the transparent layer).
void LightingEffect::publish(const PassContext& context, const Sun& sun, const glm::vec3& lightDirection,
                             const glm::mat3& viewToEnvironment, const LightingSettings& settings) const {
  SurfaceLight& out = resources_.surfaces.light;
  out.published = true;
  out.environment = &environments_.current();
  out.environmentFilteredUnit = environmentFilteredUnit_;
  out.quality = static_cast<int>(settings.quality);
  out.viewToEnvironment = viewToEnvironment;
  out.environmentIntensity = settings.environmentIntensity;
  out.lightDirection = lightDirection;
  out.lightColor = sun.illuminance;
  const PunctualLightUniforms all =
      PunctualLightUniforms::of(context.scene().lights(), context.camera().view, kMaxPunctualLights, sun.fileLight);
  out.positionRange.assign(all.positionRange, all.positionRange + all.count);
  out.colorSpot.assign(all.colorSpot, all.colorSpot + all.count);
  out.spot.assign(all.spot, all.spot + all.count);
}

void LightingEffect::render(const PassContext& context, Form form) const {
  const FrameCamera& camera = context.camera();
  const LightingSettings& settings = context.settings().of<LightingSettings>();
  const GpuEnvironment& environment = environments_.current();
  // The tier and the environment's storage are read now, not when the plan was made: neither changes its shape.
  form.quality = settings.quality;
  form.filteredFrom = environment.filteredFrom();
  // Its colour, or that of the per-pixel stages fused into it (frame/Stage.h), which its programs run after the
  // shading.
  static const std::vector<StageDecl> none;
  const std::string output = form.counting ? std::string("shading-count") : context.stageOutput();
  const std::vector<StageDecl>& stages = form.counting ? none : context.stages();
  static const std::string noChain;
  const std::string& chain = form.counting ? noChain : context.stagesName();
  context.bindForWriting(output);
  const bool writesOutput = context.writesOutput(output);

  const glm::mat3 viewRotation(camera.view);
  const Sun sun = Sun::of(settings, context.scene().lights());
  const glm::vec3 lightDirection = glm::normalize(viewRotation * sun.directionToSun);
  const glm::mat3 viewToWorld = glm::transpose(viewRotation);  // the view's rotation is orthonormal
  const glm::mat3 viewToEnvironment = environmentRotation(settings) * viewToWorld;
  const PunctualLightUniforms lights =
      form.deferred ? PunctualLightUniforms{}
                    : PunctualLightUniforms::of(context.scene().lights(), camera.view, lightsPerDraw_, sun.fileLight);
  if (!form.counting) publish(context, sun, lightDirection, viewToEnvironment, settings);
  // The texture units: gpu/TextureUnits.h.
  const int kEnvironmentUnit = TextureUnits::kEnvironment;
  const int kEnvironmentFilteredUnit = environmentFilteredUnit_;
  // The uniforms of a form's program, where it has them: a form, tier, storage or material kind (unlit) may leave
  // any out (the draws' own, and the full-screen forms' ray, are set strictly).
  auto setShading = [&](const gl::Program& p, const Form& f) {
    if (f.counting) return;
    auto optional = [&p](const char* name, const auto& value) {
      if (p.has(name)) p.set(name, value);
    };
    const bool fullscreen = f.deferred || f.background;
    optional("u_viewToEnvironment", viewToEnvironment);  // an unlit material reads no light (KHR_materials_unlit)
    optional("u_rayToEnvironment", viewToEnvironment);   // the full-screen forms' vertex stage (ENVIRONMENT_RAY)
    optional("u_sky", TextureUnits::kSky);
    optional("u_environmentIntensity", settings.environmentIntensity);
    optional("u_environment", kEnvironmentUnit);
    optional("u_environmentFiltered", kEnvironmentFilteredUnit);
    optional("u_environmentFilteredScale", environment.filteredScale() * settings.environmentIntensity);
    // The far-plane ray (only its direction is used), and along it the position where a stage reads it.
    if (fullscreen) setFarRay(p, camera.reconstruction);
    else optional("u_perspective", camera.reconstruction.perspective ? 1.0f : 0.0f);
    if (f.deferred && !f.background && chainNeedsPosition(stages))
      p.set("u_depthToRay", camera.reconstruction.depthToRay);
    if (!f.background) {
      optional("u_lightDirection", lightDirection);
      optional("u_lightColor", sun.illuminance);
      optional("u_ao", TextureUnits::kAo);
      if (p.has("u_shIrradiance")) p.set("u_shIrradiance", environment.irradianceUniform().data(), 7);
    }
    // As many lights as the program takes (MAX_PUNCTUAL_LIGHTS: fewer for the layered materials).
    if (const int count = fullscreen ? 0 : p.arraySize("u_lightPositionRange"); count > 0) {
      p.set("u_lightPositionRange", lights.positionRange, count);
      p.set("u_lightColorSpot", lights.colorSpot, count);
      p.set("u_lightSpot", lights.spot, count);
    }
    setStageUniforms(p, stages, context, writesOutput);
    setStageSamplers(p, stages, TextureUnits::kStages);
  };
  bindStageTextures(stages, TextureUnits::kStages);
  (context.has("ao") ? context.texture("ao") : white_).bind(TextureUnits::kAo);
  if (!form.counting) {
    glActiveTexture(GL_TEXTURE0 + kEnvironmentFilteredUnit);
    glBindTexture(GL_TEXTURE_2D, environment.filteredTexture());
    glActiveTexture(GL_TEXTURE0 + kEnvironmentUnit);
    glBindTexture(GL_TEXTURE_2D, environment.texture());
  }
  const SkyCubeBinding sky(form.counting ? 0 : environment.skyTexture());
  // The background: the environment where the depth is still 1 (nothing drawn), a full-screen triangle on the far
  // plane tested LEQUAL against it, writing no depth.
  auto drawBackground = [&] {
    const Form background{false, false, true};
    const gl::Program& p = program(background, {}, {}, stages, chain);
    p.use();
    setShading(p, background);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    resources_.triangle.draw();
  };

  if (form.deferred) {
    // Every pixel once, background included, by one program that tells the background by the G-buffer's depth
    // code. Not two draws over the G-buffer's depth (the shading where it is nearer than the far plane, then the
    // background): on SwiftShader that lighting pass cost 92.5 ms against this one's 85 (the default frame at
    // 1280x720, profile-passes.mjs), on llvmpipe the same (36 ms); both rasterisers shade the pixels a depth test
    // fails, and a branch runs both sides there anyway. Outside the scene's bounds on screen (PassContext::sceneRect)
    // every pixel is the background: there the background's program alone, scissored to the bands around the bounds
    // (the default frame's lighting pass on SwiftShader at 1280x720, 2CylinderEngine: 84 -> 52 ms;
    // docs/benchmarks.md, "The scene's bounds").
    if (form.counting) {
      glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
      glClear(GL_COLOR_BUFFER_BIT);
    }
    if (!form.counting) {
      const Form background{false, false, true};
      const gl::Program& b = program(background, {}, {}, stages, chain);
      b.use();
      setShading(b, background);
      context.drawAroundScene(output, [&] { resources_.triangle.draw(); });
    }
    const gl::Program& p = program(form, {}, {}, stages, chain);
    p.use();
    setShading(p, form);
    context.texture("gbuffer").bind(TextureUnits::kBaseColor);
    p.set("u_gbuffer", TextureUnits::kBaseColor);
    if (!form.counting) {
      context.texture("base-color").bind(TextureUnits::kPbr[0]);
      p.set("u_baseColor", TextureUnits::kPbr[0]);
    }
    if (form.counting) {
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
    }
    resources_.triangle.draw();
    // What this form set, put back; not the whole baseline (gl::restoreBaselineState: about 45 WebGL calls, a
    // microsecond each on the page: docs/benchmarks.md). The sky's cube goes with its binding's scope.
    if (form.counting) {
      glDisable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ZERO);
    }
    glDisable(GL_SCISSOR_TEST);  // the scene's rectangle (drawAroundScene)
    glUseProgram(0);
    unbindStageTextures(stages, TextureUnits::kStages);
    gl::unbindTextureUnits({TextureUnits::kBaseColor, TextureUnits::kAo, TextureUnits::kPbr[0], kEnvironmentUnit,
                            kEnvironmentFilteredUnit});
    return;
  }

  // Every pixel is drawn: by the scene, or by the background where the depth is still 1 (the shading forms; the
  // count adds to zero).
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glEnable(GL_DEPTH_TEST);
  // The depth pre-pass (LightingDepth::Prepass) where the pass has a depth of its own: the scene's nearest depth
  // first, with the counting forms' trivial fragment stage (the alpha test only) and colour writes off; then the
  // shading over it, as over the G-buffer's.
  const bool prepass = !context.sharesDepth(output) &&
                       settings.depthInUse(drawBuffers_ && !context.frame().forwardLighting) == LightingDepth::Prepass;
  if (prepass) {
    glClearDepthf(1.0f);
    glClear(GL_DEPTH_BUFFER_BIT);
    glDepthFunc(GL_LESS);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    const Form depthOnly{false, true, false};
    context.scene().draw(camera.view, [&](MaterialKind kind, VertexKind vertex) -> const gl::Program& {
      const gl::Program& p = program(depthOnly, kind, vertex, none, "");
      p.use();
      p.set("u_projection", camera.projection);
      return p;
    });
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }
  const bool overDepth = context.sharesDepth(output) || prepass;
  if (overDepth && stencil_ && !writesOutput) {  // the output may have no stencil (the canvas has none)
    // The G-buffer's depth holds each pixel's nearest surface: GL_EQUAL lets only that surface's fragments through,
    // and the stencil (0, set to 1 by the first that passes) only the first of them. A coplanar or edge-on face at
    // exactly that depth is not shaded again: GL_EQUAL alone would shade it too (the shading-count test caught it at
    // the edges of the built-in scene's boxes).
    glClearStencil(0);
    glClear(GL_COLOR_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 0, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
  } else if (overDepth) {
    // Without a stencil buffer: GL_LESS against that depth pulled one resolvable step towards the camera, writing
    // depth, so a later fragment of the same depth fails. Faces seen exactly edge-on may still shade a pixel twice
    // (a hidden one within that step, drawn first); the visible surface, drawn after, still wins.
    glClear(GL_COLOR_BUFFER_BIT);
    glDepthFunc(GL_LESS);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0.0f, -1.0f);
  } else {
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDepthFunc(GL_LESS);
  }
  if (form.counting) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
  }
  context.scene().draw(camera.view, [&](MaterialKind kind, VertexKind vertex) -> const gl::Program& {
    const gl::Program& p = program(form, kind, vertex, stages, chain);
    p.use();
    p.set("u_projection", camera.projection);
    setShading(p, form);
    return p;
  });
  if (!form.counting) drawBackground();
  gl::restoreBaselineState();
}

}  // namespace obscura
