// View-space position from linear depth along the pixel's ray (Gravas 2013, eq. 3.1.3), perspective or orthographic.
// CPU mirror: src/frame/ViewReconstruction.h, which derives the uniforms.
//   F(uv) = ((2 uv - 1) * farHalfExtent, -far)
//   P = (F.xy * (d * depthToRay.x + depthToRay.y), d * depthToRay.z + depthToRay.w)
// Perspective: depthToRay.xy = (1 - near/far, near/far), P on the eye's ray through F. Orthographic: (0, 1), P on the
// parallel ray through F. Both: depthToRay.zw = (near - far, -near), z = -(near + d (far - near)).
uniform vec2 u_farHalfExtent;   // the far plane's half size: far * (tan(fovx / 2), tan(fovy / 2)), or the ortho view's
uniform float u_farPlane;
uniform vec4 u_depthToRay;      // (xy scale, xy bias, z scale, z bias)
uniform float u_perspective;    // 1: perspective, 0: orthographic (the eye rays below)

vec3 farPlaneRay(vec2 uv) { return vec3((uv * 2.0 - 1.0) * u_farHalfExtent, -u_farPlane); }

// Two multiply-adds and two multiplies: as many as the perspective-only form's scalar multiply-add and vec3 scale.
vec3 viewPositionOnRay(vec3 farRay, float linearDepth) {
  return vec3(farRay.xy * (linearDepth * u_depthToRay.x + u_depthToRay.y),
              linearDepth * u_depthToRay.z + u_depthToRay.w);
}

// The ray the camera sees view-space point p along, from the eye's plane to p: p itself in perspective, along the
// view axis (0, 0, p.z) in orthographic projection (p.z < 0 for everything in front of the camera).
vec3 eyeRay(vec3 p) { return vec3(p.xy * u_perspective, p.z); }
vec3 eyeRayDirection(vec3 p) { return normalize(eyeRay(p)); }

// Where that ray starts: the eye, or the point of the eye's plane z = 0 behind p.
vec3 eyeRayOrigin(vec3 p) { return vec3(p.xy * (1.0 - u_perspective), 0.0); }

// The pixel uv that view-space point p projects to (the inverse of the ray): its x and y scaled onto the far plane.
vec2 uvOfViewPosition(vec3 p) {
  float toFarPlane = mix(1.0, u_farPlane / max(-p.z, 1e-20), u_perspective);
  return p.xy * toFarPlane / u_farHalfExtent * 0.5 + 0.5;
}
