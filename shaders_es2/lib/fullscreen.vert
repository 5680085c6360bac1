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

// ENVIRONMENT_RAY 1 (with FAR_RAY): the eye's ray in the environment's frame too, for a cube-map lookup (the
// lighting's background: lib/environment.glsl, ENVIRONMENT_SKY_CUBE). The ray is linear in uv, and so is a fixed
// rotation of it: interpolated exactly, with nothing left to compute per pixel.
#ifndef ENVIRONMENT_RAY
#define ENVIRONMENT_RAY 0
#endif

attribute vec2 a_position;  // (-1,-1), (3,-1), (-1,3)

varying vec2 v_uv;

#if FAR_RAY
#include "lib/reconstruct.glsl"
varying vec3 v_farRay;
#endif
#if ENVIRONMENT_RAY
// The view's rotation into the environment's frame: the lighting's u_viewToEnvironment, under a name of its own, as a
// uniform both stages declare must have the same precision in both (GLSL ES 1.00, sec. 4.5.3).
uniform mat3 u_rayToEnvironment;
varying vec3 v_environmentRay;
#endif

void main() {
  v_uv = a_position * 0.5 + 0.5;
#if FAR_RAY
  v_farRay = farPlaneRay(v_uv);
#endif
#if ENVIRONMENT_RAY
  v_environmentRay = u_rayToEnvironment * eyeRay(v_farRay);
#endif
#if AT_FAR_PLANE
  gl_Position = vec4(a_position, 1.0, 1.0);
#else
  gl_Position = vec4(a_position, 0.0, 1.0);
#endif
}
