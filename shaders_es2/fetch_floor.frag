// The benchmark's floor for the SAO pass: the same number of G-buffer fetches per pixel (1 + NUM_SAMPLES), at the
// spiral's offsets for a typical disk (precomputed on the CPU, identical for every pixel so access is perfectly
// coherent), and no arithmetic beyond summing. SAO cost / this cost is how much the estimator's maths and its
// scattered taps add over bare bandwidth. Not used for rendering.
#include "lib/precision.glsl"

uniform sampler2D u_gbuffer;
uniform vec2 u_offsets[NUM_SAMPLES];  // uv offsets

varying vec2 v_uv;

void main() {
  vec4 sum = texture2D(u_gbuffer, v_uv);
  for (int i = 0; i < NUM_SAMPLES; i++) sum += texture2D(u_gbuffer, v_uv + u_offsets[i]);
  gl_FragColor = sum;
}
