// Scalable Ambient Obscurance (McGuire, Mara, Luebke, HPG 2012) from the one-texture G-buffer.
// CPU mirror: src/effects/ao/SaoKernel.h (equations and constants documented there).
//
// Compile-time constants (one program per variant, so every loop bound is constant as GLSL ES 1.00 requires), beside
// those of ao/ao_estimator.glsl:
//   NUM_SAMPLES        taps per pixel (s)
//   NUM_SPIRAL_TURNS   turns of the tap spiral (tau), coprime with NUM_SAMPLES
//   FALLOFF_SAO2012    1: SAO's smooth (r^2 - v.v)^3 falloff; 0: Alchemy 2011's hard cut at r
#include "ao/ao_estimator.glsl"

const float kEpsilon = 0.01;  // SAO paper: large epsilon avoids over-darkening in cracks (here in units of r^2)

// Distances in units of the radius (SaoKernel.h): the same AO for a scene and its radius scaled together.
float tapObscurance(vec3 v, vec3 n, float bias) {
  vec3 u = v * u_invRadius;
  float uu = dot(u, u);
  float angular = max(dot(u, n) - bias, 0.0) / (uu + kEpsilon);
#if FALLOFF_SAO2012
  float f = max(1.0 - uu, 0.0);
  return f * f * f * angular;
#else
  return uu < 1.0 ? angular : 0.0;
#endif
}

void main() {
  AoCentre c;
  if (!aoCentre(c)) {
    gl_FragColor = vec4(1.0);
    return;
  }
  float log2DiskRadius = log2(max(c.diskRadius, 1e-3));
  float spin = rotationAngle(c.aoPixel);
  vec4 estimator = estimatorAt(log2DiskRadius);

  float sum = 0.0;
  for (int i = 0; i < NUM_SAMPLES; i++) {
    float alpha = (float(i) + 0.5) * (1.0 / float(NUM_SAMPLES));
    float angle = alpha * (float(NUM_SPIRAL_TURNS) * kTwoPi) + spin;
    float tapDistance = alpha * c.diskRadius;
    // The texel holding the tap point; taps leaving the image read its edge, as in the SAO reference code.
    vec2 tapPixel = clamp(floor(c.pixel + 0.5 + tapDistance * vec2(cos(angle), sin(angle))), vec2(0.0),
                          u_gbufferSize - 1.0);
    // log2 of the tap distance from per-pixel and per-tap parts (the loop is unrolled: log2(alpha) folds away).
    sum += tapObscurance(tapPoint(tapPixel, log2(alpha) + log2DiskRadius) - c.position, c.normal, estimator.y);
  }
  gl_FragColor = aoOutput(c, sum, estimator);
}
