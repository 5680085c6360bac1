// Screen-space ambient occlusion as CryEngine 2 introduced it (Mittring, "Finding Next Gen: CryEngine 2", SIGGRAPH
// 2007 course "Advanced Real-Time Rendering in 3D Graphics and Games", the SSAO section and its shader listing): the
// historical baseline, from the one-texture G-buffer.
//
// The original: sample points in a sphere around the centre C (not a hemisphere about the normal: the 2007 method
// reads no normals): the eight corners of a cube, repeated with lengths growing by 1 + 2.4/N per sample, turned per
// pixel by a rotation built from a vector of a tiled 4x4 random texture, each projected to the screen; a point counts
// as accessible where the depth buffer's surface there lies behind it, and a range check (the listing's
// fRangeIsInvalid) fades a sample to a neutral 1/2 as the surface there comes in front of the centre by a fraction
// of its depth. About half of the sphere lies behind any open plane, so the accessible fraction is about 1/2 there
// and the original greys every flat surface (its output, a + a^2 of the accessible fraction a, then lifts the
// whole image). Here:
//
// Kernel (fixed, CRYTEK_PAIRS pairs of mirrored points p and -p, 2 x CRYTEK_PAIRS taps): pair j's direction is point
// j of a spherical Fibonacci set on the upper hemisphere, z = 1 - (j + 0.5)/P, azimuth j x the golden angle
// pi (3 - sqrt 5) (equal areas: with the mirrors, evenly over the sphere); its length is
//     l_j = exp(-2.4 (1 - g_j)),   g_j = fract((j + 0.5) x 0.618034)   (golden-ratio sequence, decorrelated from z),
// log-uniform between e^-2.4 = 0.09 and 1: the continuous form of the listing's lengths, which grow by a factor
// 1 + 2.4/N per sample over N samples ((1 + 2.4/N)^N ~ e^2.4), so near points are as frequent as far ones per octave.
// Points are r' l_j d_j from C, r' = r (less where the projected radius is clamped, aoCentre). Measured on the
// built-in view at sigma = 1, k = 1: these lengths against cube-root ones (uniform in the ball's volume) MAE 0.059
// against 0.062, Pearson 0.74 against 0.53.
//
// Per-pixel rotation: the kernel is reflected about a unit vector drawn uniformly from the sphere with two
// decorrelated interleaved-gradient-noise values (arithmetic, in place of the listing's 4x4 random texture; the
// reflection is the common later form of its rotation). A reflection keeps the kernel's shape and its mirror
// symmetry.
//
// Occlusion test, depths in units of r' (the sphere is in view space, so the test does not depend on the scene's
// units): a point counts as occluded when the surface read at its projected pixel lies in front of it by more than
// beta (the fitted bias: depth quantisation) and by at most 1 (the range check: a surface more than r' in front of
// the point is taken as a separate occluder that does not reach it, as the reference ignores occluders beyond r).
// All or nothing, not the listing's fade to 1/2: a point above a plane then never counts, which the pair rule below
// needs. Measured on the built-in view at sigma = 1, k = 1 with the pair rule: range from the point MAE 0.059,
// Pearson 0.74; from the centre's depth (as the listing's) 0.061, 0.69; a fade to 1/2 over r' in front of the centre
// (the listing's, in units of r') 0.068, 0.62; none 0.066, 0.51 (a halo around every foreground object).
//
// Obscurance: the fraction of pairs whose two points are both occluded,
//     O = #{j : p_j and -p_j occluded} / CRYTEK_PAIRS.
// At most one point of a mirrored pair lies behind a plane through C, so every open plane gives O = 0 exactly, at
// every angle and rotation (the original's grey, rescaled away); a right-angle corner at C gives 1/2 (a pair escapes
// when either point lies in the free quadrant or its mirror, half of the directions), a fully enclosed point 1. It
// equals max(0, 2 f - 1) of the occluded fraction f whenever no pair is free on both sides; unlike 2 f - 1 it does not
// let a pair whose occluded point failed the range check (a floor seen at a grazing angle lies far in front of the
// points below it) cancel another pair's occlusion (built-in view, sigma = 1: MAE 0.067 -> 0.059, Pearson
// 0.64 -> 0.74). The shared A = max(0, 1 - sigma O)^k (ao/ao_estimator.glsl) applies the fitted intensity.
//
// Like the original, it compares depths at pixel centres (and, for far taps, at the depth hierarchy's pick for a
// block): on a plane seen at a grazing angle the depth changes across a pixel by more than beta r, so some points
// just above it test as occluded. That self-occlusion is Crytek's, and the tests exempt it (tests/test_sao.cpp).
//
// Compile-time constants, beside those of ao/ao_estimator.glsl:
//   CRYTEK_PAIRS   pairs of kernel points (SaoPass::mirroredPairs: floor(samples / 2), at least 1)
#include "ao/ao_estimator.glsl"

const float kGoldenAngle = 2.39996322973;     // pi (3 - sqrt 5): Fibonacci sphere azimuths
const float kGoldenFraction = 0.61803398875;  // (sqrt 5 - 1) / 2: the lengths' low-discrepancy sequence
const float kLengthSpan = 2.4;                // lengths e^-2.4 .. 1 (Mittring's listing: x (1 + 2.4/N) a sample)

// The G-buffer pixel a view-space point projects to (lib/reconstruct.glsl: uvOfViewPosition).
vec2 projectToPixel(vec3 p) { return floor(uvOfViewPosition(p) * u_gbufferSize); }

// 1 if the kernel point at `offset` (view space, scene units, from the centre) is occluded, else 0.
float pointOccluded(AoCentre c, vec3 offset, float invRadius, float bias) {
  vec3 p = c.position + offset;
  vec2 tapPixel = clamp(projectToPixel(p), vec2(0.0), u_gbufferSize - 1.0);
  vec3 q = tapPoint(tapPixel, log2(max(length(tapPixel - c.pixel), 1.0)));
  float inFront = (q.z - p.z) * invRadius;  // how far the surface lies in front of the point, in units of r'
  // A point behind the eye (a radius larger than the centre's distance) projects nowhere: not occluded.
  return step(bias, inFront) * step(inFront, 1.0) * step(p.z, 0.0);
}

void main() {
  AoCentre c;
  if (!aoCentre(c)) {
    gl_FragColor = vec4(1.0);
    return;
  }
  float log2DiskRadius = log2(max(c.diskRadius, 1e-3));
  vec4 estimator = estimatorAt(log2DiskRadius);
  // r', the sphere's radius: r, or less where the projected radius was clamped.
  float shrink = min(c.diskRadius / (u_radius * (u_projScale.x / -c.position.z + u_projScale.y)), 1.0);
  float radius = u_radius * shrink;
  float invRadius = u_invRadius / shrink;
  // The per-pixel reflection vector: uniform on the sphere from two decorrelated hash values.
  float cosTheta = radialJitter(c.aoPixel) * 2.0 - 1.0;
  float azimuth = rotationAngle(c.aoPixel.yx + vec2(11.0, 7.0));
  vec3 mirror = vec3(sqrt(max(1.0 - cosTheta * cosTheta, 0.0)) * vec2(cos(azimuth), sin(azimuth)), cosTheta);

  float bothOccluded = 0.0;
  for (int j = 0; j < CRYTEK_PAIRS; j++) {
    float z = 1.0 - (float(j) + 0.5) * (1.0 / float(CRYTEK_PAIRS));
    float angle = float(j) * kGoldenAngle;
    vec3 direction = vec3(sqrt(max(1.0 - z * z, 0.0)) * vec2(cos(angle), sin(angle)), z);
    float golden = (float(j) + 0.5) * kGoldenFraction;
    float len = exp(-kLengthSpan * (1.0 - (golden - floor(golden))));
    vec3 k = reflect(direction * (len * radius), mirror);
    bothOccluded += pointOccluded(c, k, invRadius, estimator.y) * pointOccluded(c, -k, invRadius, estimator.y);
  }
  gl_FragColor = aoOutput(c, bothOccluded * (1.0 / float(CRYTEK_PAIRS)), estimator);
}
