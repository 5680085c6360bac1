#pragma once
// What a pass that lights surfaces the lighting pass did not draw needs of this frame's light and fog (the
// transparent layer: effects/transparency), so that it lights them as the opaque layer was lit without including
// another effect. The lighting pass publishes its light as it runs (effects/lighting: the same uniforms it set), the
// Renderer the fog in use before each frame's plan (renderer/Renderer.cpp). One per Renderer, lent to every effect
// through EffectResources. Names no effect.
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gl/GlApi.h"

namespace obscura {

class GpuEnvironment;

// The lighting pass's uniforms of lighting.frag, as it set them this frame.
struct SurfaceLight {
  bool published = false;                       // the lighting pass ran this frame
  const GpuEnvironment* environment = nullptr;  // its prefiltered environment and SH irradiance (environment/)
  int environmentFilteredUnit = 0;  // the unit its filtered texture (rough levels, BRDF table) is bound to
                                    // (gpu/TextureUnits.h)
  int quality = 1;                  // the shading tier: lighting.frag's LIGHTING_QUALITY (0 low, 1 medium, 2 high)
  glm::mat3 viewToEnvironment{1.0f};
  float environmentIntensity = 1.0f;
  glm::vec3 lightDirection{0.0f, 1.0f, 0.0f};  // the sun, view space, towards it
  glm::vec3 lightColor{0.0f};                  // the sun's illuminance
  // The punctual lights, most important first: per light its u_lightPositionRange, u_lightColorSpot and u_lightSpot.
  std::vector<glm::vec4> positionRange, colorSpot, spot;
};

// The fog the fog pass applies this frame (lib/fog.glsl's uniforms), for surfaces drawn after it.
struct SurfaceFog {
  bool enabled = false;
  int mode = 1;  // FOG_MODE
  bool height = false;
  glm::vec3 color{0.0f};
  glm::vec2 factor{0.0f};  // offset, scale
  float falloff = 0.0f, heightScale = 1.0f;
  glm::vec3 upInView{0.0f, 1.0f, 0.0f};
};

struct SurfaceShading {
  SurfaceLight light;
  SurfaceFog fog;
};

}  // namespace obscura
