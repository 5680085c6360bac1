// The sRGB transfer function (IEC 61966-2-1, the real piecewise curve) and FXAA's luma: what the tone mapping
// encodes for display, and what the G-buffer pass stores the base colour in where it also writes one (several
// render targets: the deferred lighting decodes it). CPU mirror: src/encoding/ToneMapping.h. Needs lib/precision.glsl.

// The pow branch takes max(c, 0.0031308) so that it never sees 0 (pow(0, y) is only defined for y > 0, and mix would
// carry a NaN from the unused branch).
vec3 linearToSrgb(vec3 linear) {
  vec3 c = clamp(linear, 0.0, 1.0);
  vec3 curve = 1.055 * pow(max(c, 0.0031308), vec3(1.0 / 2.4)) - 0.055;
  return mix(curve, c * 12.92, vec3(lessThanEqual(c, vec3(0.0031308))));
}

vec3 srgbToLinear(vec3 srgb) {
  vec3 c = clamp(srgb, 0.0, 1.0);
  vec3 curve = pow((max(c, 0.04045) + 0.055) / 1.055, vec3(2.4));
  return mix(curve, c / 12.92, vec3(lessThanEqual(c, vec3(0.04045))));
}

// FXAA 3.11 (Lottes 2011) reads the luma of the display-encoded colour from alpha: BT.601 weights.
float fxaaLuma(vec3 srgb) { return dot(srgb, vec3(0.299, 0.587, 0.114)); }
