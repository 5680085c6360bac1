// The vignette, a per-pixel stage on display colour after the grade (src/effects/vignette/Vignette.h: the formula,
// its source, why after the tone curve, and the CPU mirror): the display-referred light darkened towards the frame's
// edges, as a lens's light falls off. Needs lib/precision.glsl and lib/stage.glsl first.
uniform vec3 u_vignetteShape;  // (3 x intensity, the x scale for roundness, 5 x smoothness)

float vignetteFactor(vec2 uv) {
  vec2 d = abs(uv - 0.5) * u_vignetteShape.x;
  d.x *= u_vignetteShape.y;
  return pow(clamp(1.0 - dot(d, d), 0.0, 1.0), u_vignetteShape.z);
}

vec3 vignetteStage(vec3 srgb, StagePixel pixel) {
  return linearToSrgb(srgbToLinear(clamp(srgb, 0.0, 1.0)) * vignetteFactor(pixel.uv));
}
