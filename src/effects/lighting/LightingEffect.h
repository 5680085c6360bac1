#pragma once
// The lit image (shaders_es2/lighting/lighting.frag, lib/pbr.glsl, lib/material.glsl, lib/environment.glsl): glTF 2.0
// metallic-roughness materials shaded with Cook-Torrance (GGX distribution, height-correlated Smith visibility,
// Schlick Fresnel) over a Lambertian diffuse, under the sun (lighting.sun-*), up to kMaxPunctualLights
// KHR_lights_punctual point and spot lights and the image-based ambient light of environment/Environment.h (diffuse
// irradiance from spherical harmonics and a prefiltered specular environment, the built-in sky or an equirectangular
// image: lighting.environment), plus the material's emission. The AO darkens the ambient term only: its diffuse part
// directly, its specular part through Lagarde's specular occlusion; the material's baked occlusion texture combines
// with the screen-space AO by their minimum (measured: docs/pbr.md). Direct light is never darkened. Where no
// geometry is, the environment itself is seen. CPU mirror of the shading: effects/lighting/PbrShading.h. It writes
// linear HDR colour in the RGBA8 encoding of lib/hdr.glsl into "scene-color", which later effects read. The pass takes
// one of these forms, chosen once the frame's plan knows which passes run (PassDecl::Alternative):
//
//   deferred  where the G-buffer pass wrote the base colour beside the G-buffer (several render targets): a
//             full-screen pass reading the normal, the base colour and the AO. The scene is drawn once per frame.
//             The base-colour target carries nothing else, so the G-buffer writes it only where every material
//             drawn is a rough dielectric (metallic 0, roughness 1, no emission, no texture but the base colour's)
//             and the scene has no punctual light (GpuScene::needsForwardLighting): the deferred form shades
//             exactly those, and any other scene takes the forward form.
//   forward   otherwise: the scene drawn again with the G-buffer pass's vertex shader text. When the G-buffer pass
//             runs it shares its depth renderbuffer: both compute the same depths (gl_Position invariant), so
//             GL_EQUAL, and a stencil test passing only the first fragment per pixel, shade each pixel once however
//             much the scene overlaps itself, coplanar and edge-on faces included. Without packed depth + stencil
//             (core GLES 2 without OES_packed_depth_stencil), GL_LESS against the depth pulled one resolvable step
//             nearer, writing depth, does nearly as well (tests/test_pipeline.cpp measures both). Without the
//             G-buffer (no effect reads it: the AO off) it clears and tests a depth buffer of its own, and pays for
//             the overdraw drawing front to back leaves. Then a full-screen triangle on the far plane draws the
//             environment where the depth is still 1 (the background; the deferred form shades it in its one pass).
//   either, tone-mapped: when the tone-mapping pass is the only reader of the HDR colour (no effect works on it in
//             between, no view shows it), the lighting applies the tone mapping itself (ToneMapInUse: exposure,
//             curve, sRGB, luma in alpha) and writes "display-color": a full-screen pass and an HDR encode and
//             decode fewer (the per-pixel stages after the lighting fuse into it: frame/Stage.h). The forward form
//             draws into the output framebuffer only where the output has a depth buffer of its own and the G-buffer
//             pass does not run (StageHead::mayWriteOutput, keepsSharedDepth); else a pass after it does.
//
// Its second target, "shading-count", is a diagnostic: the same pass with the same reads and depth set-up, counting
// how many fragments each pixel shaded (additive blending of 1/255) instead of shading them; the view
// "shading-count" shows 1 as grey 32/255. The tests read it to hold the once-per-pixel promise.
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <glm/vec3.hpp>

#include "environment/Environment.h"
#include "environment/EnvironmentCache.h"
#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"
#include "gl/RenderTarget.h"
#include "gpu/GpuScene.h"

namespace obscura {

// How much of the shading a pixel pays for (lighting.quality; the frame's preset sets it: low -> low, medium ->
// medium, high and ultra -> high). docs/lighting.md measures each tier's cost and its error against high.
//   low     the ambient from the spherical harmonics alone: diffuse E(n) / pi, and the specular as the irradiance
//           towards the reflected direction weighted by Karis's analytic (A, B) fit; no environment or table fetch,
//           the AO on both alike. The sun and the punctual lights keep their Cook-Torrance lobe.
//   medium  the split sum: the prefiltered environment and the (A, B) table, Lagarde's specular occlusion. (The
//           deferred form shades roughness 1 alone, where the prefiltered radiance is the irradiance towards the
//           reflection: it evaluates that instead of reading level 5.)
//   high    medium, plus the energy the single-scattering lobe loses: multiple scattering in the ambient
//           (Fdez-Aguera 2019) and the direct lights' energy compensation (Kulla & Conty 2017, as Filament), and the
//           reflection's horizon occlusion where a normal texture tilts it below the surface (Russell 2015).
enum class LightingQuality { Low = 0, Medium = 1, High = 2 };

// Where the lighting finds each pixel's visible surface when no other effect draws the G-buffer (the AO off, and no
// fog, DoF, edges, TAA or motion blur). With the G-buffer, every form shades each pixel once: the deferred form by
// construction, the forward form by testing GL_EQUAL against the G-buffer's depth.
//   gbuffer   the G-buffer pass runs anyway: the deferred form where it can shade the scene, else the forward form
//             over its depth.
//   prepass   the forward form draws the scene's depth first (colour writes off, the counting form's trivial
//             fragment stage), then shades over it as over the G-buffer's: two geometry draws, one shading per pixel.
//   overdraw  the forward form tests its own depth, shading every fragment that is nearer than those drawn before it
//             (front to back: GpuScene's order).
//   auto      gbuffer where the deferred form can shade the scene (one geometry pass and a full-screen one), in
//             every tier; else the medium and high tiers take prepass (two geometry passes, the first with no
//             colour to write, where the G-buffer's would write its normals too) and the low tier, whose shading
//             costs about what a depth test saves, overdraw (one geometry pass). Measured on 2CylinderEngine with
//             `preset low` and the AO off (docs/benchmarks.md, issue 26): on SwiftShader, the page's rasteriser,
//             gbuffer costs 0.67 to 0.70 of overdraw: a dense mesh's small triangles shade whole 2 x 2 quads for a
//             pixel or two, which the full-screen pass does not; llvmpipe, which shades every pixel of a full-screen
//             pass at the full cost, measures the opposite (1.2 to 1.4 x); set overdraw there.
enum class LightingDepth { Auto, GBuffer, Prepass, Overdraw };

// The sun: an overcast key light over a strong sky dome, so that ambient carries most of the light and AO reads
// clearly. Its illuminance is colour x intensity; the default intensity pi makes a white Lambertian surface facing it
// reflect its colour, as the lighting did before the BRDF had its 1 / pi.
// Where the sun comes from: lighting.sun-* (the renderer's own), or the file's first KHR_lights_punctual directional
// light (its direction and colour x intensity; the renderer's sun where the file has none).
enum class SunSource { Settings, File };

struct LightingSettings : ParameterAccess<LightingSettings> {
  SunSource sun = SunSource::Settings;
  LightingQuality quality = LightingQuality::Medium;
  QualityPreset preset = QualityPreset::Medium;  // the frame preset `quality` came from (applyPreset)
  LightingDepth depth = LightingDepth::Auto;
  // What `depth` resolves to with these settings, in a frame whose lighting can take the deferred form or not.
  LightingDepth depthInUse(bool deferredForm) const;
  float sunElevation = kBuiltinSunElevation;  // degrees above the horizon (world +y up)
  float sunAzimuth = kBuiltinSunAzimuth;      // degrees from +z towards +x
  glm::vec3 sunColor{0.50f, 0.48f, 0.44f};  // linear
  float sunIntensity = 3.14159265f;         // lux per unit of colour
  // "sky": the built-in ProceduralSky; "uniform": radiance 1 from every direction (the white furnace); else the path
  // of an equirectangular .hdr, or a PNG of RGBE bytes (loadEnvironmentImage).
  std::string environment = "sky";
  float environmentIntensity = 1.0f;  // scales the environment's radiance: ambient light and background

  glm::vec3 directionToSun() const;  // world space, unit (lighting.sun-*)
  static const std::vector<Parameter<LightingSettings>>& parameters();
  void applyPreset(QualityPreset which);
  bool matchesPreset(QualityPreset which) const;
  void validate() const { validateParameters("lighting"); }
};

// KHR_lights_punctual lights per draw: the forward lighting's loop bound (MAX_PUNCTUAL_LIGHTS), at most
// kMaxPunctualLights, as many as the context's fragment uniform vectors hold (LightingEffect::punctualLightsPerDraw).
// A frame with more lights takes, for every draw, those that light the camera's surroundings most (the largest
// intensity / distance^2 at the camera).
inline constexpr int kMaxPunctualLights = 4;
// The fragment uniform vectors of the heaviest forward lighting program without punctual lights, as GLSL ES 1.00
// packs them (Appendix A, section 7: gl/UniformPacking.h), and what each light adds (three vec4).
// Shaders.EveryProgramFitsTheGles2UniformVectors (tests/test_shaders.cpp) packs every program the renderer builds
// and holds these figures.
inline constexpr int kForwardLightingVectorsWithoutLights = 15;
// What the material layers (KHR_materials_specular, _ior, _clearcoat: MaterialKind::layered) add to it: their
// programs take (maxFragmentUniformVectors - 17) / 3 lights. At GLES 2's minimum of 16 vectors their heaviest form
// (alpha mask, tone curve inline) does not fit: such a context draws layered materials as the core material.
inline constexpr int kMaterialLayerVectors = 2;
inline constexpr int kVectorsPerPunctualLight = 3;
// What the forms keep for themselves, before any per-pixel stage fuses into them (frame/Stage.h: the stages get the
// rest): the forward form's the same 15 (the tone-mapping stage's two floats take spare columns), the deferred
// form's 14.
inline constexpr int kForwardLightingVectorsWithoutStages = 15;
inline constexpr int kDeferredLightingVectorsWithoutStages = 14;

// The sun of a frame: its world direction (towards it, unit) and illuminance, from the settings or, with lighting.sun
// file, from the scene's first directional light (`fileLight` its index in the lights, which then light the scene
// as the sun only; -1: none taken).
struct Sun {
  glm::vec3 directionToSun{0.0f, 1.0f, 0.0f};
  glm::vec3 illuminance{0.0f};
  int fileLight = -1;
  static Sun of(const LightingSettings& settings, const std::vector<PunctualLight>& lights);
};

// The view-space uniforms of the punctual lights (lighting.frag), derived once per frame on the CPU.
struct PunctualLightUniforms {
  glm::vec4 positionRange[kMaxPunctualLights]{};  // xyz position, w 1 / range^4 (0: no range; -1: directional,
                                                  // xyz the unit direction towards it)
  glm::vec4 colorSpot[kMaxPunctualLights]{};      // rgb colour x intensity, a the cone's scale
  glm::vec4 spot[kMaxPunctualLights]{};           // xyz the spot's direction, w the cone's offset
  int count = 0;
  // The first maxCount (at most kMaxPunctualLights) by that order; `skip`: a light the sun already is (Sun).
  static PunctualLightUniforms of(const std::vector<PunctualLight>& lights, const glm::mat4& view, int maxCount,
                                  int skip = -1);
};

class LightingEffect : public Effect {
 public:
  using Settings = LightingSettings;
  static constexpr bool kHasSwitch = false;
  static EffectInfo info();
  // Every variant, the forward ones with lightsPerDraw punctual lights (the layered ones with layeredLightsPerDraw,
  // by default as many; none where it is negative: their programs do not fit, punctualLightsPerDraw).
  static std::vector<ProgramSpec> programSpecs(int lightsPerDraw = kMaxPunctualLights,
                                               std::optional<int> layeredLightsPerDraw = std::nullopt);
  // The programs per-pixel stages fuse into (frame/EffectEntry.h: StageHeadSpec), for the shader checks: the
  // deferred form, the background, the forward form of the plainest and of the heaviest material, and of the heaviest
  // layered one (with the atlas, and `lightsPerDraw` punctual lights).
  static std::vector<StageHeadSpec> stageHeads(int lightsPerDraw = 0);
  // The punctual lights per draw a context of this many fragment uniform vectors holds: 4 from 27 vectors, 0 at
  // GLES 2's minimum of 16 (the sun and the environment still light the scene); for the layered materials' programs
  // 4 from 29, and -1 below 17 (they do not fit).
  static int punctualLightsPerDraw(int maxFragmentUniformVectors, bool layered = false);
  // World directions to the environment's: for the sky, the turn about +y that puts its sun at lighting.sun-azimuth;
  // else the identity.
  static glm::mat3 environmentRotation(const LightingSettings& settings);

  explicit LightingEffect(const EffectResources& resources);
  // Loads and prepares the environment lighting.environment names (and, for the sky, lighting.sun-elevation).
  void prepare(const FrameSettings& settings) override;
  void plan(FramePlanner& planner) override;

 private:
  // One form of the pass: deferred or forward, counting or shading (the per-pixel stages fused into it: PassContext).
  // background: the forward forms' full-screen draw of the environment where the scene drew nothing.
  // quality and filteredFrom (the environment's GpuEnvironment::filteredFrom) matter to the shading forms only.
  struct Form {
    bool deferred = false;
    bool counting = false;
    bool background = false;
    LightingQuality quality = LightingQuality::Medium;
    int filteredFrom = kEnvironmentLevels;
    bool operator<(const Form& o) const {
      return std::tie(deferred, counting, background, quality, filteredFrom) <
             std::tie(o.deferred, o.counting, o.background, o.quality, o.filteredFrom);
    }
  };
  static MaterialKind readKind(const Form& form, MaterialKind kind);
  // The form as its program sees it: what a counting or background form does not read is left at its default.
  static Form programForm(Form form);
  static ProgramSpec spec(const Form& form, MaterialKind kind, VertexKind vertex, EnvironmentLayout layout,
                          int lightsPerDraw);
  static ProgramSpec withoutStages(ProgramSpec head);
  // The program of a form for a material and vertex kind, with the per-pixel stages fused into the pass (`chain`:
  // their names, the key).
  const gl::Program& program(const Form& form, MaterialKind kind, VertexKind vertex,
                             const std::vector<StageDecl>& stages, const std::string& chain) const;
  void render(const PassContext& context, Form form) const;
  void publish(const PassContext& context, const Sun& sun, const glm::vec3& lightDirection,
               const glm::mat3& viewToEnvironment, const LightingSettings& settings) const;

  const EffectResources& resources_;
  // Built on first use: (form, the material kind it reads, the vertex kind, the fused stages).
  ProgramVariants<std::tuple<Form, MaterialKind, VertexKind, std::string>> programs_;
  gl::Texture2D white_;  // AO = 1 when the AO is off
  bool stencil_;         // the G-buffer's depth has stencil bits (RenderTargetPool): shade exactly once
  EnvironmentLayout layout_;              // where the prefiltered levels live (RendererOptions::environmentLayout)
  int lightsPerDraw_;                     // punctualLightsPerDraw of the context's fragment uniform vectors
  int layeredLightsPerDraw_;              // the same for the layered materials' programs
  int environmentFilteredUnit_;           // TextureUnits::environmentFiltered
  bool drawBuffers_;                      // the G-buffer pass writes the base colour (GBufferEffect's same test)
  EnvironmentCache environments_;         // the environment in use (lighting.environment), prepared before planning
};

}  // namespace obscura
