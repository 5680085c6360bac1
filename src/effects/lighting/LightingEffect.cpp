#include "effects/lighting/LightingEffect.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "base/Error.h"
#include "encoding/HdrEncoding.h"
#include "encoding/LinearDepthPacking.h"
#include "environment/BuiltinSky.h"
#include "frame/PassContext.h"
#include "gl/PipelineState.h"
#include "gpu/TextureUnits.h"

namespace obscura {

const std::vector<Parameter<LightingSettings>>& LightingSettings::parameters() {
  using S = LightingSettings;
  static const std::vector<Parameter<S>> table = {
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
  return table;
}

glm::vec3 LightingSettings::directionToSun() const { return sunDirection(sunElevation, sunAzimuth); }

PunctualLightUniforms PunctualLightUniforms::of(const std::vector<PunctualLight>& lights, const glm::mat4& view,
                                                int maxCount) {
  maxCount = std::clamp(maxCount, 0, kMaxPunctualLights);
  PunctualLightUniforms out;
  // The lights that light the camera's surroundings most: intensity / distance^2 at the camera (view-space origin).
  std::vector<std::pair<float, size_t>> order;
  for (size_t i = 0; i < lights.size(); ++i) {
    const glm::vec3 p(view * lights[i].world[3]);
    const glm::vec3& c = lights[i].color;
    order.emplace_back(-lights[i].intensity * std::max(c.r, std::max(c.g, c.b)) / std::max(glm::dot(p, p), 1e-6f), i);
  }
  std::stable_sort(order.begin(), order.end());
  for (const auto& [key, index] : order) {
    if (out.count == maxCount) break;
    const PunctualLight& light = lights[index];
    const auto k = static_cast<size_t>(out.count++);
    const glm::mat4 toView = view * light.world;
    const float range4 = light.range > 0.0f ? std::pow(light.range, 4.0f) : 0.0f;
    out.positionRange[k] = glm::vec4(glm::vec3(toView[3]), range4 > 0.0f ? 1.0f / range4 : 0.0f);
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

int LightingEffect::punctualLightsPerDraw(int maxFragmentUniformVectors) {
  return std::clamp((maxFragmentUniformVectors - kForwardLightingVectorsWithoutLights) / kVectorsPerPunctualLight, 0,
                    kMaxPunctualLights);
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

// The forms' programs. The background form is the deferred program's background alone, drawn over fullscreen.vert
// at the far plane (AT_FAR_PLANE).
ProgramSpec LightingEffect::spec(const Form& form, MaterialKind kind, VertexKind vertex, EnvironmentLayout layout,
                                 int lightsPerDraw) {
  const bool fullscreen = form.deferred || form.background;
  std::string name = "lighting[";
  if (form.background) name += "background";
  else if (form.deferred) name += "deferred";
  else name += "forward" + kind.nameSuffix() + vertex.nameSuffix();
  if (form.counting) name += ",count-shading";
  if (form.toneMap >= 0)
    name += std::string(",tonemap=") + toneMapOperatorName(static_cast<ToneMapOperator>(form.toneMap));
  if (!form.counting) name += std::string(",") + environmentLayoutName(layout);
  ProgramSpec s{name + "]", fullscreen ? "lib/fullscreen.vert" : "lib/geometry.vert", "lighting/lighting.frag",
                {{"DEFERRED", fullscreen ? "1" : "0"},
                 {"BACKGROUND", form.background ? "1" : "0"},
                 {"AT_FAR_PLANE", form.background ? "1" : "0"},
                 {"COUNT_SHADING", form.counting ? "1" : "0"},
                 {"TONEMAP_INLINE", form.toneMap >= 0 ? "1" : "0"},
                 {"MAX_PUNCTUAL_LIGHTS", std::to_string(fullscreen ? 0 : lightsPerDraw)},
                 // The deferred forms' view direction is the far-plane ray's.
                 {"FAR_RAY", fullscreen && !form.counting ? "1" : "0"}}};
  for (auto& define : GpuEnvironment::shaderDefines(layout)) s.defines.push_back(define);
  if (layout == EnvironmentLayout::MipChain && !form.counting) s.extensions.push_back("GL_EXT_shader_texture_lod");
  for (auto& define : kind.defines()) s.defines.push_back(define);
  if (!fullscreen)
    for (auto& define : vertex.defines()) s.defines.push_back(define);
  if (form.toneMap >= 0) s.defines.push_back(toneMapShaderDefine(static_cast<ToneMapOperator>(form.toneMap)));
  return s;
}

// Every form with the atlas (any GLES 2 context), and the shading forms again with the mip chain.
std::vector<ProgramSpec> LightingEffect::programSpecs(int lightsPerDraw) {
  std::vector<ProgramSpec> specs;
  for (EnvironmentLayout layout : {EnvironmentLayout::Atlas, EnvironmentLayout::MipChain})
    for (bool deferred : {false, true})
      for (bool counting : {true, false}) {
        if (counting && layout == EnvironmentLayout::MipChain) continue;
        for (int toneMap = -1; toneMap < (counting ? 0 : kToneMapOperatorCount); ++toneMap) {
          for (MaterialKind kind : MaterialKind::all()) {
            const Form form{deferred, counting, toneMap, false};
            if (readKind(form, kind) == kind) specs.push_back(spec(form, kind, {}, layout, lightsPerDraw));
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
      projection(program.optionalUniform("u_projection")),
      lightDirection(program.optionalUniform("u_lightDirection")),
      lightColor(program.optionalUniform("u_lightColor")),
      viewToEnvironment(program.optionalUniform("u_viewToEnvironment")),
      ao(program.optionalUniform("u_ao")),
      environment(program.optionalUniform("u_environment")),
      environmentBrdf(program.optionalUniform("u_environmentBrdf")),
      shIrradiance(program.optionalUniform("u_shIrradiance")),
      environmentIntensity(program.optionalUniform("u_environmentIntensity")),
      gbuffer(program.optionalUniform("u_gbuffer")),
      baseColor(program.optionalUniform("u_baseColor")),
      exposure(program.optionalUniform("u_exposure")),
      lumaInAlpha(program.optionalUniform("u_lumaInAlpha")),
      lightPositionRange(program.optionalUniform("u_lightPositionRange[0]")),
      lightColorSpot(program.optionalUniform("u_lightColorSpot[0]")),
      lightSpot(program.optionalUniform("u_lightSpot[0]")) {}

const LightingEffect::Variant& LightingEffect::variant(const Form& form, MaterialKind kind, VertexKind vertex) {
  const bool fullscreen = form.deferred || form.background;
  const auto key = std::make_tuple(form, readKind(form, kind), fullscreen ? VertexKind{} : vertex.forCurrentFrame());
  auto it = variants_.find(key);
  if (it == variants_.end()) {
    it = variants_
             .emplace(key, Variant(resources_.build(spec(form, std::get<1>(key), std::get<2>(key), layout_,
                                                         lightsPerDraw_)),
                                   !fullscreen))
             .first;
    // Resolve strictly what this form must use, so a misspelt or dropped uniform is caught where it matters.
    const gl::Program& program = it->second.program;
    if (!fullscreen) program.uniform("u_projection");
    if (!form.counting)
      for (const char* name : {"u_viewToEnvironment", "u_environment", "u_environmentIntensity"}) program.uniform(name);
    if (fullscreen && !form.counting)
      for (const char* name : {"u_farHalfExtent", "u_farPlane"}) program.uniform(name);
    if (!form.counting && !form.background)
      for (const char* name : {"u_lightDirection", "u_lightColor", "u_ao", "u_shIrradiance", "u_environmentBrdf"})
        program.uniform(name);
    if (form.deferred) program.uniform("u_gbuffer");
    if (form.deferred && !form.counting) program.uniform("u_baseColor");
    if (!fullscreen && !form.counting)
      for (const char* name : {"u_metallicRoughness", "u_emissive"}) program.uniform(name);
    if (!fullscreen && !form.counting && lightsPerDraw_ > 0) program.uniform("u_lightPositionRange[0]");
    if (form.toneMap >= 0)
      for (const char* name : {"u_exposure", "u_lumaInAlpha"}) program.uniform(name);
  }
  return it->second;
}

// A file that cannot be read is reported once (InputError: the command line stops, the page shows it) and the
// environment in use stays, so a stale path (a page's URL naming a file dropped in an earlier visit) does not fail
// every frame.
void LightingEffect::useEnvironment(const LightingSettings& settings) {
  const bool sky = settings.environment == "sky";
  if (environment_ && environmentName_ == settings.environment && (!sky || skyElevation_ == settings.sunElevation))
    return;
  const std::string name = settings.environment;
  environmentName_ = name;
  struct Prepared {
    PrefilteredEnvironment specular;
    ShIrradiance sh;
    explicit Prepared(const EnvironmentImage& image)
        : specular(PrefilteredEnvironment::of(image)), sh(ShIrradiance::project(image)) {}
    explicit Prepared(const PreparedEnvironment& made) : specular(made.specular), sh(made.irradiance) {}
  };
  // The built-in environments are prepared once per process: every Renderer starts with the sky, and its
  // prefiltering is the dearest part of making one.
  if (sky) {
    // The sky's sun stands where lighting.sun-* put the direct light. Its azimuth turns the sky about the vertical
    // (environmentRotation: free); its elevation changes the sky, which is made and prefiltered again (about a second
    // on this machine's CPU: LightingSettings marks sun-elevation slow, so the page applies it when a drag ends).
    LightingSettings defaults;
    static const Prepared defaultSky(builtinSky());  // prefiltered when the library was built
    skyElevation_ = settings.sunElevation;
    if (settings.sunElevation == defaults.sunElevation) {
      environment_ = std::make_unique<GpuEnvironment>(layout_, defaultSky.specular, defaultSky.sh);
      return;
    }
    defaults.sunElevation = settings.sunElevation;
    const Prepared raised(ProceduralSky{defaults.directionToSun()}.image(kEnvironmentWidth, kEnvironmentHeight));
    environment_ = std::make_unique<GpuEnvironment>(layout_, raised.specular, raised.sh);
    return;
  }
  if (name == "uniform") {
    static const Prepared furnace(uniformEnvironment(glm::vec3(1.0f)));
    environment_ = std::make_unique<GpuEnvironment>(layout_, furnace.specular, furnace.sh);
    return;
  }
  EnvironmentImage image;
  try {
    image = loadEnvironmentImage(name);
  } catch (const InputError&) {
    if (!environment_) useEnvironment(LightingSettings{});
    environmentName_ = name;
    throw;
  }
  const Prepared prepared(image);
  environment_ = std::make_unique<GpuEnvironment>(layout_, prepared.specular, prepared.sh);
}

LightingEffect::LightingEffect(const EffectResources& resources)
    : resources_(resources),
      white_(1, 1, GL_NEAREST, std::vector<std::uint8_t>{255, 255, 255, 255}.data()),
      stencil_(resources.caps.packedDepthStencil),
      layout_(GpuEnvironment::layoutFor(resources.caps, resources.options.environmentLayout)),
      lightsPerDraw_(punctualLightsPerDraw(resources.caps.maxFragmentUniformVectors)),
      environmentBrdfUnit_(TextureUnits::environmentBrdf(resources.caps)) {
  const HdrTexel t = encodeHdr(light_.background);
  backgroundHdr_ = glm::vec4(LinearDepthPacking::channelFromByte(t[0]), LinearDepthPacking::channelFromByte(t[1]),
                             LinearDepthPacking::channelFromByte(t[2]), LinearDepthPacking::channelFromByte(t[3]));
  // The variants are built on first use, as the G-buffer's are (GBufferEffect.cpp).
  useEnvironment(LightingSettings{});
}

void LightingEffect::plan(FramePlanner& planner) {
  using Write = PassDecl::Write;
  std::vector<std::string> reads;
  if (planner.declares("ao")) reads.push_back("ao");
  const ToneMapInUse tone = ToneMapInUse::of(planner.settings().of<TonemapSettings>());
  const int op = static_cast<int>(tone.op);
  const LightingSettings& lighting = planner.settings().of<LightingSettings>();
  useEnvironment(lighting);
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> all = reads;
    all.insert(all.end(), more.begin(), more.end());
    return all;
  };
  auto runAs = [this, scale = tone.exposureScale, lighting](Form form, std::string output) {
    return [this, form, output, scale, lighting](PassContext& context) {
      render(context, form, output, scale, lighting);
    };
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
      // Best first: deferred and tone-mapped, deferred, forward and tone-mapped (with the G-buffer's depth, or its
      // own); else the pass as declared.
      pass.alternatives = {
          Alternative{{"base-color"}, "tonemap", true, with({"gbuffer", "base-color"}), toDisplay,
                      runAs({true, false, op, false}, "display-color")},
          Alternative{{"base-color"}, "", false, with({"gbuffer", "base-color"}),
                      {{output, TargetSize::full(), Write::Depth::None, ""}}, runAs({true, false, -1, false}, output)},
          Alternative{{"gbuffer"}, "tonemap", false, with({"gbuffer"}), toDisplayShared,
                      runAs({false, false, op, false}, "display-color")},
          Alternative{{}, "tonemap", false, reads, toDisplayOwn, runAs({false, false, op, false}, "display-color")},
      };
    }
    planner.add(std::move(pass));
  }
}

void LightingEffect::render(const PassContext& context, const Form& form, const std::string& output,
                            float exposureScale, const LightingSettings& settings) {
  using gl::Program;
  const FrameCamera& camera = context.camera();
  context.bindForWriting(output);
  const bool lumaInAlpha = !context.writesOutput(output);
  const ToneMapInUse tone{static_cast<ToneMapOperator>(std::max(form.toneMap, 0)), exposureScale};

  const glm::mat3 viewRotation(camera.view);
  const glm::vec3 lightDirection = glm::normalize(viewRotation * settings.directionToSun());
  const glm::mat3 viewToWorld = glm::transpose(viewRotation);  // the view's rotation is orthonormal
  const glm::mat3 viewToEnvironment = environmentRotation(settings) * viewToWorld;
  const bool fullscreen = form.deferred || form.background;
  const PunctualLightUniforms lights =
      fullscreen ? PunctualLightUniforms{}
                 : PunctualLightUniforms::of(context.scene().lights(), camera.view, lightsPerDraw_);
  // The texture units: gpu/TextureUnits.h.
  const int kEnvironmentUnit = TextureUnits::kEnvironment;
  const int kEnvironmentBrdfUnit = environmentBrdfUnit_;
  auto setShading = [&](const Variant& v) {
    if (form.counting) return;
    Program::set(v.lightDirection, lightDirection);
    Program::set(v.lightColor, settings.sunColor * settings.sunIntensity);
    Program::set(v.viewToEnvironment, viewToEnvironment);
    if (v.lightPositionRange >= 0) {
      glUniform4fv(v.lightPositionRange, lightsPerDraw_, &lights.positionRange[0].x);
      glUniform4fv(v.lightColorSpot, lightsPerDraw_, &lights.colorSpot[0].x);
      glUniform4fv(v.lightSpot, lightsPerDraw_, &lights.spot[0].x);
    }
    Program::set(v.ao, TextureUnits::kAo);
    Program::set(v.environment, kEnvironmentUnit);
    Program::set(v.environmentBrdf, kEnvironmentBrdfUnit);
    Program::set(v.farHalfExtent, camera.reconstruction.farHalfExtent);
    Program::set(v.farPlane, camera.reconstruction.far);
    Program::set(v.shIrradiance, environment_->irradianceUniform().data(), 7);
    Program::set(v.environmentIntensity, settings.environmentIntensity);
    Program::set(v.exposure, exposureScale);
    Program::set(v.lumaInAlpha, lumaInAlpha ? 1.0f : 0.0f);
  };
  (context.has("ao") ? context.texture("ao") : white_).bind(TextureUnits::kAo);
  if (!form.counting) {
    glActiveTexture(GL_TEXTURE0 + kEnvironmentBrdfUnit);
    glBindTexture(GL_TEXTURE_2D, environment_->brdfTexture());
    glActiveTexture(GL_TEXTURE0 + kEnvironmentUnit);
    glBindTexture(GL_TEXTURE_2D, environment_->texture());
  }

  if (form.deferred) {
    // Every pixel once, background included: no clear, no depth.
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
    resources_.triangle.draw();
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
  if (context.sharesDepth(output) && stencil_) {
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
  } else if (context.sharesDepth(output)) {
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
  if (!form.counting) {
    // The background: the environment where the depth is still 1 (nothing drawn), a full-screen triangle on the far
    // plane tested LEQUAL against it, writing no depth.
    const Variant& v = variant({false, false, form.toneMap, true}, {}, {});
    v.program.use();
    setShading(v);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    resources_.triangle.draw();
  }
  gl::restoreBaselineState();
}

}  // namespace obscura
