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
// Fitted parameters (lib/ao_estimator.glsl): the obscurance O = 1 - V goes through the shared
// A = max(0, 1 - sigma O)^k; beta (a fraction of r) lifts the horizon of taps within beta r of the tangent plane
// (the same tessellation and depth-quantisation guard as SAO's bias).
//
// Compile-time constants, beside those of lib/ao_estimator.glsl:
//   GTAO_SLICES   slices per pixel (each rotated by pi / GTAO_SLICES, all by the per-pixel angle)
//   GTAO_STEPS    taps per side of a slice (so 2 x GTAO_SLICES x GTAO_STEPS taps in all)
//   THIN_OCCLUDER_BLEND  the thickness heuristic's blend (0: a height field)
#include "lib/ao_estimator.glsl"

const float kPi = 3.14159265359;
const float kHalfPi = 1.57079632679;
const float kFalloffFraction = 0.2;  // the horizon fades out over the last fifth of r

// The cosine-weighted measure of the arc [h0, h1] about the projected normal at angle gamma (eq. 10).
float arcVisibility(float h0, float h1, float gamma) {
  float cosGamma = cos(gamma);
  float sinGamma = sin(gamma);
  return 0.25 * (-cos(2.0 * h0 - gamma) + cosGamma + 2.0 * h0 * sinGamma) +
         0.25 * (-cos(2.0 * h1 - gamma) + cosGamma + 2.0 * h1 * sinGamma);
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
    // Taps within beta r of the tangent plane do not occlude (the tangent plane itself is no occluder).
    float aboveTangent = step(bias, dot(w, c.normal));
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
  vec3 V = normalize(-c.position);
  float noise = rotationAngle(c.aoPixel) * (1.0 / kTwoPi);  // [0, 1)
  // The step jitter: a second, decorrelated fraction of the same hash.
  float jitter = fract(noise * 7.0 + 0.5);

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
    float gamma = sign(dot(projectedNormal, T)) * acos(cosGamma);

    float h0 = -acos(clamp(sideHorizon(c, V, -d, jitter, log2DiskRadius, estimator.y), -1.0, 1.0));
    float h1 = acos(clamp(sideHorizon(c, V, d, jitter, log2DiskRadius, estimator.y), -1.0, 1.0));
    h0 = gamma + max(h0 - gamma, -kHalfPi);
    h1 = gamma + min(h1 - gamma, kHalfPi);
    visible += projectedLength * arcVisibility(h0, h1, gamma);
    open += projectedLength * arcVisibility(gamma - kHalfPi, gamma + kHalfPi, gamma);
  }
  float visibility = clamp(visible / max(open, 1e-4), 0.0, 1.0);
  gl_FragColor = aoOutput(c, 1.0 - visibility, estimator);
}
