// Ground-truth ambient occlusion (Jimenez, Wu, Pesce, Jarabo, "Practical Real-Time Strategies for Accurate Indirect
// Occlusion", SIGGRAPH 2016 course; Activision tech report ATVI-TR-16-01) from the one-texture G-buffer.
//
// The reference (obscura-reference) is the cosine-weighted visibility of the hemisphere within the radius r. GTAO
// evaluates that integral exactly for a height field: the hemisphere is cut into slices through the view vector V;
// in each slice, the horizons h_0 <= 0 <= h_1 (angles from V, towards the -d and +d sides of the slice's screen
// direction d) bound the visible arc, and its cosine-weighted measure about the slice's projected normal (angle
// gamma from V, length |n_p|) is (paper eq. 10)
//     a(h_0, h_1) = 1/4 (-cos(2 h_0 - gamma) + cos gamma + 2 h_0 sin gamma)
//                 + 1/4 (-cos(2 h_1 - gamma) + cos gamma + 2 h_1 sin gamma),
// with each horizon clamped to the hemisphere, gamma -/+ pi/2 (eq. 9). The visibility is then
//     V = sum_slices |n_p| a(h_0, h_1) / sum_slices |n_p| a(gamma - pi/2, gamma + pi/2):
// the paper's |n_p|-weighted mean over slices, divided by the same for an open sky. With many slices the
// denominator tends to 1 (the integral is exact); with the one or two slices a pixel can afford, it keeps an
// unoccluded surface at exactly 1 whatever its slices' angles, and the blur averages the rotations.
//
// Per slice side, STEPS taps march out to the projected radius h, at distances ((s + jitter) / STEPS)^2 h (dense
// near the centre, where occluders subtend most; XeGTAO's sample distribution power 2).
//
// Occluders with a thickness (ao.layers, ao.thickness). A height field makes every occluder infinitely thick behind
// its front face, so a thin object (a pillar, a railing) in front of a far surface hides the sky behind it for the
// whole slice: the halo. Here a tap occludes only the directions to the segment of its pixel's ray between its front
// point and its back point, clipped to the ball of radius r about the centre (the reference's cut at r): the back
// point is the second depth layer's (ao.layers 2, effects/ao/DepthPeelPass.h: for a closed occluder its back face),
// or, with one layer, the point ao.thickness r behind the front (a heuristic; per radius in pixels, the knots' w;
// docs/accuracy.md, "Thickness"). Two consecutive taps whose depth ranges overlap, within ao.surface-gap r, are one
// occluder: the quadrilateral between their segments is solid too (the first tap joins the centre's own surface this
// way), so a continuous surface occludes as the height field's horizon does, and only a gap in depth lets the sky
// through. The union of the occluded directions is kept per side as 8 sectors of u = a(direction) / a(hemisphere
// edge), the cosine-weighted share of the side's open arc between V and the direction (eq. 10's half: sideArc), so
// every sector weighs the same; each tap's interval covers sectors by fraction, and the side's visibility is the mean
// uncovered fraction. This is the visibility bitmask of Therrien, Levesque, Gilet ("Screen Space Indirect Lighting
// with Visibility Bitmasks", 2023) in GLSL ES 1.00's arithmetic (two vec4 of coverage, no bitwise operators),
// cosine-weighted, with the segments' connectivity for a pixel's few taps. With an unbounded thickness and every tap
// connected it is exactly the horizon integral above.
//
// Fitted parameters (ao/ao_estimator.glsl): the obscurance O = 1 - V goes through the shared
// A = max(0, 1 - sigma O)^k; beta (a fraction of r) fades out taps whose nearest occluding point lies within beta r
// of the tangent plane (the same tessellation and depth-quantisation guard as SAO's bias).
//
// Compile-time constants, beside those of ao/ao_estimator.glsl (AO_LAYERS among them):
//   GTAO_SLICES   slices per pixel (each rotated by pi / GTAO_SLICES, all by the per-pixel angle)
//   GTAO_STEPS    taps per side of a slice (so GTAO_SIDES x GTAO_SLICES x GTAO_STEPS taps in all)
//   GTAO_SIDES    2: both sides of each slice. 1 (small budgets): one side per pixel, picked at random in
//                 proportion to its open arc and weighted so that the expectation is the two-sided slice's (see
//                 main); the budget buys twice the steps, a longer search, which misses fewer occluders than half as
//                 many taps (averaged over frames by the temporal AO, that bias would stay)
#include "ao/ao_estimator.glsl"

const float kPi = 3.14159265359;
const float kHalfPi = 1.57079632679;
const float kFalloffFraction = 0.05;  // an occluder fades out over the last twentieth of r

// acos to about 0.01 rad with one square root (Lagarde's fit, as XeGTAO's XeGTAO_FastACos): GLSL's acos costs a
// polynomial and more on CPU rasterisers, and AO needs no more precision than this.
float fastAcos(float x) {
  float a = abs(x);
  float result = (-0.156583 * a + kHalfPi) * sqrt(1.0 - a);
  return x >= 0.0 ? result : kPi - result;
}

// The 4x4 Bayer index 0 .. 15 of a pixel: 4 B2(x mod 2, y mod 2) + B2(floor(x/2) mod 2, floor(y/2) mod 2) with the
// 2x2 matrix B2(a, b) = 2 |a - b| + b ([[0, 2], [3, 1]]), in arithmetic (GLSL ES 1.00 has no bitwise operators).
float bayer4(vec2 pixel) {
  vec2 low = mod(pixel, 2.0);
  vec2 high = mod(floor(pixel * 0.5), 2.0);
  return 4.0 * (2.0 * abs(low.x - low.y) + low.y) + 2.0 * abs(high.x - high.y) + high.y;
}

// One side's half of eq. 10, 1/4 (-cos(2h - gamma) + cos gamma + 2 h sin gamma), for the horizon of cosine c at
// angle h = sideSign * acos(c), clamped to the hemisphere (|h - gamma| <= pi/2). No cosine is evaluated: unclamped,
// cos(2h - gamma) = cos 2h cos gamma + sin 2h sin gamma with cos 2h = 2c^2 - 1 and sin 2h = 2 sin h c; clamped,
// h = gamma +- pi/2 and cos(2h - gamma) = -cos gamma.
float sideArc(float c, float sideSign, float gamma, float cosGamma, float sinGamma) {
  float h = sideSign * fastAcos(c);
  float limit = gamma + sideSign * kHalfPi;
  bool clamped = sideSign * (h - limit) > 0.0;
  float sinH = sideSign * sqrt(max(1.0 - c * c, 0.0));
  float cosTwiceHMinusGamma = clamped ? -cosGamma : (2.0 * c * c - 1.0) * cosGamma + 2.0 * sinH * c * sinGamma;
  return 0.25 * (-cosTwiceHMinusGamma + cosGamma + 2.0 * (clamped ? limit : h) * sinGamma);
}

uniform float u_surfaceGap;  // the depth gap two taps' segments may leave and still be one occluder, units of r

// The directions an occluder along one pixel's ray, the segment from `front` to `back` (view space), takes from the
// centre: x, y the u interval of its part within r of the centre (w + s (b - w), s in [s0, s1], inside the unit ball,
// units of r); z its weight; w 1 where any of it lies inside the ball. The segment fades out as its closest point to
// the centre nears r, over the last FALLOFF_FRACTION of r (the reference's cut at r, smoothed so depth quantisation
// does not flicker). One whose nearest point lies within beta r of the tangent plane does not occlude (the tangent
// plane itself is no occluder), with a ramp over the next beta r (at least 0.01 r) for the same reason.
vec4 occluderSpan(AoCentre c, vec3 front, vec3 back, vec3 V, float sideSign, float bias, float gamma, float cosGamma,
                  float sinGamma, float inverseOpen) {
  vec3 w = (front - c.position) * u_invRadius;
  vec3 e = (back - front) * u_invRadius;
  float ee = max(dot(e, e), 1e-8), we = dot(w, e);
  float discriminant = we * we - ee * (dot(w, w) - 1.0);
  float root = sqrt(max(discriminant, 0.0));
  float s0 = max((-we - root) / ee, 0.0), s1 = min((-we + root) / ee, 1.0);
  vec3 near = w + s0 * e, far = w + s1 * e;
  float inside = discriminant > 0.0 && s0 < s1 ? 1.0 : 0.0;
  vec3 closest = w + clamp(-we / ee, 0.0, 1.0) * e;
  float weight = inside * clamp((1.0 - length(closest)) * (1.0 / kFalloffFraction), 0.0, 1.0) *
                 clamp((dot(near, c.normal) - bias) / max(bias, 0.01), 0.0, 1.0);
  float uNear = sideArc(clamp(dot(near, V) / max(length(near), 1e-4), -1.0, 1.0), sideSign, gamma, cosGamma,
                        sinGamma) * inverseOpen;
  float uFar = sideArc(clamp(dot(far, V) / max(length(far), 1e-4), -1.0, 1.0), sideSign, gamma, cosGamma,
                       sinGamma) * inverseOpen;
  return vec4(min(uNear, uFar), max(uNear, uFar), weight, inside);
}

// The visible fraction of one side of a slice (direction `side` in pixels, unit length; `sideSign` +1 or -1; its open
// arc `openSide`): the mean uncovered fraction of its 8 sectors of u (see the top of the file). `thickness`: with one
// layer, how far behind each tap's front its occluder reaches, in scene units.
float sideVisibleFraction(AoCentre c, float centreBackDepth, vec3 V, vec2 side, float sideSign, float jitter,
                          float bias, float thickness, float gamma, float cosGamma, float sinGamma, float openSide) {
  vec4 occupiedLow = vec4(0.0), occupiedHigh = vec4(0.0);
  const vec4 kSectorLow = vec4(0.0, 0.125, 0.25, 0.375);
  float inverseOpen = 1.0 / max(openSide, 1e-4);
  // The previous tap's segment along the side: its u range, whether it reaches into the ball and its depths; first
  // the centre's, whose surface lies along the tangent plane (u = 1).
  float previousLo = 1.0, previousHi = 1.0, previousFrontDepth = -c.position.z, previousBackDepth = centreBackDepth;
  float previousInside = 1.0;
#if AO_LAYERS == 2
  float previousDistance = 0.0;  // pixels from the centre
#endif
  for (int s = 0; s < GTAO_STEPS; s++) {
    float fraction = (float(s) + jitter) * (1.0 / float(GTAO_STEPS));
    float tapDistance = max(fraction * fraction * c.diskRadius, 1.0);
    vec2 tapPixel = clamp(floor(c.pixel + 0.5 + tapDistance * side), vec2(0.0), u_gbufferSize - 1.0);
#if AO_LAYERS == 2
    vec3 point, backPoint;
    tapLayers(tapPixel, log2(tapDistance), point, backPoint);
#else
    vec3 point = tapPoint(tapPixel, log2(tapDistance));
    vec3 backPoint = point + thickness * eyeRayDirection(point);  // along the pixel's ray
#endif
    // The occluder along the tap's ray: the segment from its front point to its back point.
    vec4 span = occluderSpan(c, point, backPoint, V, sideSign, bias, gamma, cosGamma, sinGamma, inverseOpen);
    float tapLo = span.x, tapHi = span.y, weight = span.z, inside = span.w;
#if AO_LAYERS == 2
    // Where this tap's occluder is not the previous tap's surface (not joined, below), its edge lies somewhere
    // between the two taps, and the taps alone see it only from this one on: the band of a far surface beside a
    // silhouette then misses the occluder's near part. The occluder is taken to reach the midpoint, its expected
    // edge, at the tap's depths (its segment moved there along the side). Two layers only, whose segments are the
    // occluder's own depth extent (docs/accuracy.md, "Occluders to the midpoint": MAE 0.0404 -> 0.0390): one layer's
    // deep segments join most taps already (0.0434 -> 0.0429), for the same cost, a quarter more of the pass.
    vec3 edgeRay = farPlaneRay((c.pixel + 0.5 + 0.5 * (previousDistance + tapDistance) * side) / u_gbufferSize);
    vec4 edge = occluderSpan(c, edgeRay * (point.z / edgeRay.z), edgeRay * (backPoint.z / edgeRay.z), V, sideSign,
                             bias, gamma, cosGamma, sinGamma, inverseOpen);
    float reachesEdge = edge.z * inside;
    float apartLo = mix(tapLo, min(tapLo, edge.x), reachesEdge), apartHi = mix(tapHi, max(tapHi, edge.y), reachesEdge);
    previousDistance = tapDistance;
#else
    float apartLo = tapLo, apartHi = tapHi;
#endif
    // Two consecutive segments whose depth ranges overlap (within the gap) are one occluder: the quadrilateral
    // between them is solid too, and from the centre it covers the directions between its four corners. The join
    // ramps in over the last quarter of the gap, so a depth quantised differently does not flip it.
    float overlap = min(-backPoint.z, previousBackDepth) + u_surfaceGap * u_radius - max(-point.z, previousFrontDepth);
    float joined = previousInside * inside * clamp(overlap / max(0.25 * u_surfaceGap, 0.01) * u_invRadius, 0.0, 1.0);
    float lo = mix(apartLo, min(tapLo, previousLo), joined), hi = mix(apartHi, max(tapHi, previousHi), joined);
    previousLo = tapLo;
    previousHi = tapHi;
    previousInside = inside;
    previousFrontDepth = -point.z;
    previousBackDepth = -backPoint.z;
    occupiedLow = max(occupiedLow, weight * clamp((min(vec4(hi), kSectorLow + 0.125) - max(vec4(lo), kSectorLow)) *
                                                      8.0, 0.0, 1.0));
    occupiedHigh = max(occupiedHigh, weight * clamp((min(vec4(hi), kSectorLow + 0.625) -
                                                     max(vec4(lo), kSectorLow + 0.5)) * 8.0, 0.0, 1.0));
  }
  return 1.0 - dot(occupiedLow + occupiedHigh, vec4(0.125));
}

void main() {
  AoCentre c;
  if (!aoCentre(c)) {
    gl_FragColor = vec4(1.0);
    return;
  }
  float log2DiskRadius = log2(max(c.diskRadius, 1e-3));
  vec4 estimator = estimatorAt(log2DiskRadius);
  float thickness = estimator.w * u_radius;  // one layer: the knots' thickness at this radius in pixels
  vec3 V = -eyeRayDirection(c.position);
  // The slices' rotation: a 4x4 ordered (Bayer) pattern, so every 4x4 block holds 16 evenly spaced angles and the
  // bilateral blur (9 taps a direction at the medium preset) averages them all on a flat surface; the interleaved
  // gradient noise SAO uses left diagonal streaks where two slices per pixel sampled a wall's foot. The steps'
  // jitter keeps that noise.
  // With ao.temporal, each frame moves every angle by a fraction of the Bayer step (u_frameOffset.x of 1/16, a
  // Halton sequence), so 8 frames fill the 16 angles' gaps with 8 more each, and the steps' jitter moves too.
  float noise = (bayer4(c.aoPixel) + fract(0.5 + u_frameOffset.x)) * (1.0 / 16.0);  // [0, 1)
  float jitter = radialJitter(c.aoPixel);
#if GTAO_SIDES == 1
  float sideChoice = radialJitter(c.aoPixel.yx + vec2(5.0, 3.0));  // decorrelated from the steps' jitter
#endif

  // The depth of the centre's own back point: the first segment joins the centre's surface through it.
#if AO_LAYERS == 2
  vec3 centreFront, centreBack;
  tapLayers(c.pixel, 0.0, centreFront, centreBack);
  float centreBackDepth = -centreBack.z;
#else
  float centreBackDepth = -(c.position + thickness * eyeRayDirection(c.position)).z;
#endif
  float visible = 0.0, open = 0.0;
  for (int slice = 0; slice < GTAO_SLICES; slice++) {
    float phi = (float(slice) + noise) * (kPi / float(GTAO_SLICES));
    vec2 d = vec2(cos(phi), sin(phi));
    // The slice plane through V and the screen direction d; T is its tangent towards +d, perpendicular to V.
    vec3 direction = vec3(d, 0.0);
    vec3 T = normalize(direction - dot(direction, V) * V);
    vec3 axis = cross(T, V);
    vec3 projectedNormal = c.normal - axis * dot(c.normal, axis);
    float projectedLength = length(projectedNormal);
    float cosGamma = clamp(dot(projectedNormal, V) / max(projectedLength, 1e-4), -1.0, 1.0);
    float sinGamma = dot(projectedNormal, T) / max(projectedLength, 1e-4);
    float gamma = sign(sinGamma) * fastAcos(cosGamma);

    // An open sky: both horizons at the hemisphere's edge, eq. 10 = cos gamma + gamma sin gamma.
    float openSky = cosGamma + gamma * sinGamma;
    float openPlus = 0.5 * openSky + 0.25 * kPi * sinGamma;  // eq. 10's half with h_1 = gamma + pi/2
#if GTAO_SIDES == 1
    // One side, drawn with probability o_s / (o_+ + o_-), its open arc's share, and weighted (o_+ + o_-) a_s / o_s
    // with a_s = o_s f_s (f_s its visible fraction): its expectation is the two-sided slice's, and the visibility
    // stays in [0, 1].
    float sideSign = sideChoice * openSky < openPlus ? 1.0 : -1.0;
    float openSide = sideSign > 0.0 ? openPlus : openSky - openPlus;
    visible += projectedLength * openSky *
               sideVisibleFraction(c, centreBackDepth, V, sideSign * d, sideSign, jitter, estimator.y, thickness,
                                   gamma, cosGamma, sinGamma, openSide);
#else
    visible += projectedLength *
               (openPlus * sideVisibleFraction(c, centreBackDepth, V, d, 1.0, jitter, estimator.y, thickness, gamma,
                                               cosGamma, sinGamma, openPlus) +
                (openSky - openPlus) * sideVisibleFraction(c, centreBackDepth, V, -d, -1.0, jitter, estimator.y,
                                                           thickness, gamma, cosGamma, sinGamma, openSky - openPlus));
#endif
    open += projectedLength * openSky;
  }
  float visibility = clamp(visible / max(open, 1e-4), 0.0, 1.0);
  gl_FragColor = aoOutput(c, 1.0 - visibility, estimator);
}
