// Colour grading on display colour, a per-pixel stage after the tone curve (src/effects/grading/ColorGrading.h: the
// steps, their sources, and the CPU mirror gradeDisplay, which tests/test_grading.cpp holds this to). Needs
// lib/precision.glsl and lib/stage.glsl first.
//   GRADING_BALANCE 1   white balance, ASC CDL, saturation, contrast (display-linear), else none of them
//   GRADING_LUT 1       the 3D LUT: its RGBA8 strip (encoding/ColorLut.h), bilinear in red and green by the hardware,
//                       linear in blue by hand between two slices
#if GRADING_BALANCE
// diag(slope) M^-1 diag(LMS(D65) / LMS(white)) M on linear Rec. 709: the white balance and the CDL's slope in one
// matrix, made on the CPU once a frame (gradingBalance).
uniform mat3 u_gradingBalance;
uniform vec3 u_gradingOffset, u_gradingPower;
uniform vec2 u_gradingSaturationContrast;
#endif
#if GRADING_LUT
uniform sampler2D u_gradingLut;      // the strip, LINEAR
uniform vec4 u_gradingLutLayout;     // (lattice points N, slices per row, strip width, strip height)
uniform vec3 u_gradingLutDomainMin, u_gradingLutDomainScale;  // input to [0, 1]: (c - min) * scale
uniform float u_gradingLutIntensity;

// The texel of lattice point (r, g) of slice b, as uv of the strip (r, g in lattice units, fractional).
vec2 gradingLutUv(vec2 rg, float slice) {
  float row = floor((slice + 0.5) / u_gradingLutLayout.y);
  vec2 origin = vec2(slice - row * u_gradingLutLayout.y, row) * u_gradingLutLayout.x;
  return (origin + rg + 0.5) / u_gradingLutLayout.zw;
}

vec3 gradingLut(vec3 srgb) {
  float n = u_gradingLutLayout.x;
  vec3 x = clamp((srgb - u_gradingLutDomainMin) * u_gradingLutDomainScale, 0.0, 1.0) * (n - 1.0);
  float b0 = min(floor(x.b), n - 2.0);
  vec3 lower = texture2D(u_gradingLut, gradingLutUv(x.rg, b0)).rgb;
  vec3 upper = texture2D(u_gradingLut, gradingLutUv(x.rg, b0 + 1.0)).rgb;
  return mix(lower, upper, x.b - b0);
}
#endif

vec3 gradeDisplay(vec3 srgb) {
#if GRADING_BALANCE
  vec3 c = pow(max(u_gradingBalance * srgbToLinear(srgb) + u_gradingOffset, 0.0), u_gradingPower);
  float luma = dot(c, vec3(0.2126, 0.7152, 0.0722));
  c = vec3(luma) + u_gradingSaturationContrast.x * (c - vec3(luma));
  c = 0.18 * pow(max(c, 0.0) * (1.0 / 0.18), vec3(u_gradingSaturationContrast.y));
  srgb = linearToSrgb(clamp(c, 0.0, 1.0));
#endif
#if GRADING_LUT
  srgb = mix(srgb, gradingLut(srgb), u_gradingLutIntensity);
#endif
  return srgb;
}

vec3 gradingStage(vec3 srgb, StagePixel pixel) { return gradeDisplay(srgb); }
