#pragma once
// The lit image: the scene drawn again with the G-buffer's vertex stage (shaders_es2/lighting.frag), base colour under
// one directional light and a sky/ground hemisphere ambient; the AO multiplies the ambient term only. It writes
// linear HDR colour in the RGBA8 HDR encoding (lib/hdr.glsl) into "scene-color", which later effects read.
//
// When the G-buffer pass runs, the lighting pass shares its depth renderbuffer and tests against it: both passes run
// the same vertex shader text on the same uniforms with gl_Position invariant, so they compute the same depths.
// GL_EQUAL against that depth, and a stencil test passing only the first fragment per pixel, shade each pixel once
// however much the scene overlaps itself, coplanar and edge-on faces included. Where the context has no packed depth
// + stencil (core GLES 2 without OES_packed_depth_stencil), GL_LESS against the depth pulled one resolvable step
// nearer, writing depth, does nearly as well (tests/test_pipeline.cpp measures both). Without the G-buffer (no
// effect reads it: the AO off), it clears and tests a depth buffer of its own, and pays for overdraw.
//
// Its second target, "shading-count", is a diagnostic: the same pass with the same reads and depth set-up, counting
// how many fragments each pixel shaded (additive blending of 1/255) instead of shading them; the view
// "shading-count" shows 1 as grey 32/255. The tests read it to hold the once-per-pixel promise.
#include <vector>

#include <glm/vec3.hpp>

#include "core/EffectTable.h"
#include "core/GpuScene.h"
#include "gl/RenderTarget.h"

namespace obscura {

struct Lighting {
  // An overcast key light over a strong sky dome: ambient carries most of the light, so AO reads clearly.
  glm::vec3 directionToLight{0.45f, 0.8f, 0.35f};  // world space, normalised when used
  glm::vec3 lightColor{0.50f, 0.48f, 0.44f};
  glm::vec3 skyColor{0.62f, 0.66f, 0.72f};
  glm::vec3 groundColor{0.30f, 0.28f, 0.26f};
  glm::vec3 background{0.349f, 0.415f, 0.501f};  // linear radiance where no geometry is (a pale blue sky)
};

class LightingEffect : public Effect {
 public:
  using Settings = NoSettings;
  static constexpr bool kHasSwitch = false;
  static EffectInfo info();
  static std::vector<ProgramSpec> programSpecs();

  explicit LightingEffect(const EffectResources& resources);
  void plan(FramePlanner& planner) override;

 private:
  struct Variant {
    explicit Variant(gl::Program built);
    gl::Program program;
    GeometryUniforms geometry;
    GLint projection, lightDirection, viewUp, lightColor, skyColor, groundColor, ao;
  };
  void render(const PassContext& context, const std::string& output) const;

  Variant shade_;         // the lit image
  Variant countShading_;  // the shading-count view: how many fragments each pixel shaded
  gl::Texture2D white_;   // AO = 1 when the AO is off
  bool stencil_;          // the G-buffer's depth has stencil bits (RenderTargetPool): shade exactly once
  Lighting light_;
};

}  // namespace obscura
