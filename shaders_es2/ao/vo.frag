// Volumetric obscurance (Loos, Sloan, "Volumetric Obscurance", I3D 2010) from the one-texture G-buffer.
//
// The paper defines the obscurance at C as the integral of an occupancy function around C times a compact kernel;
// with the kernel the indicator of a ball it is the occupied fraction of the ball, which the paper estimates with
// line samples (its "line integrals"): the ball is cut into segments along the lines of sight through sample points
// p of the disk it covers on screen, and the depth buffer says how much of each segment lies behind the visible
// surface, that is, inside solid (the height-field assumption). Here the ball has radius r (the AO radius) and the
// lines are the exact eye rays through the pixels the taps read, so the estimate holds under perspective at any
// place in the image; every length is in units of r, so the AO is the same for a scene and its radius scaled
// together.
//
// Per tap, along its eye ray u (unit, view space) parametrised by s (units of r) from a, the point where the ray
// crosses the plane z = C.z (relative to C, in units of r):
//   - the ball's chord: |a + s u| <= 1, s in [s0, s1] = -a.u -/+ sqrt((a.u)^2 - a.a + 1);
//   - the free half-space above the centre's tangent plane, lifted by the bias: n.(a + s u) > beta. The paper
//     measures the whole ball, so a flat plane is half occupied (its obscurance is 1/2) and one seen at a grazing
//     angle more or less than that; measuring only the part of the ball above the tangent plane (the usual fix)
//     makes every plane exactly unoccluded, whatever its angle, and a right-angle corner about 1/2;
//   - the surface the tap read at s_d: the segment beyond it is solid.
// L = the length of the chord above the tangent plane, F = the part of it in front of the surface, and
//     O = 1 - sum F / sum L,
// the occupied fraction of the half-ball above the tangent plane, sampled by line integrals (each line weighted by
// its length, so the sum is the paper's volume integral). The shared A = max(0, 1 - sigma O)^k
// (ao/ao_estimator.glsl) applies the fitted intensity.
//
// Sample points: VO_PAIRS points of the unit disk scaled to the projected radius h, on a Vogel (sunflower) spiral,
// point i at radius sqrt((i + 0.5)/N) (equal areas) and angle i x the golden angle pi (3 - sqrt 5), all rotated by
// a per-pixel angle (interleaved gradient noise), each with its mirror image -p: the paper's paired samples,
// 2 x VO_PAIRS taps. The depth buffer cannot tell how thick an occluder is, and a height field makes every surface
// solid to infinity behind it, so a thin object in front of the ball (a pillar before a wall) fills whole lines of it:
// a dark halo. The pair guesses instead: when the surface one sample read lies in front of the whole ball by more than
// kThinMargin r (an occluder that need not reach the ball) and its partner's does not, the sample takes its partner's
// free fraction (the surface mirrored through C, a locally planar guess). The margin is measured, not the paper's:
// on the built-in view at sigma = 1, k = 1 the pairs take MAE 0.064 -> 0.041 and Pearson 0.67 -> 0.83 with no margin,
// and a margin of r/2 gives 0.034 and 0.88 (r/4: 0.037, r: 0.049): a floor seen at a grazing angle lies a little
// in front of the ball below a wall's foot, and without a margin it counted as a thin occluder there.
//
// Compile-time constants, beside those of ao/ao_estimator.glsl:
//   VO_PAIRS   pairs of taps per pixel (SaoPass::mirroredPairs: floor(samples / 2), at least 1)
#include "ao/ao_estimator.glsl"

const float kGoldenAngle = 2.39996322973;  // pi (3 - sqrt 5), Vogel 1979
const float kThinMargin = 0.5;             // a surface this far (units of r) in front of the ball may be thin

// One line sample at the tap pixel: its chord length above the tangent plane (x), the free part of it (y), and
// whether the surface lay more than kThinMargin in front of the whole ball (z: 1 = a possibly thin occluder).
vec3 lineSample(AoCentre c, vec2 offset, float bias) {
  vec2 tapPixel = clamp(floor(c.pixel + 0.5 + offset), vec2(0.0), u_gbufferSize - 1.0);
  vec3 q = tapPoint(tapPixel, log2(max(length(offset), 1.0)));
  vec3 u = eyeRayDirection(q);  // the eye's ray through q, or the view axis in orthographic projection
  // a: the ray's point at the centre's depth, relative to C; the surface at s_d along the ray from there.
  float t = (q.z - c.position.z) / u.z;
  vec3 a = (q - u * t - c.position) * u_invRadius;
  float sd = t * u_invRadius;
  float au = dot(a, u);
  float halfChord = sqrt(max(au * au - dot(a, a) + 1.0, 0.0));
  float s0 = -au - halfChord, s1 = -au + halfChord;
  // Above the lifted tangent plane: n.a + s n.u > beta, a half-line towards the eye (n.u < 0) or away from it.
  float nu = dot(c.normal, u);
  float na = dot(c.normal, a);
  float st = (bias - na) / (abs(nu) > 1e-6 ? nu : 1e-6);
  float lo = nu > 0.0 ? max(s0, st) : s0;
  float hi = nu > 0.0 ? s1 : min(s1, st);
  float lengthAbove = max(hi - lo, 0.0);
  float free = clamp(min(hi, sd) - lo, 0.0, lengthAbove);
  return vec3(lengthAbove, free, step(sd, s0 - kThinMargin) * step(0.0, lengthAbove - 1e-6));
}

void main() {
  AoCentre c;
  if (!aoCentre(c)) {
    gl_FragColor = vec4(1.0);
    return;
  }
  float log2DiskRadius = log2(max(c.diskRadius, 1e-3));
  vec4 estimator = estimatorAt(log2DiskRadius);
  float spin = rotationAngle(c.aoPixel);

  float total = 0.0, free = 0.0;
  for (int i = 0; i < VO_PAIRS; i++) {
    float angle = float(i) * kGoldenAngle + spin;
    vec2 offset = sqrt((float(i) + 0.5) * (1.0 / float(VO_PAIRS))) * c.diskRadius * vec2(cos(angle), sin(angle));
    vec3 first = lineSample(c, offset, estimator.y);
    vec3 second = lineSample(c, -offset, estimator.y);
    // A sample behind a possibly thin occluder takes its partner's free fraction, unless both are.
    float firstFree = first.z > 0.5 && second.z < 0.5 ? first.x * second.y / max(second.x, 1e-6) : first.y;
    float secondFree = second.z > 0.5 && first.z < 0.5 ? second.x * first.y / max(first.x, 1e-6) : second.y;
    total += first.x + second.x;
    free += firstFree + secondFree;
  }
  float obscurance = total > 1e-6 ? clamp(1.0 - free / total, 0.0, 1.0) : 0.0;
  gl_FragColor = aoOutput(c, obscurance, estimator);
}
