// Chromatic aberration (src/effects/chromatic_aberration/ChromaticAberrationEffect.h: why a pass of its own, and the
// CPU mirror): a lens bends red less than blue, so away from the axis the red image lies further out than the green
// and the blue further in (lateral chromatic aberration grows with the field angle): the red image is the green one
// magnified by 1 + k, the blue one by 1 - k, so a pixel reads red at its offset from the centre divided by 1 + k and
// blue divided by 1 - k, bilinearly by hand (display-color is fetched NEAREST, like every target), green where it is;
// alpha keeps FXAA's luma.
#include "lib/precision.glsl"
#include "lib/srgb.glsl"

uniform sampler2D u_color;    // display-color (sRGB; luma in alpha)
uniform vec2 u_size;          // pixels
uniform vec2 u_shift;         // (1 / (1 + k), 1 / (1 - k))
uniform float u_lumaInAlpha;  // 1: luma in alpha, for FXAA; 0: alpha 1, for the output framebuffer

varying vec2 v_uv;

vec4 texel(vec2 p) { return texture2D(u_color, (clamp(p, vec2(0.0), u_size - 1.0) + 0.5) / u_size); }

vec4 bilinear(vec2 uv) {
  vec2 p = uv * u_size - 0.5;
  vec2 i0 = floor(p);
  vec2 f = p - i0;
  return mix(mix(texel(i0), texel(i0 + vec2(1.0, 0.0)), f.x), mix(texel(i0 + vec2(0.0, 1.0)), texel(i0 + 1.0), f.x),
             f.y);
}

void main() {
  vec2 offset = v_uv - 0.5;
  vec3 color = vec3(bilinear(0.5 + offset * u_shift.x).r, texture2D(u_color, v_uv).g,
                    bilinear(0.5 + offset * u_shift.y).b);
  gl_FragColor = vec4(color, mix(1.0, fxaaLuma(color), u_lumaInAlpha));
}
