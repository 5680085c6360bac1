// The vignette (src/effects/vignette/Vignette.h: the formula, its source and the CPU mirror): the HDR colour darkened
// towards the frame's edges, before the tone curve, as a lens's light falls off. Needs lib/precision.glsl first.
uniform vec3 u_vignetteShape;  // (3 x intensity, the x scale for roundness, 5 x smoothness)

float vignetteFactor(vec2 uv) {
  vec2 d = abs(uv - 0.5) * u_vignetteShape.x;
  d.x *= u_vignetteShape.y;
  return pow(clamp(1.0 - dot(d, d), 0.0, 1.0), u_vignetteShape.z);
}

vec3 vignette(vec3 linear, vec2 uv) { return linear * vignetteFactor(uv); }
