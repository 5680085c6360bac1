// Scalable Ambient Obscurance (McGuire, Mara, Luebke, HPG 2012) from the one-texture G-buffer.
// CPU mirror: src/core/SaoKernel.h (equations and constants documented there).
//
// Compile-time constants (one program per variant, so every loop bound is constant as GLSL ES 1.00 requires):
//   NUM_SAMPLES        taps per pixel (s)
//   NUM_SPIRAL_TURNS   turns of the tap spiral (tau), coprime with NUM_SAMPLES
//   FALLOFF_SAO2012    1: SAO's smooth (r^2 - v.v)^3 falloff; 0: Alchemy 2011's hard cut at r
//
// Output: R = ambient visibility A, GB = the centre's 16-bit depth code (the blur's key), A = 1.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/reconstruct.glsl"

uniform sampler2D u_gbuffer;
uniform vec2 u_gbufferSize;     // G-buffer size in pixels
uniform float u_projScale;      // pixels per metre at 1 m: height / (2 tan(fovy / 2))
uniform float u_radius;         // r, metres
uniform float u_bias;           // beta, metres
uniform float u_intensityScale; // sigma * 5 / s (SAO 2012) or sigma * 2 / s (Alchemy 2011)
uniform float u_contrast;       // k
uniform float u_maxRadiusPixels;

varying vec2 v_uv;
varying vec3 v_farRay;

const float kEpsilon = 0.01;  // SAO paper: large epsilon avoids over-darkening in cracks
const float kTwoPi = 6.28318530718;

// Interleaved gradient noise (Jimenez 2014): an arithmetic per-pixel hash in [0, 1).
float rotationAngle(vec2 pixel) {
  float inner = 0.06711056 * pixel.x + 0.00583715 * pixel.y;
  float noise = 52.9829189 * (inner - floor(inner));
  return kTwoPi * (noise - floor(noise));
}

// View-space position of the surface seen through G-buffer pixel `pixel` (integer coordinates).
vec3 tapPosition(vec2 pixel) {
  vec2 uv = (pixel + 0.5) / u_gbufferSize;
  return viewPositionOnRay(farPlaneRay(uv), unpackLinearDepth(texture2D(u_gbuffer, uv).ba));
}

float tapObscurance(vec3 v, vec3 n) {
  float vv = dot(v, v);
  float vn = dot(v, n);
  float angular = max(vn - u_bias, 0.0) / (vv + kEpsilon);
#if FALLOFF_SAO2012
  float f = max(u_radius * u_radius - vv, 0.0) / (u_radius * u_radius);
  return f * f * f * angular;
#else
  return vv < u_radius * u_radius ? angular : 0.0;
#endif
}

void main() {
  // Integer pixel coordinates from the highp varying: gl_FragCoord is only mediump in GLSL ES 1.00 (exact to 2048).
  vec2 pixel = floor(v_uv * u_gbufferSize);
  vec4 centre = texture2D(u_gbuffer, v_uv);
  float code = unpackDepthCode(centre.ba);
  if (isBackgroundCode(code)) {
    gl_FragColor = vec4(1.0);
    return;
  }
  vec3 C = viewPositionOnRay(v_farRay, code * (1.0 / 65535.0));
  vec3 n = decodeNormal(centre.rg);

  // The world-space radius projected to pixels at the centre's depth, clamped (paper sec. 3.2).
  float diskRadius = min(u_projScale * u_radius / -C.z, u_maxRadiusPixels);
  float spin = rotationAngle(pixel);

  float sum = 0.0;
  for (int i = 0; i < NUM_SAMPLES; ++i) {
    float alpha = (float(i) + 0.5) * (1.0 / float(NUM_SAMPLES));
    float angle = alpha * (float(NUM_SPIRAL_TURNS) * kTwoPi) + spin;
    // The texel holding the tap point; taps leaving the image read its edge, as in the SAO reference code.
    vec2 tapPixel = floor(pixel + 0.5 + alpha * diskRadius * vec2(cos(angle), sin(angle)));
    tapPixel = clamp(tapPixel, vec2(0.0), u_gbufferSize - 1.0);
    sum += tapObscurance(tapPosition(tapPixel) - C, n);
  }
  float visibility = pow(max(0.0, 1.0 - sum * u_intensityScale), u_contrast);
  gl_FragColor = vec4(visibility, bytesToChannels(channelsToBytes(centre.ba)), 1.0);
}
