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

uniform sampler2D u_color;     // scene-color, HDR-encoded
uniform float u_lumaInAlpha;   // 1: luma in alpha, for FXAA; 0: alpha 1, for the output framebuffer

varying vec2 v_uv;

void main() {
  vec3 hdr = decodeHdr(texture2D(u_color, v_uv));
#if AUTO_EXPOSURE
  hdr *= exposureFromTarget(texture2D(u_exposureTarget, vec2(0.5)));
#endif
  vec3 display = linearToSrgb(toneMap(hdr));
  gl_FragColor = vec4(display, mix(1.0, fxaaLuma(display), u_lumaInAlpha));
}
