// Tone mapping as a per-pixel stage (src/effects/tonemap/TonemapEffect.h; the stage: src/frame/Stage.h): linear HDR
// colour exposed and mapped by the curve TONEMAP_OPERATOR selects (lib/tonemap.glsl: u_exposure), encoded sRGB for
// the RGBA8 display target (the stage's output encoding puts the luma FXAA reads in alpha). CPU mirror:
// src/encoding/ToneMapping.h (ToneMapInUse::displayColor).
// AUTO_EXPOSURE 1: the exposure is auto exposure's (effects/auto_exposure/), read from its 1 x 1 target, and
// u_exposure is 1.
// LENS_LIGHT 1: the light the lens adds (effects/lens_flare, effects/glare: `lens-light`, RGB9E5 at 1/4 of the
// frame), upsampled bilinearly by hand (four texels decoded, then weighted) and added to the HDR colour first.
#include "lib/tonemap.glsl"
#if AUTO_EXPOSURE
#include "lib/packing.glsl"
#include "lib/exposure.glsl"
uniform sampler2D u_exposureTarget;  // auto exposure's `exposure`: BA the EV to apply
#endif
#if LENS_LIGHT
uniform sampler2D u_lensLight;
uniform vec2 u_lensLightSize;  // texels

vec3 lensLightTexel(vec2 texel) {
  return decodeHdr(texture2D(u_lensLight, (clamp(texel, vec2(0.0), u_lensLightSize - 1.0) + 0.5) / u_lensLightSize));
}

vec3 lensLight(vec2 uv) {
  vec2 p = uv * u_lensLightSize - 0.5;
  vec2 i0 = floor(p);
  vec2 f = p - i0;
  return mix(mix(lensLightTexel(i0), lensLightTexel(i0 + vec2(1.0, 0.0)), f.x),
             mix(lensLightTexel(i0 + vec2(0.0, 1.0)), lensLightTexel(i0 + vec2(1.0, 1.0)), f.x), f.y);
}
#endif

vec3 tonemapStage(vec3 linear, StagePixel pixel) {
#if LENS_LIGHT
  linear += lensLight(pixel.uv);
#endif
#if AUTO_EXPOSURE
  linear *= exposureFromTarget(texture2D(u_exposureTarget, vec2(0.5)));
#endif
  return linearToSrgb(toneMap(linear));
}
