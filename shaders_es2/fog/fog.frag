// Distance fog (src/effects/fog/FogEffect.h, whose FogFactor is this shader's CPU mirror): the lit HDR colour blended
// towards the fog colour, c = f c_s + (1 - f) c_f (Schmalstieg's deck, "Distance fog"), with the fog factor f of
// FOG_MODE at the pixel's distance from the camera, reconstructed from the G-buffer's linear depth.
//   FOG_MODE 0 linear: f = clamp(offset - scale d)       (d_end - d) / (d_end - d_start)
//            1 exponential: f = 2^(-scale d)              e^(-d_f d), scale = d_f log2 e
//            2 squared exponential: f = 2^(-(scale d)^2)  e^(-(d_f d)^2), scale = d_f sqrt(log2 e)
//   FOG_HEIGHT 1: d is the distance through fog of the density at height 0 that holds as much fog as the ray,
//            d' = d e^(-b h_0) (1 - e^(-b u d)) / (b u) (FogEffect.h).
#include "lib/precision.glsl"
#include "lib/hdr.glsl"
#include "lib/reconstruct.glsl"

uniform sampler2D u_color;    // "scene-color", HDR-encoded, NEAREST
uniform sampler2D u_gbuffer;  // linear depth in BA
uniform vec3 u_fogColor;      // c_f, linear HDR
uniform vec2 u_factor;        // (offset, scale)
#if FOG_HEIGHT
uniform float u_falloff;      // b, per metre
uniform float u_heightScale;  // e^(-b h_0), h_0 the camera's world height
uniform vec3 u_upInView;      // world up in view space
#endif

varying vec2 v_uv;
varying vec3 v_farRay;

const float ENDLESS = 1e30;  // the background, and rays into unending fog

// The fog along `ray` (view space), which starts at `origin`: the eye, or a point of its plane (orthographic).
float fogDistance(vec3 ray, vec3 origin, bool background) {
  float d = length(ray);
#if FOG_HEIGHT
  float climb = u_falloff * dot(ray, u_upInView) / d;
  float heightScale = u_heightScale * exp(clamp(-u_falloff * dot(origin, u_upInView), -80.0, 80.0));
  if (background) return climb > 0.0 ? min(heightScale / climb, ENDLESS) : ENDLESS;
  float x = climb * d;
  float g = abs(x) < 1e-3 ? 1.0 - 0.5 * x : (1.0 - exp(min(-x, 80.0))) / x;
  return min(d * heightScale * g, ENDLESS);
#else
  return background ? ENDLESS : d;
#endif
}

void main() {
  float code = unpackDepthCode(texture2D(u_gbuffer, v_uv).ba);
  bool background = isBackgroundCode(code);
  // The background's ray is the far-plane ray itself: only its direction counts.
  vec3 viewPosition = background ? v_farRay : viewPositionOnRay(v_farRay, code * (1.0 / 65535.0));
  vec3 ray = eyeRay(viewPosition);  // from the eye, or from its plane (the origin: only height fog reads it)
  float d = fogDistance(ray, viewPosition - ray, background);
#if FOG_MODE == 0
  float f = clamp(u_factor.x - u_factor.y * d, 0.0, 1.0);
#elif FOG_MODE == 1
  float f = exp2(-min(u_factor.y * d, 126.0));
#else
  float s = min(u_factor.y * d, 12.0);
  float f = exp2(-s * s);
#endif
  vec3 surface = decodeHdr(texture2D(u_color, v_uv));
  gl_FragColor = encodeHdr(mix(u_fogColor, surface, f));
}
