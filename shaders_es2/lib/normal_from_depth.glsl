// The view-space normal of a G-buffer pixel reconstructed from the depths of its four neighbours (gbuffer.normals
// reconstructed; Gravas 2013, sec. 3.1.4). CPU mirror: src/frame/NormalFromDepth.h.
//
// A central difference smears a normal across every depth edge, a one-sided one across half of them. Per direction,
// the lesser of the two one-sided differences (the one whose depth changes least) stays on the pixel's own surface
// wherever one side does: the tangent along x is P(x+1) - P or P - P(x-1), along y likewise, and n = t_x x t_y,
// turned towards the eye. Where the two steps agree (a plane), the tangent blends into the central difference, which
// halves the 16-bit depth's noise and does not flip with the choice of side. A neighbour outside the image or on the
// background never is the lesser. Where both differences of a direction cross a depth edge (a feature one pixel wide:
// both neighbours more than kNormalEdgeJump of the pixel's depth away), the reconstruction has no surface to follow
// and the caller's fallback normal is taken (the estimator's: the stored normal): tests/test_normals_from_depth.cpp
// measures the error and where it falls back.
// Needs lib/packing.glsl and lib/reconstruct.glsl.

const float kNormalEdgeJump = 0.1;  // a one-sided depth step beyond this fraction of the depth crosses an edge

// The 16-bit depth code of G-buffer pixel `pixel` (integer coordinates), or one far beyond the far plane where it is
// outside the image or the background (so its step is never the lesser). The steps are compared as codes, integers
// exactly represented: a scene and its camera scaled together choose the same sides (the scale test).
float neighbourCode(sampler2D gbuffer, vec2 size, vec2 pixel) {
  float code = unpackDepthCode(texture2D(gbuffer, (pixel + 0.5) / size).ba);
  bool outside = pixel.x < 0.0 || pixel.y < 0.0 || pixel.x > size.x - 1.0 || pixel.y > size.y - 1.0;
  return outside || isBackgroundCode(code) ? 1e9 : code;
}

vec3 pointOfCode(vec2 size, vec2 pixel, float code) {
  return viewPositionOnRay(farPlaneRay((pixel + 0.5) / size), code * (1.0 / 65535.0));
}

// The tangent along one axis from the pixel's point `centre` (depth code `code`) and its two neighbours': the lesser
// one-sided difference, blended towards the central one (half the depth quantisation's noise) as the two steps agree,
// so the choice between the sides, which flips at a tie, moves nothing.
vec3 axisTangent(vec2 size, vec2 pixel, vec2 axis, vec3 centre, float code, float before, float after) {
  vec3 back = centre - pointOfCode(size, pixel - axis, before), ahead = pointOfCode(size, pixel + axis, after) - centre;
  float stepBack = abs(code - before), stepAhead = abs(after - code);
  vec3 lesser = stepBack < stepAhead ? back : ahead;
  float agreement = clamp(1.0 - abs(stepBack - stepAhead) / (0.5 * (stepBack + stepAhead) + 1.0), 0.0, 1.0);
  return mix(lesser, 0.5 * (back + ahead), agreement);
}

// `code`: the pixel's own depth code. Returns `fallback` where a direction has no side on the pixel's surface.
vec3 normalFromDepth(sampler2D gbuffer, vec2 size, vec2 pixel, float code, vec3 fallback) {
  vec2 dx = vec2(1.0, 0.0), dy = vec2(0.0, 1.0);
  float left = neighbourCode(gbuffer, size, pixel - dx), right = neighbourCode(gbuffer, size, pixel + dx);
  float below = neighbourCode(gbuffer, size, pixel - dy), above = neighbourCode(gbuffer, size, pixel + dy);
  // The edge test in codes: kNormalEdgeJump of the view depth near + code (far - near) / 65535, u_depthToRay.w being
  // -near and .z near - far (perspective and orthographic alike).
  float edge = kNormalEdgeJump * (code + 65535.0 * u_depthToRay.w / u_depthToRay.z);
  if (min(abs(code - left), abs(right - code)) > edge || min(abs(code - below), abs(above - code)) > edge)
    return fallback;
  vec3 centre = pointOfCode(size, pixel, code);
  vec3 n = normalize(cross(axisTangent(size, pixel, dx, centre, code, left, right),
                           axisTangent(size, pixel, dy, centre, code, below, above)));
  return dot(n, eyeRay(centre)) > 0.0 ? -n : n;  // towards the camera (lib/reconstruct.glsl)
}
