// Distance fog (src/effects/fog/FogEffect.h, whose FogFactor is this shader's CPU mirror): the lit HDR colour blended
// towards the fog colour by lib/fog.glsl's factor at the pixel's distance from the camera, reconstructed from the
// G-buffer's linear depth.
#include "lib/precision.glsl"
#include "lib/hdr.glsl"
#include "lib/reconstruct.glsl"
#include "lib/fog.glsl"

uniform sampler2D u_color;    // "scene-color", HDR-encoded, NEAREST
uniform sampler2D u_gbuffer;  // linear depth in BA

varying vec2 v_uv;
varying vec3 v_farRay;

void main() {
  float code = unpackDepthCode(texture2D(u_gbuffer, v_uv).ba);
  bool background = isBackgroundCode(code);
  // The background's ray is the far-plane ray itself: only its direction counts.
  vec3 viewPosition = background ? v_farRay : viewPositionOnRay(v_farRay, code * (1.0 / 65535.0));
  vec3 ray = eyeRay(viewPosition);  // from the eye, or from its plane (the origin: only height fog reads it)
  float f = fogFactor(ray, viewPosition - ray, background);
  vec3 surface = decodeHdr(texture2D(u_color, v_uv));
  gl_FragColor = encodeHdr(mix(u_fogColor, surface, f));
}
