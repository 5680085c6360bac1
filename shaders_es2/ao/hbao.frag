// Horizon-based ambient occlusion (Bavoil, Sainz, Dimitrov, "Image-Space Horizon-Based Ambient Occlusion",
// SIGGRAPH 2008 talk and sketch; Bavoil, Sainz, the chapter of the same name in ShaderX7, 2009; NVIDIA's HBAO+ in
// spirit) from the one-texture G-buffer.
//
// The talk's occlusion integral over the hemisphere, in azimuth theta and elevation alpha, and its closed form when
// the attenuation W is left out:
//     AO = 1/(2 pi) integral_theta integral_{t(theta)}^{h(theta)} W(omega) cos(alpha) d alpha d theta
//        = 1/N_d sum_directions (sin h - sin t)                (W = 1; N_d directions)
// where, in the slice of direction theta, t is the elevation of the surface's tangent and h the elevation of the
// horizon (the highest tap). With the attenuation W, the per-step form of the implementations (ShaderX7, NVIDIA's
// SDK sample) sums, along each direction, the rises of the horizon weighted by the attenuation at the tap that
// raised it:
//     AO_theta = sum_steps W(d_i) (sin h_i - sin h_{i-1}),   h_0 = the tangent t (raised by the angle bias),
//     h_i = max(h_{i-1}, elevation of tap i),
// which telescopes to the closed form when W = 1. W(d) = 1 - (d/r)^2, the talk's attenuation (d: the tap's distance
// from the centre; taps at or beyond r count nothing), with d in units of r here, so the AO is the same for a scene
// and its radius scaled together.
//
// Elevations are measured in the slice plane through the eye that holds the tap's own screen direction (every pixel
// on a screen line through the centre back-projects into that plane), from the direction perpendicular to the view
// vector V in it: at the image centre that is the paper's image plane; elsewhere the image-plane elevation (the
// tap's z over its xy length) tilts with the perspective and puts taps on a plane seen at a grazing angle above its
// tangent. The tangent's elevation comes from the G-buffer normal n (the talk reads a normal buffer too; ShaderX7's
// version differentiates the depth buffer instead): in the slice's frame (T, V), the tangent towards
// +T is perpendicular to n's projection (n.T, n.V), so sin t = -(n.T) / |(n.T, n.V)|, with n.V > 0 for every
// surface the camera sees. Each tap's slice is taken from the point it actually read (its pixel, or the depth
// hierarchy's pick for its block), so a tap on the tangent plane has h = t exactly; a direction's horizon is kept
// as the largest rise sin h - sin t above the tangent.
//
// Sampling (SaoPass::hbaoSampling): HBAO_DIRECTIONS directions, 2 pi / HBAO_DIRECTIONS apart, all rotated by a
// per-pixel angle (the paper's per-pixel random rotation, here interleaved gradient noise), each marched over
// HBAO_STEPS taps at ((s + jitter) / HBAO_STEPS) h pixels (the paper's jittered steps; at least one pixel), h the
// projected radius. Every tap is one G-buffer or hierarchy fetch: HBAO_DIRECTIONS x HBAO_STEPS per pixel.
//
// Obscurance: O = (1/N_d) sum_theta AO_theta, in [0, 1] for a surface the directions see from both sides (opposite
// directions' tangents have opposite sines); the shared A = max(0, 1 - sigma O)^k (ao/ao_estimator.glsl) applies
// the fitted intensity (the paper's "strength"). The fitted bias beta (a fraction of r) plays the paper's angle
// bias: each direction's horizon starts sin(atan beta) above the tangent's sine (atan beta: the elevation of a point
// beta r above the tangent plane at distance r, seen from a tangent at elevation 0), so depth and normal
// quantisation on a plane do not count.
//
// Compile-time constants, beside those of ao/ao_estimator.glsl:
//   HBAO_DIRECTIONS   directions per pixel (N_d)
//   HBAO_STEPS        taps per direction (N_s)
#include "ao/ao_estimator.glsl"

// A view-space point's place on the screen, up to a constant scale: in tangent units (x and y over depth), or x and y
// themselves in orthographic projection.
vec2 screenPosition(vec3 p) { return p.xy / mix(1.0, -p.z, u_perspective); }

// One direction's occlusion: the attenuated rises of its horizon (the per-step form above).
float directionOcclusion(AoCentre c, vec3 V, vec2 d, float jitter, float log2DiskRadius, float sinBias) {
  vec2 centreTangent = screenPosition(c.position);
  float horizon = sinBias;  // the largest rise sin h - sin t so far; starts at the angle bias
  float occlusion = 0.0;
  for (int s = 0; s < HBAO_STEPS; s++) {
    float tapDistance = max((float(s) + jitter) * (1.0 / float(HBAO_STEPS)) * c.diskRadius, 1.0);
    vec2 tapPixel = clamp(floor(c.pixel + 0.5 + tapDistance * d), vec2(0.0), u_gbufferSize - 1.0);
    vec2 readPixel;
    vec3 q = tapPoint(tapPixel, log2(tapDistance), readPixel);
    vec3 w = (q - c.position) * u_invRadius;  // in units of r
    // The slice through the eye holding this tap: its screen direction X from the centre, and the unit tangent T
    // of that plane perpendicular to V (the tap lies in the plane spanned by T and V).
    vec2 screen = screenPosition(q) - centreTangent;
    vec3 X = vec3(screen / max(length(screen), 1e-12), 0.0);
    vec3 T = normalize(X - dot(X, V) * V);
    float wT = dot(w, T), wV = dot(w, V);
    float nT = dot(c.normal, T), nV = dot(c.normal, V);
    float sinH = wV * inversesqrt(max(wT * wT + wV * wV, 1e-12));
    float sinT = -nT * inversesqrt(max(nT * nT + nV * nV, 1e-12));
    float rise = sinH - sinT;
    float distanceSquared = dot(w, w);
    // A tap counts within r (W > 0) when it raises the horizon. One that read the centre's own pixel (at the image
    // edge, or a hierarchy level's pick) has no slice: told by its pixel, not by its point, since a GPU may rebuild
    // the centre's point with other roundings (contracted products) than the tap's, and a point a rounding away from
    // the centre has a slice of any direction and a rise of up to 1 (NVIDIA, 2026-11-29: a flat plane at 0.63).
    if (distanceSquared < 1.0 && rise > horizon && any(notEqual(readPixel, c.pixel))) {
      occlusion += (1.0 - distanceSquared) * (rise - horizon);
      horizon = rise;
    }
  }
  return occlusion;
}

void main() {
  AoCentre c;
  if (!aoCentre(c)) {
    gl_FragColor = vec4(1.0);
    return;
  }
  float log2DiskRadius = log2(max(c.diskRadius, 1e-3));
  vec4 estimator = estimatorAt(log2DiskRadius);
  vec3 V = -eyeRayDirection(c.position);
  // Per-pixel rotation (interleaved gradient noise) and a decorrelated step jitter: the same hash at a transposed,
  // shifted pixel.
  float rotation = rotationAngle(c.aoPixel) * (1.0 / float(HBAO_DIRECTIONS));
  float jitter = radialJitter(c.aoPixel.yx + vec2(11.0, 7.0));
  // sin(atan(beta)): the angle bias.
  float sinBias = estimator.y * inversesqrt(1.0 + estimator.y * estimator.y);

  float sum = 0.0;
  for (int k = 0; k < HBAO_DIRECTIONS; k++) {
    float phi = float(k) * (kTwoPi / float(HBAO_DIRECTIONS)) + rotation;
    sum += directionOcclusion(c, V, vec2(cos(phi), sin(phi)), jitter, log2DiskRadius, sinBias);
  }
  gl_FragColor = aoOutput(c, sum * (1.0 / float(HBAO_DIRECTIONS)), estimator);
}
