// Tone mapping: the lit HDR colour decoded (NEAREST fetch, then decode: filtering an encoded texel is not filtering
// the colour), exposed and mapped by the curve TONEMAP_OPERATOR selects, encoded sRGB for the RGBA8 display target.
// Alpha carries the luma of the display colour, which FXAA 3.11 reads. CPU mirror: src/encoding/ToneMapping.h.
// AUTO_EXPOSURE 1: the exposure is auto exposure's (effects/auto_exposure/), read from its 1 x 1 target, and u_exposure
// is 1.
#include "lib/precision.glsl"
#include "lib/hdr.glsl"
#include "lib/tonemap.glsl"
#if AUTO_EXPOSURE
#include "lib/packing.glsl"
#include "lib/exposure.glsl"
uniform sampler2D u_exposureTarget;  // auto exposure's `exposure`: BA the EV to apply
#endif
// LENS_LIGHT 1: the light the lens adds (effects/lens_flare, effects/glare: `lens-light`, RGB9E5 at 1/4 of the
// frame), upsampled bilinearly by hand (four texels decoded, then weighted) and added to the HDR colour.
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

uniform sampler2D u_color;     // scene-color, HDR-encoded
uniform float u_lumaInAlpha;   // 1: luma in alpha, for FXAA; 0: alpha 1, for the output framebuffer

varying vec2 v_uv;

void main() {
  vec3 hdr = decodeHdr(texture2D(u_color, v_uv));
#if LENS_LIGHT
  hdr += lensLight(v_uv);
#endif
#if AUTO_EXPOSURE
  hdr *= exposureFromTarget(texture2D(u_exposureTarget, vec2(0.5)));
#endif
  vec3 display = linearToSrgb(toneMap(hdr));
  gl_FragColor = vec4(display, mix(1.0, fxaaLuma(display), u_lumaInAlpha));
}
