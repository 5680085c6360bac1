// Depth-aware upsampling of half-resolution AO to the G-buffer's resolution (joint bilateral upsampling).
//
// Each full-resolution pixel blends the four nearest half-resolution AO pixels with bilinear weights times a range
// weight: exp(-(delta / sigma)^2) with delta the candidate surface's distance from this pixel's tangent plane (view
// metres), times ((n . n_candidate + 1) / 2)^10, as in the blur. When no candidate lies on this pixel's surface
// (all weights vanish, e.g. a thin object seen by no half-resolution pixel), the candidate nearest the tangent
// plane is used, so AO never bleeds in from the background or from another surface.
//
// Output: R = AO, GB = this pixel's own depth code (the full-resolution key), A = 1.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/reconstruct.glsl"
#include "ao/ao_resolution.glsl"

uniform sampler2D u_ao;        // half-resolution AO (R) + depth code (GB)
uniform vec2 u_aoSize;
uniform sampler2D u_gbuffer;   // full resolution
uniform float u_invSigma2;     // 1 / sigma^2, scene units^-2 (sigma is a fraction of the AO radius)

varying vec2 v_uv;
varying vec3 v_farRay;

void main() {
  vec2 pixel = floor(v_uv * u_gbufferSize);
  vec4 g = texture2D(u_gbuffer, v_uv);
  float code = unpackDepthCode(g.ba);
  vec2 key = bytesToChannels(channelsToBytes(g.ba));
  if (isBackgroundCode(code)) {
    gl_FragColor = vec4(1.0, key, 1.0);
    return;
  }
  vec3 P = viewPositionOnRay(v_farRay, code * (1.0 / 65535.0));
  vec3 n = decodeNormal(g.rg);

  // AO pixel p stands for G-buffer pixel 2p: this pixel's position in AO pixels, and the 2x2 AO pixels around it.
  vec2 aoPosition = pixel / u_aoScale;
  vec2 base = floor(aoPosition);
  vec2 f = aoPosition - base;

  float sum = 0.0, weightSum = 0.0;
  float nearestAo = 1.0, nearestDelta = 1e20;
  for (int j = 0; j < 2; j++) {
    for (int i = 0; i < 2; i++) {
      vec2 offset = vec2(float(i), float(j));
      vec2 aoPixel = clamp(base + offset, vec2(0.0), u_aoSize - 1.0);
      vec4 candidate = texture2D(u_ao, (aoPixel + 0.5) / u_aoSize);
      float candidateCode = unpackDepthCode(candidate.gb);
      if (isBackgroundCode(candidateCode)) continue;
      vec2 candidateUv = (gbufferPixelOf(aoPixel) + 0.5) / u_gbufferSize;
      vec3 candidateP = viewPositionOnRay(farPlaneRay(candidateUv), candidateCode * (1.0 / 65535.0));
      vec3 candidateN = decodeNormal(texture2D(u_gbuffer, candidateUv).rg);
      float delta = abs(dot(n, candidateP - P));
      vec2 bilinear = mix(1.0 - f, f, offset);
      float weight = bilinear.x * bilinear.y * exp(-delta * delta * u_invSigma2) * normalSimilarity(n, candidateN);
      sum += candidate.r * weight;
      weightSum += weight;
      if (delta < nearestDelta) {
        nearestDelta = delta;
        nearestAo = candidate.r;
      }
    }
  }
  float ao = weightSum > 1e-4 ? sum / weightSum : nearestAo;
  gl_FragColor = vec4(ao, key, 1.0);
}
