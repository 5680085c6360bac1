// Lens flare (src/effects/lens_flare/LensFlareEffect.h: the method, its source and the CPU mirror): John Chapman's
// screen-space pseudo lens flare (2013) on bloom's bright pass at 1/4 of the frame. Ghosts are copies of the bright
// light along the line through the image centre, a halo is a ring of it, each channel sampled a little apart along that
// line (chromatic dispersion), and the optional lens dirt modulates the result. The tone mapping adds it to the frame.
#include "lib/precision.glsl"
#include "lib/hdr.glsl"

#define MAX_GHOSTS 8

uniform sampler2D u_bright;    // bloom-bright: RGB9E5, 1/4 of the frame
uniform vec2 u_brightSize;     // its size in texels
uniform float u_ghosts;        // 1 .. MAX_GHOSTS
uniform float u_dispersal;     // the spacing of the ghosts along the line through the centre
uniform float u_haloWidth;     // the halo's radius, in uv of the frame's height
uniform vec2 u_aspect;         // (width / height, 1): uv to a frame whose units are equal in x and y
uniform float u_distortion;    // the chromatic dispersion, in uv of the frame's height
uniform float u_intensity;
#if LENS_DIRT
uniform sampler2D u_dirt;      // plain linear RGB, LINEAR filtered
#endif

varying vec2 v_uv;

vec3 bright(vec2 uv) {
  // Outside the frame (a dispersed sample beyond its edge), the edge's texel.
  vec2 texel = clamp(floor(uv * u_brightSize), vec2(0.0), u_brightSize - 1.0);
  return decodeHdr(texture2D(u_bright, (texel + 0.5) / u_brightSize));
}

// Each channel a little further out than the last along `direction` (uv): red in, blue out, as a lens disperses.
vec3 dispersed(vec2 uv, vec2 direction) {
  return vec3(bright(uv - direction * u_distortion).r, bright(uv).g, bright(uv + direction * u_distortion).b);
}

// Chapman's falloff: 1 at the centre, 0 at the corners (|0.5 - uv| / |(0.5, 0.5)|).
float falloff(vec2 uv, float power) { return pow(max(1.0 - length(0.5 - uv) * 1.4142135, 0.0), power); }

void main() {
  vec2 t = 1.0 - v_uv;  // the image flipped through its centre
  vec2 ghostStep = (0.5 - t) * u_dispersal;
  // The line's direction on screen (equal units in x and y), back in uv; none at the exact centre.
  vec2 along = ghostStep * u_aspect;
  float lengthAlong = length(along);
  vec2 direction = lengthAlong > 1e-6 ? along / (lengthAlong * u_aspect) : vec2(0.0);
  vec3 flare = vec3(0.0);
  for (int i = 0; i < MAX_GHOSTS; i++) {
    if (float(i) >= u_ghosts) break;
    vec2 source = fract(t + ghostStep * float(i));
    flare += dispersed(source, direction) * falloff(source, 10.0);
  }
  // The halo: the light at u_haloWidth from the flipped pixel towards the centre (a ring round the centre for a light
  // there), weighted by its distance from the centre.
  vec2 halo = fract(t + direction * u_haloWidth);
  flare += dispersed(halo, direction) * falloff(halo, 5.0);
#if LENS_DIRT
  flare *= texture2D(u_dirt, v_uv).rgb;
#endif
  gl_FragColor = encodeHdr(flare * u_intensity);
}
