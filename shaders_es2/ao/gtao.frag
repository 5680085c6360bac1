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
// near the centre, where occluders subtend most; XeGTAO's sample distribution power 2). A tap's point Q counts when
// it lies within r of the centre C: its horizon cosine is dot(normalize(Q - C), V), faded to the side's lowest
// value over the last FALLOFF_FRACTION of r (the reference's cut at r, smoothed so depth noise does not flicker).
// Thickness heuristic (GTAO course, sec. "thickness"): a height field makes every occluder infinitely thick behind
// its front face, so a thin object (a pillar, a railing) would hide the sky behind it for the whole slice. When a
// tap farther out lies lower than the horizon found so far, the occluder may have ended: the horizon falls a
// fraction THIN_OCCLUDER_BLEND of the way towards it.
//
// Fitted parameters (ao/ao_estimator.glsl): the obscurance O = 1 - V goes through the shared
// A = max(0, 1 - sigma O)^k; beta (a fraction of r) lifts the horizon of taps within beta r of the tangent plane
// (the same tessellation and depth-quantisation guard as SAO's bias).
//
// Compile-time constants, beside those of ao/ao_estimator.glsl:
//   GTAO_SLICES   slices per pixel (each rotated by pi / GTAO_SLICES, all by the per-pixel angle)
//   GTAO_STEPS    taps per side of a slice (so GTAO_SIDES x GTAO_SLICES x GTAO_STEPS taps in all)
//   GTAO_SIDES    2: both sides of each slice. 1 (small budgets): one side per pixel, picked at random in
//                 proportion to its open arc and weighted so that the expectation is the two-sided slice's (see
//                 main); the budget buys twice the steps, a longer horizon search, whose maximum misses fewer
//                 occluders than half as many taps (averaged over frames by the temporal AO, that bias would stay)
//   THIN_OCCLUDER_BLEND  the thickness heuristic's blend (0: a height field)
#include "ao/ao_estimator.glsl"

const float kPi = 3.14159265359;
const float kHalfPi = 1.57079632679;
const float kFalloffFraction = 0.05;  // the horizon fades out over the last twentieth of r

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

// The highest horizon cosine along one side of a slice (direction `side` in pixels, unit length).
float sideHorizon(AoCentre c, vec3 V, vec2 side, float jitter, float log2DiskRadius, float bias) {
  float horizon = -1.0;
  for (int s = 0; s < GTAO_STEPS; s++) {
    float fraction = (float(s) + jitter) * (1.0 / float(GTAO_STEPS));
    float tapDistance = max(fraction * fraction * c.diskRadius, 1.0);  // at least the neighbouring pixel
    vec2 tapPixel = clamp(floor(c.pixel + 0.5 + tapDistance * side), vec2(0.0), u_gbufferSize - 1.0);
    vec3 w = (tapPoint(tapPixel, log2(tapDistance)) - c.position) * u_invRadius;  // in units of r
    float distance = length(w);
    float cosine = dot(w, V) / max(distance, 1e-4);
    // Taps within beta r of the tangent plane do not occlude (the tangent plane itself is no occluder); the step is a
    // ramp over the next beta r (at least 0.01 r), so a tap does not flip in and out with depth quantisation.
    float aboveTangent = clamp((dot(w, c.normal) - bias) / max(bias, 0.01), 0.0, 1.0);
    float weight = clamp((1.0 - distance) * (1.0 / kFalloffFraction), 0.0, 1.0) * aboveTangent;
    float tapHorizon = mix(-1.0, cosine, weight);
    // Higher: the new horizon. Lower (and in range): the thickness heuristic's partial step down.
    float blend = tapHorizon > horizon ? 1.0 : float(THIN_OCCLUDER_BLEND) * step(0.001, weight);
    horizon = mix(horizon, tapHorizon, blend);
  }
  return horizon;
}

void main() {
  AoCentre c;
  if (!aoCentre(c)) {
    gl_FragColor = vec4(1.0);
    return;
  }
  float log2DiskRadius = log2(max(c.diskRadius, 1e-3));
  vec3 estimator = estimatorAt(log2DiskRadius);
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
#if GTAO_SIDES == 1
    // One side, drawn with probability o_s / (o_+ + o_-), its open arc's share (o_+ = 1/2 (cos gamma + gamma sin
    // gamma) + pi/4 sin gamma: eq. 10's half with h_1 = gamma + pi/2), and weighted (o_+ + o_-) a_s / o_s: its
    // expectation is a(h_0, h_1), the two-sided slice's, and the visibility stays in [0, 1].
    float openPlus = 0.5 * openSky + 0.25 * kPi * sinGamma;
    float sideSign = sideChoice * openSky < openPlus ? 1.0 : -1.0;
    float openSide = sideSign > 0.0 ? openPlus : openSky - openPlus;
    float cs = clamp(sideHorizon(c, V, sideSign * d, jitter, log2DiskRadius, estimator.y), -1.0, 1.0);
    visible += projectedLength * openSky * sideArc(cs, sideSign, gamma, cosGamma, sinGamma) / max(openSide, 1e-4);
    open += projectedLength * openSky;
#else
    float c1 = clamp(sideHorizon(c, V, d, jitter, log2DiskRadius, estimator.y), -1.0, 1.0);
    float c0 = clamp(sideHorizon(c, V, -d, jitter, log2DiskRadius, estimator.y), -1.0, 1.0);
    visible += projectedLength *
               (sideArc(c0, -1.0, gamma, cosGamma, sinGamma) + sideArc(c1, 1.0, gamma, cosGamma, sinGamma));
    open += projectedLength * openSky;
#endif
  }
  float visibility = clamp(visible / max(open, 1e-4), 0.0, 1.0);
  gl_FragColor = aoOutput(c, 1.0 - visibility, estimator);
}
