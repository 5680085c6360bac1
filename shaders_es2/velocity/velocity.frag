// Motion vectors: each pixel's screen-space motion since the previous frame, packed in RGBA8 (lib/packing.glsl:
// packVelocity, 16 bits per component). Both projections are unjittered, so temporal jitter is not motion.
// VELOCITY_CAMERA 1: the full-screen pass. Every pixel as if the scene stood still: its view position from the
//   G-buffer's depth, seen through the previous frame's camera (u_viewToPreviousClip); background pixels as
//   directions (w = 0), which only the camera's rotation moves. An orthographic camera sees no direction at a point of
//   its image (every ray is parallel): its background pixels move as the far plane does (w = 1).
// VELOCITY_CAMERA 0: the geometry drawn over it where something moves (geometry.vert with PREVIOUS 1 gives both clip
//   positions: the previous pose through the previous camera). ALPHA_MASK as in the G-buffer pass.
#include "lib/precision.glsl"
#include "lib/packing.glsl"

#if VELOCITY_CAMERA
#include "lib/reconstruct.glsl"
uniform sampler2D u_gbuffer;
uniform mat4 u_unjitteredProjection;
uniform mat4 u_viewToPreviousClip;  // previous projection x previous view x inverse(view), unjittered
varying vec2 v_uv;
varying vec3 v_farRay;
#else
#include "lib/material.glsl"
varying vec2 v_texcoord;
varying vec4 v_currentClip;
varying vec4 v_previousClip;
#endif

void main() {
#if VELOCITY_CAMERA
  vec4 gbuffer = texture2D(u_gbuffer, v_uv);
  float code = unpackDepthCode(gbuffer.ba);
  vec4 p = isBackgroundCode(code) ? vec4(v_farRay, 1.0 - u_perspective)
                                  : vec4(viewPositionOnRay(v_farRay, code * (1.0 / 65535.0)), 1.0);
  vec4 current = u_unjitteredProjection * p;
  vec4 previous = u_viewToPreviousClip * p;
#else
#if ALPHA_MASK
  if (alphaMasked(v_texcoord)) discard;
#endif
  vec4 current = v_currentClip;
  vec4 previous = v_previousClip;
#endif
  // Normalised device coordinates span 2 per screen; uv spans 1.
  // A point behind the previous camera (w <= 0) has no screen position: its motion clamps to the largest.
  vec2 velocity = 0.5 * (current.xy / current.w - previous.xy / max(previous.w, 1e-6));
  gl_FragColor = packVelocity(velocity);
}
