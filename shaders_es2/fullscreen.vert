// One triangle covering the viewport, with the far-plane ray of each pixel interpolated for view reconstruction
// (Gravas 2013, sec. 3.1.3.5: the ray comes "for free" from the rasterizer, and is exact since it is linear in uv).
#include "lib/reconstruct.glsl"

attribute vec2 a_position;  // (-1,-1), (3,-1), (-1,3)

varying vec2 v_uv;
varying vec3 v_farRay;

void main() {
  v_uv = a_position * 0.5 + 0.5;
  v_farRay = farPlaneRay(v_uv);
  gl_Position = vec4(a_position, 0.0, 1.0);
}
