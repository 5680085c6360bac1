// Distance fog as a per-pixel stage (src/effects/fog/FogEffect.h, whose FogFactor is this function's CPU mirror; the
// stage: src/frame/Stage.h): the lit HDR colour blended towards the fog colour, c = f c_s + (1 - f) c_f
// (Schmalstieg's deck, "Distance fog"), with the fog factor f of FOG_MODE at the pixel's distance from the camera.
//   FOG_MODE 0 linear: f = clamp(offset - scale d)       (d_end - d) / (d_end - d_start)
//            1 exponential: f = 2^(-scale d)              e^(-d_f d), scale = d_f log2 e
//            2 squared exponential: f = 2^(-(scale d)^2)  e^(-(d_f d)^2), scale = d_f sqrt(log2 e)
//   FOG_HEIGHT 1: d is the distance through fog of the density at height 0 that holds as much fog as the ray,
//            d' = d e^(-b h_0) (1 - e^(-b u d)) / (b u) (FogEffect.h).
// It reads its pixel's view-space position (fused into the lighting: the surface's own; alone: from the G-buffer's
// 16-bit linear depth), the background's as a ray through the pixel.

#include "lib/reconstruct.glsl"  // eyeRay: the eye's rays, perspective or orthographic

uniform vec3 u_fogColor;      // c_f, linear HDR
uniform vec2 u_fogFactor;     // (offset, scale)
#if FOG_HEIGHT
uniform float u_fogFalloff;      // b, per metre
uniform float u_fogHeightScale;  // e^(-b h_0), h_0 the camera's world height
uniform vec3 u_fogUpInView;      // world up in view space
#endif

const float FOG_ENDLESS = 1e30;  // the background, and rays into unending fog

// The fog along `ray` (view space), which starts at `origin`: the eye, or a point of its plane (orthographic).
float fogDistance(vec3 ray, vec3 origin, bool background) {
  float d = length(ray);
#if FOG_HEIGHT
  float climb = u_fogFalloff * dot(ray, u_fogUpInView) / d;
  float heightScale = u_fogHeightScale * exp(clamp(-u_fogFalloff * dot(origin, u_fogUpInView), -80.0, 80.0));
  if (background) return climb > 0.0 ? min(heightScale / climb, FOG_ENDLESS) : FOG_ENDLESS;
  float x = climb * d;
  float g = abs(x) < 1e-3 ? 1.0 - 0.5 * x : (1.0 - exp(min(-x, 80.0))) / x;
  return min(d * heightScale * g, FOG_ENDLESS);
#else
  return background ? FOG_ENDLESS : d;
#endif
}

vec3 fogStage(vec3 color, StagePixel pixel) {
  // From the eye, or from its plane (orthographic; the origin: only height fog reads it).
  vec3 ray = eyeRay(pixel.viewPosition);
  float d = fogDistance(ray, pixel.viewPosition - ray, pixel.background);
#if FOG_MODE == 0
  float f = clamp(u_fogFactor.x - u_fogFactor.y * d, 0.0, 1.0);
#elif FOG_MODE == 1
  float f = exp2(-min(u_fogFactor.y * d, 126.0));
#else
  float s = min(u_fogFactor.y * d, 12.0);
  float f = exp2(-s * s);
#endif
  return mix(u_fogColor, color, f);
}
