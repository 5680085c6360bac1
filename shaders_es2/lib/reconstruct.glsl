// View-space position from linear depth along the pixel's far-plane ray (Gravas 2013, eq. 3.1.3).
// CPU mirror: src/frame/ViewReconstruction.h.
//   F(uv) = ((2 uv - 1) * farHalfExtent, -far)       P = F(uv) * (d * (1 - near/far) + near/far)
uniform vec2 u_farHalfExtent;   // far * (tan(fovx / 2), tan(fovy / 2))
uniform float u_farPlane;
uniform vec2 u_depthToRay;      // (1 - near/far, near/far)

vec3 farPlaneRay(vec2 uv) { return vec3((uv * 2.0 - 1.0) * u_farHalfExtent, -u_farPlane); }

// One multiply-add per pixel, then a vec3 scale.
vec3 viewPositionOnRay(vec3 farRay, float linearDepth) {
  return farRay * (linearDepth * u_depthToRay.x + u_depthToRay.y);
}
