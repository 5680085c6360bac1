// Distance fog as a per-pixel stage (src/effects/fog/FogEffect.h, whose FogFactor is the CPU mirror; the stage:
// src/frame/Stage.h): the lit HDR colour blended towards the fog colour, c = f c_s + (1 - f) c_f (Schmalstieg's deck,
// "Distance fog"), with lib/fog.glsl's fog factor f of FOG_MODE (and FOG_HEIGHT) at the pixel's distance from the
// camera; the transparent layer applies the same factor to each surface it composites.
// It reads its pixel's view-space position (fused into the lighting: the surface's own; alone: from the G-buffer's
// 16-bit linear depth), the background's as a ray through the pixel.

#include "lib/reconstruct.glsl"  // eyeRay: the eye's rays, perspective or orthographic
#include "lib/fog.glsl"          // fogFactor, and the uniforms u_fog*

vec3 fogStage(vec3 color, StagePixel pixel) {
  // From the eye, or from its plane (orthographic; the origin: only height fog reads it).
  vec3 ray = eyeRay(pixel.viewPosition);
  return mix(u_fogColor, color, fogFactor(ray, pixel.viewPosition - ray, pixel.background));
}
