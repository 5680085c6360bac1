// Separable bilateral blur of the AO (one direction per pass: horizontal, then vertical).
//
// Input: R = AO, GB = 16-bit depth code (the SAO pass writes them side by side so this pass reads one texture).
// Output: the same layout, so the second pass reads the first one's output the same way.
//
// Weights, per tap i in [-BLUR_RADIUS, BLUR_RADIUS] at a stride of u_stepPixels:
//   spatial  exp(-i^2 / (2 s^2)), s = (BLUR_RADIUS + 1) / 2 taps, or a quarter of the AO radius projected at the
//            centre's depth (h, as the estimator's disk) where that is less (at least half a tap): the AO varies on
//            the scale of h, and a wider blur smears the contact lines of small radii (docs/accuracy.md, "Blur
//            width")
//   range    exp(-(delta / sigma)^2), delta in view-space units, so the result does not depend on near / far,
//            and sigma a fraction of the AO radius, so it does not depend on the scene's units either:
//              NORMAL_AWARE 0: delta = |z_tap - z_centre|
//              NORMAL_AWARE 1: delta = distance of the tap's point from the centre's tangent plane (a plane seen at
//                              a grazing angle still blurs), times the normal weight ((n_c.n_t + 1) / 2)^10
//                              (Gravas 2013, eq. 3.2.2 with k_n = 10)
// Background pixels (depth code 65535) are left alone and never contribute.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/reconstruct.glsl"
#include "ao/ao_resolution.glsl"

uniform sampler2D u_ao;
uniform vec2 u_aoSize;        // pixels
uniform vec2 u_stepPixels;    // blur direction times stride, in AO pixels
uniform float u_gaussianK;    // 1 / (2 s^2), s the preset's width in taps
// A quarter of the projected radius in taps at view depth z: u_widthScale.x / z + u_widthScale.y (the estimator's
// pixels-per-unit form, FrameCamera::projScale, times r / 4 and divided by the AO scale and the stride).
uniform vec2 u_widthScale;
uniform float u_invSigma2;    // 1 / sigma^2, scene units^-2 (sigma is a fraction of the AO radius)
#if NORMAL_AWARE
uniform sampler2D u_gbuffer;  // normals in RG
#else
uniform float u_near;
uniform float u_depthRange;   // far - near
#endif

varying vec2 v_uv;

// 1 / (2 s^2) for the centre at view depth z (positive).
float gaussianKAt(float z) {
  float width = max(u_widthScale.x / max(z, 1e-6) + u_widthScale.y, 0.5);
  return max(u_gaussianK, 0.5 / (width * width));
}

#if NORMAL_AWARE
// View position and normal of the surface AO pixel `aoPixel` stands for, given its depth code.
vec3 surfacePoint(vec2 aoPixel, float code, out vec3 normal) {
  vec2 uv = (gbufferPixelOf(aoPixel) + 0.5) / u_gbufferSize;
  normal = decodeNormal(texture2D(u_gbuffer, uv).rg);
  return viewPositionOnRay(farPlaneRay(uv), code * (1.0 / 65535.0));
}
#endif

void main() {
  vec2 aoPixel = floor(v_uv * u_aoSize);
  vec4 centre = texture2D(u_ao, v_uv);
  float code = unpackDepthCode(centre.gb);
  vec2 key = bytesToChannels(channelsToBytes(centre.gb));
  if (isBackgroundCode(code)) {
    gl_FragColor = vec4(1.0, key, 1.0);
    return;
  }
#if NORMAL_AWARE
  vec3 n;
  vec3 P = surfacePoint(aoPixel, code, n);
  float gaussianK = gaussianKAt(-P.z);
#else
  float z = u_near + code * (1.0 / 65535.0) * u_depthRange;
  float gaussianK = gaussianKAt(z);
#endif

  float sum = centre.r;
  float weightSum = 1.0;
  for (int i = -BLUR_RADIUS; i <= BLUR_RADIUS; i++) {
    if (i == 0) continue;
    vec2 tapPixel = aoPixel + u_stepPixels * float(i);
    vec4 tap = texture2D(u_ao, (tapPixel + 0.5) / u_aoSize);
    float tapCode = unpackDepthCode(tap.gb);
#if NORMAL_AWARE
    vec3 tapNormal;
    vec3 tapP = surfacePoint(tapPixel, tapCode, tapNormal);
    float delta = dot(n, tapP - P);
    float normalWeight = normalSimilarity(n, tapNormal);
#else
    float delta = u_near + tapCode * (1.0 / 65535.0) * u_depthRange - z;
    float normalWeight = 1.0;
#endif
    float weight = exp(-float(i * i) * gaussianK - delta * delta * u_invSigma2) * normalWeight;
    // Taps on the background or outside the image contribute nothing.
    bool outside = tapPixel.x < 0.0 || tapPixel.y < 0.0 || tapPixel.x >= u_aoSize.x || tapPixel.y >= u_aoSize.y;
    if (isBackgroundCode(tapCode) || outside) weight = 0.0;
    sum += tap.r * weight;
    weightSum += weight;
  }
  gl_FragColor = vec4(sum / weightSum, key, 1.0);
}
