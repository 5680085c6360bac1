// Distance fog's factor (src/effects/fog/FogEffect.h, whose FogFactor is its CPU mirror): f = 1 keeps a surface's
// colour, 0 gives the fog colour, c = f c_s + (1 - f) c_f (Schmalstieg's deck, "Distance fog"), with f of FOG_MODE at
// the distance d from the camera:
//   FOG_MODE 0 linear: f = clamp(offset - scale d)       (d_end - d) / (d_end - d_start)
//            1 exponential: f = 2^(-scale d)              e^(-d_f d), scale = d_f log2 e
//            2 squared exponential: f = 2^(-(scale d)^2)  e^(-(d_f d)^2), scale = d_f sqrt(log2 e)
//   FOG_HEIGHT 1: d is the distance through fog of the density at height 0 that holds as much fog as the ray,
//            d' = d e^(-b h_0) (1 - e^(-b u d)) / (b u) (FogEffect.h).
// The fog stage applies it to the opaque frame (fog/fog.glsl, fused into the lighting or a stage pass); the
// transparent layer to each surface at its own distance (transparency/composite.glsl), which composites to the same
// colour for exponential fog. Its uniforms are the fog effect's (u_fog*), set by both.
#ifndef FOG_GLSL
#define FOG_GLSL

uniform vec3 u_fogColor;         // c_f, linear HDR
uniform vec2 u_fogFactor;        // (offset, scale)
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

// f along `ray` from `origin` (fogDistance); `background`: the ray continued to infinity.
float fogFactor(vec3 ray, vec3 origin, bool background) {
  float d = fogDistance(ray, origin, background);
#if FOG_MODE == 0
  return clamp(u_fogFactor.x - u_fogFactor.y * d, 0.0, 1.0);
#elif FOG_MODE == 1
  return exp2(-min(u_fogFactor.y * d, 126.0));
#else
  float s = min(u_fogFactor.y * d, 12.0);
  return exp2(-s * s);
#endif
}

#endif
