// Motion blur: McGuire, Hennessy, Bukowski and Osman, "A Reconstruction Filter for Plausible Motion Blur" (I3D 2012;
// the SIGGRAPH 2012 talk "Scalable Motion Blur and Ambient Occlusion"). effects/motion_blur/MotionBlurEffect.h
// describes the passes.
//
// Every velocity here is the paper's half-vector V: half of a pixel's motion over the exposure, in pixels (the blur
// spans X - V .. X + V), clamped to the largest blur radius K (paper sec. 3, eq. 1). Stored between the passes in the
// velocity target's own packing (lib/packing.glsl: packVelocity), as V / frame size.
//
// MOTION_BLUR_PASS 1: tile columns: the largest V of each run of K pixels in a row, from the velocity target.
// MOTION_BLUR_PASS 2: tiles: the largest of each run of K tile columns in a column (with pass 1: TileMax, K x K).
// MOTION_BLUR_PASS 3: NeighborMax: the largest V of the 3 x 3 tiles around each tile.
// MOTION_BLUR_PASS 4: the reconstruction (paper, Algorithm 3, with each sample weighted as the share of the exposure
//   it stands for: see the loop), on the display colour.
#include "lib/precision.glsl"
#include "lib/packing.glsl"

uniform vec2 u_frameSize;  // the frame, pixels
// Pixel coordinates come from the highp varying, not gl_FragCoord: that is only mediump in GLSL ES 1.00, and a half
// float cannot hold a pixel centre beyond 1024 (llvmpipe really evaluates it so).
varying vec2 v_uv;

#if MOTION_BLUR_PASS == 1 || MOTION_BLUR_PASS == 4
uniform vec2 u_halfExposure;  // 0.5 * shutter * frame size: a velocity texel (uv per frame) -> V in pixels
uniform float u_maxRadius;    // K, pixels

// V of a velocity texel, its length clamped to K (the paper clamps to [0.5, K] as well; a zero motion stays zero
// here, and the weights below treat every length as at least half a pixel).
vec2 halfMotion(vec4 velocityTexel) {
  vec2 q = unpackVelocity(velocityTexel) * u_halfExposure;
  float len = length(q);
  return len > u_maxRadius ? q * (u_maxRadius / len) : q;
}
#endif

#if MOTION_BLUR_PASS == 1 || MOTION_BLUR_PASS == 2
// Along rows (pass 1), then along columns (pass 2).
#include "lib/tile_run.glsl"

void main() {
  vec2 first = tileRunFirst();
  vec2 largest = vec2(0.0);
  float largestLength = -1.0;
  for (int i = 0; i < MAX_TILE; i++) {
    vec4 texel;
    if (!tileRunTexel(first, i, texel)) break;
#if MOTION_BLUR_PASS == 1
    vec2 v = halfMotion(texel);
#else
    vec2 v = unpackVelocity(texel) * u_frameSize;
#endif
    float len = dot(v, v);
    if (len > largestLength) {
      largest = v;
      largestLength = len;
    }
  }
  gl_FragColor = packVelocity(largest / u_frameSize);
}
#endif

#if MOTION_BLUR_PASS == 3
uniform sampler2D u_tiles;
uniform vec2 u_tilesSize;  // texels (of the tiles read, and of the target written: the same)

void main() {
  vec2 centre = floor(v_uv * u_tilesSize) + 0.5;
  vec2 largest = vec2(0.0);
  float largestLength = -1.0;
  for (int y = -1; y <= 1; y++) {
    for (int x = -1; x <= 1; x++) {
      // Outside the frame the nearest edge tile counts again (the texture clamps to its edge).
      vec2 v = unpackVelocity(texture2D(u_tiles, (centre + vec2(float(x), float(y))) / u_tilesSize)) * u_frameSize;
      float len = dot(v, v);
      if (len > largestLength) {
        largest = v;
        largestLength = len;
      }
    }
  }
  gl_FragColor = packVelocity(largest / u_frameSize);
}
#endif

#if MOTION_BLUR_PASS == 4
uniform sampler2D u_color;        // display colour (sRGB; luma in alpha, a linear function of it: blended alike)
uniform sampler2D u_velocity;
uniform sampler2D u_gbuffer;
uniform sampler2D u_neighborMax;
uniform vec2 u_tilesSize;         // NeighborMax's texels
uniform float u_tile;             // K
uniform float u_near, u_depthRange;  // view depth = near + linear depth * (far - near)
uniform float u_alphaIsOne;       // 1: writing the output framebuffer (alpha 1); 0: keep the blended luma

// The paper's SOFT_Z_EXTENT, relative to depth here (as the AO blur's depth weights are), so that one setting holds
// at any scene scale: two samples within 5 % of each other's depth count as one surface.
const float kSoftDepth = 0.05;

float viewDepth(vec2 uv) {
  return u_near + unpackDepthCode(texture2D(u_gbuffer, uv).ba) * (1.0 / 65535.0) * u_depthRange;
}

// 1 where a surface at depth `a` is in front of one at depth `b`, falling to 0 once it is behind by the soft extent
// (the paper's softDepthCompare).
float inFront(float a, float b) { return clamp(1.0 - (a - b) / (kSoftDepth * min(a, b)), 0.0, 1.0); }
// Whether a pixel blurred by a half-vector of length `len` reaches `distance` pixels: the paper's cylinder test, a
// hard but antialiased edge (Algorithm 3).
float cylinder(float distance, float len) { return 1.0 - smoothstep(0.95 * len, 1.05 * len, distance); }

// Per-pixel jitter of the sample positions (Jimenez 2014, interleaved gradient noise): it turns the banding of S
// fixed taps into noise (paper sec. 4, "we jitter the sample positions").
float interleavedGradientNoise(vec2 pixel) {
  return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

void main() {
  vec2 x = floor(v_uv * u_frameSize) + 0.5;
  vec2 uvX = x / u_frameSize;
  vec4 colorX = texture2D(u_color, uvX);
  vec2 vN = unpackVelocity(texture2D(u_neighborMax, (floor(x / u_tile) + 0.5) / u_tilesSize)) * u_frameSize;
  float lengthN = length(vN);
  // Early exit where the neighbourhood barely moves (paper: "if |V_N| <= 0.5 + epsilon, return C[X]"): the pixel
  // is exactly what it was.
  if (lengthN <= 0.505) {
    gl_FragColor = vec4(colorX.rgb, mix(colorX.a, 1.0, u_alphaIsOne));
    return;
  }
  float lengthX = max(length(halfMotion(texture2D(u_velocity, uvX))), 0.5);
  float depthX = viewDepth(uvX);
  vec4 sum = vec4(0.0);
  float jitter = interleavedGradientNoise(x) - 0.5;
  for (int i = 0; i < SAMPLES; i++) {
    // S samples spread evenly over [-1, 1] along V_N, shifted by the jitter: each stands for 1/S of the exposure.
    float t = mix(-1.0, 1.0, (float(i) + jitter + 1.0) / float(SAMPLES + 1));
    vec2 y = clamp(floor(x + vN * t) + 0.5, vec2(0.5), u_frameSize - 0.5);
    vec2 uvY = y / u_frameSize;
    float distance = length(y - x);
    float depthY = viewDepth(uvY);
    float lengthY = max(length(halfMotion(texture2D(u_velocity, uvY))), 0.5);
    // The paper's classification of Y against X. In front, Y's own blur reaches X (a moving object's streak over a
    // still background); behind, X's blur uncovers Y (the background showing through a moving object's edge).
    // Both hold on one surface moving as one. Where neither does, X keeps its own colour for that part of the
    // exposure. The paper weights these cases by cones, by a double cylinder and X by 1 / |V[X]|; that blurred
    // the inside of a moving object's edge far too little against the accumulation reference (its own surface
    // outweighed the background uncovered 3 to 1), so each sample here counts as the share of the exposure it
    // stands for, with the cylinder tests deciding whether it reaches X (docs/temporal-effects.md).
    float reaches = inFront(depthY, depthX) * cylinder(distance, lengthY);
    float uncovers = inFront(depthX, depthY) * cylinder(distance, lengthX);
    float a = max(reaches, uncovers);
    sum += a * texture2D(u_color, uvY) + (1.0 - a) * colorX;
  }
  vec4 blurred = sum * (1.0 / float(SAMPLES));
  gl_FragColor = vec4(blurred.rgb, mix(blurred.a, 1.0, u_alphaIsOne));
}
#endif
