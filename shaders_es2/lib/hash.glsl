// A hash of a 2D point to [0, 1) without bitwise operators or sin (Dave Hoskins, "Hash without Sine", 2014:
// hash12), the same in every precision GLSL ES 1.00's highp float gives. CPU mirror: src/frame/PixelHash.h.
float hash12(vec2 p) {
  vec3 p3 = fract(vec3(p.xyx) * 0.1031);
  p3 += dot(p3, p3.yzx + 33.33);
  return fract((p3.x + p3.y) * p3.z);
}
