#pragma once
// The transparent layer (glTF alphaMode BLEND, and KHR_materials_transmission): the surfaces the opaque frame leaves
// out (Material::transparent: not in the G-buffer, so not in the AO, the velocity, DoF, motion blur, TAA or the
// edges), drawn after it, each lit as the lighting pass lit the opaque layer (the BLENDED form of
// lighting/lighting.frag: PBR, the environment, the sun, the punctual lights, the material's extensions; no
// screen-space AO) and fogged by its own distance, then composited over what lies behind it in linear HDR colour:
// c = a c_s + (1 - a) c_behind, straight alpha as glTF defines BLEND (shaders_es2/transparency/composite.glsl).
//
// Where it runs: after the lighting, the points and lines and the fog, before TAA, bloom and the tone mapping. Its
// colour is linear HDR, so highlights on glass are tone-mapped and bloom with the rest; it composites over the
// fogged opaque frame and fogs each surface by its own distance, which for exponential fog is exactly the fog of
// the whole path (f(d_p) f(d_w - d_p) = f(d_w): docs/transparency.md); TAA and bloom then treat the composite as any
// colour (TAA reprojects it with the opaque layer's motion: a moving pane trails, documented there).
//
// How (RGB9E5 colour cannot be blended by the hardware: docs/architecture.md): the pass copies the opaque frame into
// its target (glCopyTexSubImage2D, byte-exact), then draws the transparent instances back to front (GpuScene::
// transparentBatches: per instance, by its bounds' centre; a double-sided material's back faces before its front
// faces), depth-tested against the opaque layer's depth (the G-buffer's renderbuffer) without writing depth. The
// draws go in batches whose pixel rectangles do not overlap: before each batch the target's pixels under it are
// copied into the `behind` texture, and each fragment reads what lies behind it there, decodes it, composites and
// encodes. Overlapping transparent surfaces are therefore composited in order, exactly, from either side.
//
// Transmission (KHR_materials_transmission, thin-walled): a pass "transmission-levels" first halves the opaque frame
// TRANSMISSION_LEVELS times (box filtered in decoded colour) into the same `behind` texture beside the copy, and a
// transmissive fragment reads what shows through it at the blur its roughness asks for (the sample viewer's
// log2(width) x roughness x clamp(2 ior - 2, 0, 1), up to the last level), its Fresnel from the ior.
//
// One switch, `transparency` (on): off leaves the transparent layer out of the frame (the split view compares).
#include <map>
#include <tuple>
#include <vector>

#include "environment/Environment.h"
#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"
#include "gl/RenderTarget.h"
#include "gpu/GpuScene.h"

namespace obscura {

struct TransparencySettings : ParameterAccess<TransparencySettings> {
  bool enabled = true;
  static const std::vector<Parameter<TransparencySettings>>& parameters();
  void validate() const { validateParameters("transparency"); }
};

// The blurred levels transmission reads: each half the one before, 1/2 .. 1/64 of the frame.
inline constexpr int kTransmissionLevels = 6;

// What the transparent layer's programs take from a context's fragment uniform vectors, as GLSL ES 1.00 packs them
// (GLES 2 guarantees 16): the heaviest program (every PBR texture, transmission) without the material layers, fog
// and punctual lights needs kTransparentVectors, 16; the layers (KHR_materials_specular, _ior, _clearcoat) add
// kTransparentLayerVectors, the fog (its colour, factors and height terms) kTransparentFogVectors, the environment's
// rough levels through the hardware's filter (their RGBM scale: lib/environment.glsl) kTransparentFilteredVectors
// (none with the fog, whose last row has room for it), each light 3. TransparencyEffect::budget spends a context's vectors in that order of need: the fog first (a surface
// unfogged in a foggy frame stands out most), then the layers, then the filtered levels (without them the same
// levels are read by hand: the same light, dearer), then the lights.
// Shaders.EveryProgramFitsTheGles2UniformVectors holds these figures.
inline constexpr int kTransparentVectors = 16;
inline constexpr int kTransparentLayerVectors = 2;
inline constexpr int kTransparentFogVectors = 3;
inline constexpr int kTransparentFilteredVectors = 1;

// What a context can give the transparent layer (TransparencyEffect::budget).
struct TransparentBudget {
  bool fog = false;     // each surface fogged by its own distance (else it shows only the fog behind it)
  bool layers = false;  // the material layers (else a layered material is drawn as the core one)
  bool filtered = false;  // the environment's filtered levels (else every level read by hand)
  int lights = 0;       // punctual lights per draw
};

class TransparencyEffect : public Effect {
 public:
  using Settings = TransparencySettings;
  static constexpr bool kHasSwitch = true;
  static EffectInfo info();
  // Every program of the layer: for the shader checks, at the budget a context of `fragmentVectors` gives.
  static std::vector<ProgramSpec> programSpecs(int fragmentVectors = 1 << 12);
  static TransparentBudget budget(int fragmentVectors);

  explicit TransparencyEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;

 private:
  // A program's fog: none, or lib/fog.glsl's mode and height term.
  struct FogKey {
    bool on = false;
    int mode = 1;
    bool height = false;
    auto key() const { return std::tie(on, mode, height); }
    bool operator<(const FogKey& o) const { return key() < o.key(); }
  };
  // A program's shading, as the lighting pass shades this frame (SurfaceLight): its tier (LIGHTING_QUALITY) and the
  // environment's first level read through the hardware's filter (ENVIRONMENT_FILTERED_FROM).
  struct ShadingKey {
    int quality = 1;
    int filteredFrom = kEnvironmentLevels;
    auto key() const { return std::tie(quality, filteredFrom); }
    bool operator<(const ShadingKey& o) const { return key() < o.key(); }
  };
  struct Variant {
    explicit Variant(gl::Program built);
    gl::Program program;
    GLint projection, lightDirection, lightColor, viewToEnvironment, environment, environmentFiltered;
    GLint environmentFilteredScale, shIrradiance;
    GLint environmentIntensity, lightPositionRange, lightColorSpot, lightSpot, behind, behindLayout;
    GLint fogColor, fogFactor, falloff, heightScale, upInView, perspective;
  };
  static ProgramSpec spec(MaterialKind kind, VertexKind vertex, FogKey fog, ShadingKey shading,
                          EnvironmentLayout layout, int lights);
  const Variant& variant(MaterialKind kind, VertexKind vertex, FogKey fog, ShadingKey shading);
  // The `behind` texture for frames of this size: the copy's [0, W) x [0, H), then the levels beside it.
  void fitBehind(glm::ivec2 size);
  void renderLevels(const PassContext& context);
  void renderLayer(const PassContext& context);

  const EffectResources& resources_;
  TransparentBudget budget_;
  EnvironmentLayout layout_;
  std::map<std::tuple<MaterialKind, VertexKind, FogKey, ShadingKey>, Variant> variants_;
  gl::Program levelsProgram_;
  GLint levelsSource_, levelsSourceRect_, levelsSourceSize_, levelsTargetOrigin_;
  gl::Texture2D behind_;
  glm::ivec2 frameSize_{0}, padded_{0};  // W x H, and W' x H' (multiples of 2^kTransmissionLevels)
  std::vector<gl::RenderTarget> levels_;  // level k at [k - 1], (W' / 2^k) x (H' / 2^k)
  gl::FramebufferHandle sourceFramebuffer_;  // the opaque frame attached, to copy it
};

}  // namespace obscura
