// One triangle covering the viewport, with the far-plane ray of each pixel interpolated for view reconstruction
// (Gravas 2013, sec. 3.1.3.5: the ray comes "for free" from the rasterizer, and is exact since it is linear in uv).
// Passes that reconstruct nothing (colour passes: tone mapping, FXAA, the views) define FAR_RAY 0 and skip the
// varying, which CPU rasterisers pay for per pixel.
#ifndef FAR_RAY
#define FAR_RAY 1
#endif
// AT_FAR_PLANE 1: the triangle lies on the far plane (window depth 1), so a depth test LEQUAL passes only where
// nothing was drawn (the forward lighting's background).
#ifndef AT_FAR_PLANE
#define AT_FAR_PLANE 0
#endif

attribute vec2 a_position;  // (-1,-1), (3,-1), (-1,3)

varying vec2 v_uv;

#if FAR_RAY
#include "lib/reconstruct.glsl"
varying vec3 v_farRay;
#endif

void main() {
  v_uv = a_position * 0.5 + 0.5;
#if FAR_RAY
  v_farRay = farPlaneRay(v_uv);
#endif
#if AT_FAR_PLANE
  gl_Position = vec4(a_position, 1.0, 1.0);
#else
  gl_Position = vec4(a_position, 0.0, 1.0);
#endif
}
