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
#include "gl/PipelineState.h"
#include "gpu/TextureUnits.h"

namespace obscura {

const std::vector<Parameter<LightingSettings>>& LightingSettings::parameters() {
  using S = LightingSettings;
  static const std::vector<Parameter<S>> table = [] {
    std::vector<std::string> presetNames;
    for (QualityPreset p : allQualityPresets()) presetNames.push_back(presetName(p));
    Parameter<S> presetParameter{{"preset", parse::joinChoices(presetNames, " | "),
                                  "quality preset: the shading tier (low: low, medium: medium, high and ultra: high)",
                                  ParameterKind::Choice, 0.0, 0.0, presetNames},
                                 {}, {}, {}, {}};
    presetParameter.set = [](S& s, const std::string& v) { s.applyPreset(parsePreset(v)); };
    presetParameter.get = [](const S& s) {
      return s.matchesPreset(s.preset) ? std::string(presetName(s.preset)) : "";
    };
    presetParameter.valid = [](const S&) { return true; };
    return std::vector<Parameter<S>>{
      std::move(presetParameter),
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
          "cheapest measured for the tier",
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
  if (quality == LightingQuality::Low) return LightingDepth::Overdraw;
  return deferredForm ? LightingDepth::GBuffer : LightingDepth::Prepass;
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
  if (!form.deferred || form.counting) form.overDepth = false;
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
  if (form.quality == LightingQuality::Low && !form.counting && !form.background && form.overDepth == form.deferred)
    layout = EnvironmentLayout::Atlas;
  const bool fullscreen = form.deferred || form.background;
  std::string name = "lighting[";
  if (form.background) name += "background";
  else if (form.deferred) name += "deferred";
  else name += "forward" + kind.nameSuffix() + vertex.nameSuffix();
  if (form.counting) name += ",count-shading";
  if (form.toneMap >= 0)
    name += std::string(",tonemap=") + toneMapOperatorName(static_cast<ToneMapOperator>(form.toneMap));
  const bool shading = !form.counting && !form.background;
  if (form.overDepth) name += ",over-depth";
  if (shading && form.quality != LightingQuality::Medium)
    name += form.quality == LightingQuality::Low ? ",low" : ",high";
  if (shading && form.filteredFrom < kEnvironmentLevels) name += ",filtered";
  if (!form.counting) name += std::string(",") + environmentLayoutName(layout);
  ProgramSpec s{name + "]", fullscreen ? "lib/fullscreen.vert" : "lib/geometry.vert", "lighting/lighting.frag",
                {{"DEFERRED", fullscreen ? "1" : "0"},
                 {"BACKGROUND", form.background ? "1" : "0"},
                 {"OVER_DEPTH", form.overDepth ? "1" : "0"},
                 {"AT_FAR_PLANE", form.background || form.overDepth ? "1" : "0"},
                 {"COUNT_SHADING", form.counting ? "1" : "0"},
                 {"TONEMAP_INLINE", form.toneMap >= 0 ? "1" : "0"},
                 {"LIGHTING_QUALITY", std::to_string(static_cast<int>(form.quality))},
                 {"MAX_PUNCTUAL_LIGHTS", std::to_string(fullscreen ? 0 : lightsPerDraw)},
                 // The deferred forms' view direction is the far-plane ray's.
                 {"FAR_RAY", fullscreen && !form.counting ? "1" : "0"}}};
  for (auto& define : GpuEnvironment::shaderDefines(layout, form.filteredFrom)) s.defines.push_back(define);
  if (layout == EnvironmentLayout::MipChain && !form.counting) s.extensions.push_back("GL_EXT_shader_texture_lod");
  for (auto& define : kind.defines()) s.defines.push_back(define);
  if (!fullscreen)
    for (auto& define : vertex.defines()) s.defines.push_back(define);
  if (form.toneMap >= 0) s.defines.push_back(toneMapShaderDefine(static_cast<ToneMapOperator>(form.toneMap)));
  return s;
}

// Every form with the atlas (any GLES 2 context), and the shading forms again with the mip chain; the shading forms
// in each tier, the medium and high ones with and without the filtered levels.
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
  for (EnvironmentLayout layout : {EnvironmentLayout::Atlas, EnvironmentLayout::MipChain})
    for (bool deferred : {false, true})
      for (bool counting : {true, false}) {
        if (counting && layout == EnvironmentLayout::MipChain) continue;
        for (int toneMap = -1; toneMap < (counting ? 0 : kToneMapOperatorCount); ++toneMap) {
          for (const Shading& shading : counting ? std::vector<Shading>{shadings[1]} : shadings)
            for (bool overDepth : {false, true}) {
              if (overDepth && (!deferred || counting)) continue;
              // The low tier's shading reads no level: its forms differ by layout only in the deferred background.
              if (shading.quality == LightingQuality::Low && layout == EnvironmentLayout::MipChain &&
                  overDepth == deferred)
                continue;
              for (MaterialKind kind : MaterialKind::all()) {
                // The extended kinds (unlit, layered) take the forward forms only (Material::needsForwardLighting),
                // with the atlas, in HDR in every tier and with one tone curve in the medium one: enough for the
                // shader checks to compile every #if of them, without multiplying the programs by every curve.
                if (kind.extended() && (deferred || layout != EnvironmentLayout::Atlas || toneMap > 0 ||
                                        (toneMap == 0 && (shading.quality != LightingQuality::Medium ||
                                                          shading.filteredFrom != kEnvironmentLevels))))
                  continue;
                if (kind.layered && layeredLightsPerDraw < 0) continue;
                const Form form{deferred, counting, toneMap, false, shading.quality, shading.filteredFrom, overDepth};
                if (readKind(form, kind) == kind)
                  specs.push_back(spec(form, kind, {}, layout, kind.layered ? layeredLightsPerDraw : lightsPerDraw));
              }
            }
          if (!deferred && !counting) specs.push_back(spec({false, false, toneMap, true}, {}, {}, layout, 0));
        }
      }
  for (VertexKind vertex : VertexKind::validated())
    specs.push_back(spec({false, false, -1, false}, {}, vertex, EnvironmentLayout::Atlas, lightsPerDraw));
  return specs;
}

LightingEffect::Variant::Variant(gl::Program built, bool geometryStage)
    : program(std::move(built)),
      geometry(geometryStage ? GeometryUniforms(program) : GeometryUniforms()),
      farHalfExtent(program.optionalUniform("u_farHalfExtent")),
      farPlane(program.optionalUniform("u_farPlane")),
      perspective(program.optionalUniform("u_perspective")),
      projection(program.optionalUniform("u_projection")),
      lightDirection(program.optionalUniform("u_lightDirection")),
      lightColor(program.optionalUniform("u_lightColor")),
      viewToEnvironment(program.optionalUniform("u_viewToEnvironment")),
      ao(program.optionalUniform("u_ao")),
      environment(program.optionalUniform("u_environment")),
      environmentFiltered(program.optionalUniform("u_environmentFiltered")),
      environmentFilteredScale(program.optionalUniform("u_environmentFilteredScale")),
      shIrradiance(program.optionalUniform("u_shIrradiance")),
      environmentIntensity(program.optionalUniform("u_environmentIntensity")),
      gbuffer(program.optionalUniform("u_gbuffer")),
      baseColor(program.optionalUniform("u_baseColor")),
      exposure(program.optionalUniform("u_exposure")),
      lumaInAlpha(program.optionalUniform("u_lumaInAlpha")),
      lightPositionRange(program.optionalUniform("u_lightPositionRange[0]")),
      lightColorSpot(program.optionalUniform("u_lightColorSpot[0]")),
      lightSpot(program.optionalUniform("u_lightSpot[0]")) {}

const LightingEffect::Variant& LightingEffect::variant(const Form& asked, MaterialKind kind, VertexKind vertex) {
  const Form form = programForm(asked);
  const bool fullscreen = form.deferred || form.background;
  MaterialKind read = readKind(form, kind);
  // A context whose fragment uniform vectors do not hold the layers draws the core material (kMaterialLayerVectors).
  read.layered = read.layered && layeredLightsPerDraw_ >= 0;
  const auto key = std::make_tuple(form, read, fullscreen ? VertexKind{} : vertex.forCurrentFrame());
  auto it = variants_.find(key);
  if (it == variants_.end()) {
    const int lights = std::get<1>(key).layered ? layeredLightsPerDraw_ : lightsPerDraw_;
    it = variants_
             .emplace(key, Variant(resources_.build(spec(form, std::get<1>(key), std::get<2>(key), layout_, lights)),
                                   !fullscreen))
             .first;
    it->second.lights = fullscreen ? 0 : lights;
    // Resolve strictly what this form must use, so a misspelt or dropped uniform is caught where it matters.
    const gl::Program& program = it->second.program;
    // An unlit material reads no light (KHR_materials_unlit).
    const bool lit = !form.counting && !std::get<1>(key).unlit;
    if (!fullscreen) program.uniform("u_projection");
    if (lit)
      for (const char* name : {"u_viewToEnvironment", "u_environmentIntensity"}) program.uniform(name);
    // The deferred shading alone (roughness 1: level 5) reads no level by hand where level 5 is filtered, and the
    // low tier none at all; every other form reads level 0 at least (its background, or a smooth material).
    const bool readsByHand = form.background || (lit && form.quality != LightingQuality::Low &&
                                                 !(form.overDepth && form.filteredFrom < kEnvironmentLevels));
    if (readsByHand) program.uniform("u_environment");
    if (fullscreen && !form.counting)
      for (const char* name : {"u_farHalfExtent", "u_farPlane"}) program.uniform(name);
    if (lit && !form.background)
      for (const char* name : {"u_lightDirection", "u_lightColor", "u_ao", "u_shIrradiance"}) program.uniform(name);
    if (lit && !form.background && form.quality != LightingQuality::Low) program.uniform("u_environmentFiltered");
    if (lit && !form.background && form.filteredFrom < kEnvironmentLevels)
      program.uniform("u_environmentFilteredScale");
    if (form.deferred) program.uniform("u_gbuffer");
    if (form.deferred && !form.counting) program.uniform("u_baseColor");
    if (!fullscreen && lit)
      for (const char* name : {"u_metallicRoughness", "u_emissive"}) program.uniform(name);
    if (!fullscreen && lit && lights > 0) program.uniform("u_lightPositionRange[0]");
    if (!fullscreen && lit && std::get<1>(key).layered)
      for (const char* name : {"u_specular", "u_clearcoat", "u_clearcoatRoughness"}) program.uniform(name);
    if (form.toneMap >= 0)
      for (const char* name : {"u_exposure", "u_lumaInAlpha"}) program.uniform(name);
  }
  return it->second;
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
      white_(1, 1, GL_NEAREST, std::vector<std::uint8_t>{255, 255, 255, 255}.data()),
      stencil_(resources.caps.packedDepthStencil),
      layout_(GpuEnvironment::layoutFor(resources.caps, resources.options.environmentLayout)),
      lightsPerDraw_(punctualLightsPerDraw(resources.caps.maxFragmentUniformVectors)),
      layeredLightsPerDraw_(punctualLightsPerDraw(resources.caps.maxFragmentUniformVectors, true)),
      environmentFilteredUnit_(TextureUnits::environmentFiltered(resources.caps)),
      drawBuffers_(resources.caps.drawBuffers && resources.options.allowDrawBuffers),
      environments_(layout_, resources.options.environmentFiltering) {
  const HdrTexel t = encodeHdr(light_.background);
  backgroundHdr_ = glm::vec4(LinearDepthPacking::channelFromByte(t[0]), LinearDepthPacking::channelFromByte(t[1]),
                             LinearDepthPacking::channelFromByte(t[2]), LinearDepthPacking::channelFromByte(t[3]));
  // The variants are built on first use, as the G-buffer's are (GBufferEffect.cpp): building every material's here
  // cost the page's start-up a program each (docs/resolution.md, "Start-up").
  environments_.use("sky", LightingSettings{}.directionToSun());
}

void LightingEffect::plan(FramePlanner& planner) {
  using Write = PassDecl::Write;
  std::vector<std::string> reads;
  if (planner.declares("ao")) reads.push_back("ao");
  const ToneMapInUse tone = ToneMapInUse::of(planner.settings().of<TonemapSettings>());
  const int op = static_cast<int>(tone.op);
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> all = reads;
    for (std::string& target : more)
      if (std::find(all.begin(), all.end(), target) == all.end()) all.push_back(std::move(target));
    return all;
  };
  // The G-buffer's depth also when nothing else needs the G-buffer, where that is the cheaper (LightingDepth).
  const LightingSettings& lighting = planner.settings().of<LightingSettings>();
  const bool deferredForm = drawBuffers_ && !planner.frame().forwardLighting;
  if (lighting.depthInUse(deferredForm) == LightingDepth::GBuffer) reads.push_back("gbuffer");
  auto runAs = [this, scale = tone.exposureScale](Form form, std::string output) {
    return [this, form, output, scale](PassContext& context) { render(context, form, output, scale); };
  };

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
    pass.run = runAs({false, counting, -1, false}, output);
    using Alternative = PassDecl::Alternative;
    if (counting) {
      pass.alternatives.push_back(Alternative{{"base-color"}, "", false, {"gbuffer"},
                                              {{output, TargetSize::full(), Write::Depth::None, ""}},
                                              runAs({true, true, -1, false}, output)});
    } else {
      const std::vector<Write> toDisplay = {{"display-color", TargetSize::full(), Write::Depth::None, ""}};
      const std::vector<Write> toDisplayShared = {
          {"display-color", TargetSize::full(), Write::Depth::Shared, "gbuffer"}};
      const std::vector<Write> toDisplayOwn = {{"display-color", TargetSize::full(), Write::Depth::Own, ""}};
      // Best first: deferred and tone-mapped (over the G-buffer's depth where a pass reads the display colour after
      // it; into the output framebuffer, which has no depth, with the background in the same program), deferred,
      // forward and tone-mapped (with the G-buffer's depth, or its own); else the pass as declared.
      pass.alternatives = {
          Alternative{{"base-color"}, "tonemap", false, with({"gbuffer", "base-color"}), toDisplayShared,
                      runAs({true, false, op, false, LightingQuality::Medium, kEnvironmentLevels, true},
                            "display-color")},
          Alternative{{"base-color"}, "tonemap", true, with({"gbuffer", "base-color"}), toDisplay,
                      runAs({true, false, op, false}, "display-color")},
          Alternative{{"base-color"}, "", false, with({"gbuffer", "base-color"}),
                      {{output, TargetSize::full(), Write::Depth::Shared, "gbuffer"}},
                      runAs({true, false, -1, false, LightingQuality::Medium, kEnvironmentLevels, true}, output)},
          Alternative{{"gbuffer"}, "tonemap", false, with({"gbuffer"}), toDisplayShared,
                      runAs({false, false, op, false}, "display-color")},
          Alternative{{}, "tonemap", false, reads, toDisplayOwn, runAs({false, false, op, false}, "display-color")},
      };
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

void LightingEffect::render(const PassContext& context, Form form, const std::string& output, float exposureScale) {
  using gl::Program;
  const LightingSettings& settings = context.settings().of<LightingSettings>();
  const FrameCamera& camera = context.camera();
  const GpuEnvironment& environment = environments_.current();
  // The tier and the environment's storage are read now, not when the plan was made: neither changes its shape.
  form.quality = settings.quality;
  form.filteredFrom = environment.filteredFrom();
  context.bindForWriting(output);
  const bool lumaInAlpha = !context.writesOutput(output);
  const ToneMapInUse tone{static_cast<ToneMapOperator>(std::max(form.toneMap, 0)), exposureScale};

  const glm::mat3 viewRotation(camera.view);
  const Sun sun = Sun::of(settings, context.scene().lights());
  const glm::vec3 lightDirection = glm::normalize(viewRotation * sun.directionToSun);
  const glm::mat3 viewToWorld = glm::transpose(viewRotation);  // the view's rotation is orthonormal
  const glm::mat3 viewToEnvironment = environmentRotation(settings) * viewToWorld;
  const bool fullscreen = form.deferred || form.background;
  const PunctualLightUniforms lights =
      fullscreen ? PunctualLightUniforms{}
                 : PunctualLightUniforms::of(context.scene().lights(), camera.view, lightsPerDraw_, sun.fileLight);
  if (!form.counting) publish(context, sun, lightDirection, viewToEnvironment, settings);
  // The texture units: gpu/TextureUnits.h.
  const int kEnvironmentUnit = TextureUnits::kEnvironment;
  const int kEnvironmentFilteredUnit = environmentFilteredUnit_;
  auto setShading = [&](const Variant& v) {
    if (form.counting) return;
    Program::set(v.lightDirection, lightDirection);
    Program::set(v.lightColor, sun.illuminance);
    Program::set(v.viewToEnvironment, viewToEnvironment);
    if (v.lightPositionRange >= 0) {
      glUniform4fv(v.lightPositionRange, v.lights, &lights.positionRange[0].x);
      glUniform4fv(v.lightColorSpot, v.lights, &lights.colorSpot[0].x);
      glUniform4fv(v.lightSpot, v.lights, &lights.spot[0].x);
    }
    Program::set(v.ao, TextureUnits::kAo);
    Program::set(v.environment, kEnvironmentUnit);
    Program::set(v.environmentFiltered, kEnvironmentFilteredUnit);
    Program::set(v.environmentFilteredScale, environment.filteredScale() * settings.environmentIntensity);
    Program::set(v.farHalfExtent, camera.reconstruction.farHalfExtent);
    Program::set(v.farPlane, camera.reconstruction.far);
    Program::set(v.perspective, camera.reconstruction.perspective ? 1.0f : 0.0f);
    Program::set(v.shIrradiance, environment.irradianceUniform().data(), 7);
    Program::set(v.environmentIntensity, settings.environmentIntensity);
    Program::set(v.exposure, exposureScale);
    Program::set(v.lumaInAlpha, lumaInAlpha ? 1.0f : 0.0f);
  };
  (context.has("ao") ? context.texture("ao") : white_).bind(TextureUnits::kAo);
  if (!form.counting) {
    glActiveTexture(GL_TEXTURE0 + kEnvironmentFilteredUnit);
    glBindTexture(GL_TEXTURE_2D, environment.filteredTexture());
    glActiveTexture(GL_TEXTURE0 + kEnvironmentUnit);
    glBindTexture(GL_TEXTURE_2D, environment.texture());
  }
  // The background: the environment where the depth is still 1 (nothing drawn), a full-screen triangle on the far
  // plane tested LEQUAL against it, writing no depth.
  auto drawBackground = [&] {
    const Variant& v = variant({false, false, form.toneMap, true}, {}, {});
    v.program.use();
    setShading(v);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    resources_.triangle.draw();
  };

  if (form.deferred) {
    // Every pixel once, background included. Over the G-buffer's depth (form.overDepth): the shading where the
    // depth is nearer than the far plane (a triangle on the far plane, tested GL_GREATER), then the background where
    // it is not; else one program for both, which tells the background by the G-buffer's depth code.
    form.overDepth = form.overDepth && !form.counting && context.sharesDepth(output);
    if (form.counting) {
      glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
      glClear(GL_COLOR_BUFFER_BIT);
    }
    const Variant& v = variant(form, {}, {});
    v.program.use();
    setShading(v);
    context.texture("gbuffer").bind(TextureUnits::kBaseColor);
    Program::set(v.gbuffer, TextureUnits::kBaseColor);
    if (!form.counting) {
      context.texture("base-color").bind(TextureUnits::kPbr[0]);
      Program::set(v.baseColor, TextureUnits::kPbr[0]);
    }
    if (form.counting) {
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
    }
    if (form.overDepth) {
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_GREATER);
      glDepthMask(GL_FALSE);
    }
    resources_.triangle.draw();
    if (form.overDepth) drawBackground();
    gl::restoreBaselineState();
    return;
  }

  if (form.counting) {
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  } else {
    // Where no geometry is, the background's radiance, encoded as the lit pixels are.
    const glm::vec4 clear = form.toneMap >= 0 ? tone.displayColor(light_.background, lumaInAlpha) : backgroundHdr_;
    glClearColor(clear.r, clear.g, clear.b, clear.a);
  }
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
    const Form depthOnly{false, true, -1, false};
    context.scene().draw(camera.view, [&](MaterialKind kind, VertexKind vertex) -> const GeometryUniforms& {
      const Variant& v = variant(depthOnly, kind, vertex);
      v.program.use();
      Program::set(v.projection, camera.projection);
      return v.geometry;
    });
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }
  const bool overDepth = context.sharesDepth(output) || prepass;
  if (overDepth && stencil_) {
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
  context.scene().draw(camera.view, [&](MaterialKind kind, VertexKind vertex) -> const GeometryUniforms& {
    const Variant& v = variant(form, kind, vertex);
    v.program.use();
    Program::set(v.projection, camera.projection);
    setShading(v);
    return v.geometry;
  });
  if (!form.counting) drawBackground();
  gl::restoreBaselineState();
}

}  // namespace obscura
