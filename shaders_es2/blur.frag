// Separable bilateral blur of the AO (one direction per pass: horizontal, then vertical).
//
// Input: R = AO, GB = 16-bit depth code (the SAO pass writes them side by side so this pass reads one texture).
// Output: the same layout, so the second pass reads the first one's output the same way.
//
// Weights, per tap i in [-BLUR_RADIUS, BLUR_RADIUS] at a stride of u_stepPixels:
//   spatial  exp(-i^2 / (2 s^2)), s = (BLUR_RADIUS + 1) / 2 taps
//   range    exp(-(delta / sigma)^2), delta in view-space metres, so the result does not depend on near / far:
//              NORMAL_AWARE 0: delta = |z_tap - z_centre|
//              NORMAL_AWARE 1: delta = distance of the tap's point from the centre's tangent plane (a plane seen at
//                              a grazing angle still blurs), times the normal weight ((n_c.n_t + 1) / 2)^10
//                              (Gravas 2013, eq. 3.2.2 with k_n = 10)
// Background pixels (depth code 65535) are left alone and never contribute.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/reconstruct.glsl"

uniform sampler2D u_ao;
uniform vec2 u_aoSize;        // pixels
uniform vec2 u_stepPixels;    // blur direction times stride, in pixels
uniform float u_gaussianK;    // 1 / (2 s^2)
uniform float u_invSigma2;    // 1 / sigma^2, metres^-2
#if NORMAL_AWARE
uniform sampler2D u_gbuffer;  // normals in RG
#else
uniform float u_near;
uniform float u_depthRange;   // far - near
#endif

varying vec2 v_uv;
varying vec3 v_farRay;

void main() {
  vec4 centre = texture2D(u_ao, v_uv);
  float code = unpackDepthCode(centre.gb);
  vec2 key = bytesToChannels(channelsToBytes(centre.gb));
  if (isBackgroundCode(code)) {
    gl_FragColor = vec4(1.0, key, 1.0);
    return;
  }
  float depth = code * (1.0 / 65535.0);
#if NORMAL_AWARE
  vec3 P = viewPositionOnRay(v_farRay, depth);
  vec3 n = decodeNormal(texture2D(u_gbuffer, v_uv).rg);
#else
  float z = u_near + depth * u_depthRange;
#endif

  float sum = centre.r;
  float weightSum = 1.0;
  for (int i = -BLUR_RADIUS; i <= BLUR_RADIUS; ++i) {
    if (i == 0) continue;
    vec2 uv = v_uv + u_stepPixels * float(i) / u_aoSize;
    vec4 tap = texture2D(u_ao, uv);
    float tapCode = unpackDepthCode(tap.gb);
    float tapDepth = tapCode * (1.0 / 65535.0);
#if NORMAL_AWARE
    vec3 tapP = viewPositionOnRay(farPlaneRay(uv), tapDepth);
    float delta = dot(n, tapP - P);
    float normalWeight = pow(max(0.0, dot(n, decodeNormal(texture2D(u_gbuffer, uv).rg)) * 0.5 + 0.5), 10.0);
#else
    float delta = u_near + tapDepth * u_depthRange - z;
    float normalWeight = 1.0;
#endif
    float weight = exp(-float(i * i) * u_gaussianK - delta * delta * u_invSigma2) * normalWeight;
    // Taps on the background or outside the image contribute nothing.
    if (isBackgroundCode(tapCode) || uv.x < 0.0 || uv.y < 0.0 || uv.x > 1.0 || uv.y > 1.0) weight = 0.0;
    sum += tap.r * weight;
    weightSum += weight;
  }
  gl_FragColor = vec4(sum / weightSum, key, 1.0);
}
