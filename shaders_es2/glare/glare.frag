// Glare streaks (src/effects/glare/GlareEffect.h: the method, its source and the CPU mirror of the weights): one pass
// of Kawase's iterated streak filter along one ray from every pixel, on bloom's bright pass at 1/4 of the frame.
// Pass n takes 4 taps at s 4^n steps (s = 0 .. 3) towards the light, weighted a^(s 4^n) and normalised, so three
// passes reach 63 steps with the weight a^D of each. GLARE_LAST 1: the ray's last pass, which scales the streak by the
// intensity and adds the light gathered so far (earlier rays, the lens flare) from u_sum.
#include "lib/precision.glsl"
#include "lib/hdr.glsl"

uniform sampler2D u_source;  // RGB9E5: the bright pass, or the line's previous pass
uniform vec2 u_step;         // this pass's step between taps, in uv (from the pixel towards the light it gathers)
uniform vec4 u_weights;      // the taps' weights at 0, 1, 2, 3 steps
#if GLARE_LAST
uniform sampler2D u_sum;     // RGB9E5: the light gathered so far (the same size)
uniform float u_intensity;
uniform float u_hasSum;      // 0: nothing gathered yet (u_sum is not read)
#endif

varying vec2 v_uv;

// Outside the frame is dark (clamping to the edge would repeat an edge's light along the streak).
vec3 tap(vec2 uv) {
  vec2 inside = step(vec2(0.0), uv) * step(uv, vec2(1.0));
  return decodeHdr(texture2D(u_source, uv)) * (inside.x * inside.y);
}

void main() {
  vec3 streak = tap(v_uv) * u_weights.x + tap(v_uv + u_step) * u_weights.y + tap(v_uv + 2.0 * u_step) * u_weights.z +
                tap(v_uv + 3.0 * u_step) * u_weights.w;
#if GLARE_LAST
  streak *= u_intensity;
  if (u_hasSum > 0.5) streak += decodeHdr(texture2D(u_sum, v_uv));
#endif
  gl_FragColor = encodeHdr(streak);
}
