// Temporal AO (ao.temporal): this frame's raw AO (few taps, turned to new directions and distances each frame) mixed
// into the history of the previous frames, reprojected through the motion vectors. CPU mirror: effects/ao/AoTemporal.h.
//
// Per AO pixel, with C its view-space point and n its normal (the G-buffer's):
//   1. reprojection: the previous uv is uv - v, v the velocity target's motion (uv units, unjittered: TAA's sub-pixel
//      jitter is not motion); the history texel nearest it (packed bytes: no filtering);
//   2. rejection: the history texel's depth gives the point Q it saw, rebuilt through the previous frame's camera and
//      moved into this frame's view space (as if it stood still). The history is kept only where Q lies within
//      u_planeTolerance of C's tangent plane: a disocclusion (the history saw the object that uncovered C), another
//      surface (a depth step) or a surface turned away (Q leaves the plane) all fail it, while a sub-pixel jitter or
//      a slanted plane do not (a point moved along its own plane stays in it, as the bilateral blur's tangent-plane
//      weight reasons). Outside the screen, on the background or without history, it is dropped too;
//   3. rectification, only where something within the AO radius moves relative to C (a moving object's contact
//      shadow on a still floor, which keeps its depth and normal, would otherwise linger as a trail): the history's
//      AO is clamped to the range of this frame's raw AO in the 3x3 neighbourhood (the neighbourhood clamp of
//      temporal antialiasing) and the mean's memory is held to 2 kLagPixels / motion frames. Everywhere else the
//      history is not clamped: a few taps give skewed per-pixel values (often 1, sometimes dark), whose 3x3 range
//      often misses their mean, and a clamp everywhere biased the still room's AO light (docs/temporal-effects.md);
//   4. accumulation: a running mean of at most N frames, A = H + (a - H) / m with m = min(n + 1, N) and n the frames
//      the history holds (1 .. N, stored in A), 0 where it was rejected: the first N frames are an exact mean of
//      every frame seen, after that an exponential average with weight 1/N.
// The result is written with stochastic rounding to 8 bits (floor(255 A + u), u uniform per pixel and frame): a
// running mean rounded to the nearest level each frame would stall wherever (a - H) / m is under half a level
// (biased by up to N / 2 levels); rounded stochastically it is unbiased.
//
// Output (the ao-raw layout, so the blur reads it unchanged): R = AO, GB = the centre's depth code, A = n / 255.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/reconstruct.glsl"
#include "ao/ao_resolution.glsl"

uniform sampler2D u_aoRaw;     // this frame's AO (ao-raw layout)
uniform sampler2D u_history;   // the previous frame's output (this layout)
uniform sampler2D u_velocity;  // lib/packing.glsl: packVelocity
uniform sampler2D u_gbuffer;   // normals in RG
uniform vec2 u_aoSize;
uniform float u_historyValid;  // 1 when the history holds the previous frame of this AO, else 0
uniform float u_maxFrames;     // N
uniform float u_planeTolerance;  // scene units
uniform float u_ditherOffset;  // per frame, [0, 1)
// The previous frame's camera: its far-plane rays and depth scale (lib/reconstruct.glsl's uniforms, then), and the
// transform of its view space into this frame's.
uniform vec2 u_previousFarHalfExtent;
uniform vec4 u_previousDepthToRay;
uniform mat4 u_previousViewToView;
uniform vec2 u_diskScale;         // r times projScale: h = u_diskScale.x / -z + u_diskScale.y (AoCentre's)
uniform float u_maxRadiusPixels;
uniform float u_objectsMove;      // 1 when some instance's pose differs from the previous frame's
uniform vec2 u_tapRotation;       // this frame's turn of the velocity taps: (cos, sin)

varying vec2 v_uv;

// Relative motion (G-buffer pixels per frame) between the centre and a point within the AO radius above which the
// history is rectified (effects/ao/AoTemporal.h: kRelativeMotionPixels).
const float kRelativeMotion = 0.5;
// How far (G-buffer pixels) the accumulated AO may lag behind something moving nearby (kLagPixels: measured on the
// sliding box of tests/test_temporal_ao.cpp, where 1 left more noise in the uncovered band and 4 a faint trail).
const float kLagPixels = 2.0;

// A tap direction turned by this frame's rotation.
vec2 turned(vec2 d) {
  return vec2(u_tapRotation.x * d.x - u_tapRotation.y * d.y, u_tapRotation.y * d.x + u_tapRotation.x * d.y);
}

// The motion of G-buffer pixel `pixel` relative to `velocity`, in G-buffer pixels per frame.
float relativeMotion(vec2 pixel, vec2 velocity) {
  vec2 tapPixel = clamp(floor(pixel), vec2(0.0), u_gbufferSize - 1.0);
  return length((unpackVelocity(texture2D(u_velocity, (tapPixel + 0.5) / u_gbufferSize)) - velocity) * u_gbufferSize);
}

float interleavedGradientNoise(vec2 pixel) {
  float inner = 0.06711056 * pixel.x + 0.00583715 * pixel.y;
  return fract(52.9829189 * fract(inner));
}

void main() {
  vec2 aoPixel = floor(v_uv * u_aoSize);
  vec4 current = texture2D(u_aoRaw, (aoPixel + 0.5) / u_aoSize);
  vec2 depthBytes = channelsToBytes(current.gb);
  float code = depthBytes.x * 256.0 + depthBytes.y;
  if (isBackgroundCode(code)) {
    gl_FragColor = vec4(1.0, bytesToChannels(depthBytes), bytesToChannels(vec2(0.0)).x);
    return;
  }
  vec2 uv = (gbufferPixelOf(aoPixel) + 0.5) / u_gbufferSize;
  vec3 n = decodeNormal(texture2D(u_gbuffer, uv).rg);
  vec3 C = viewPositionOnRay(farPlaneRay(uv), code * (1.0 / 65535.0));

  // 1. Reprojection.
  vec2 velocity = unpackVelocity(texture2D(u_velocity, uv));
  vec2 previousUv = uv - velocity;

  // Does anything within the AO radius move relative to this pixel? Only there can a still surface's AO change
  // (a moving object's contact shadow on a still floor), and only when some object moves at all (u_objectsMove: a
  // camera moving through a still scene changes no AO; the reprojection follows it). 8 velocity taps, 4 at h on
  // the axes and 4 at h / 2 on the diagonals (h the projected radius), the pattern turned every frame
  // (u_tapRotation) so that what slips between the taps in one frame is caught in the next.
  float motion = 0.0;
  if (u_objectsMove > 0.5) {
    float h = min(u_diskScale.x / -C.z + u_diskScale.y, u_maxRadiusPixels);
    vec2 centrePixel = uv * u_gbufferSize;
    motion = max(motion, relativeMotion(centrePixel + h * turned(vec2(1.0, 0.0)), velocity));
    motion = max(motion, relativeMotion(centrePixel + h * turned(vec2(0.0, 1.0)), velocity));
    motion = max(motion, relativeMotion(centrePixel + h * turned(vec2(-1.0, 0.0)), velocity));
    motion = max(motion, relativeMotion(centrePixel + h * turned(vec2(0.0, -1.0)), velocity));
    motion = max(motion, relativeMotion(centrePixel + h * turned(vec2(0.354, 0.354)), velocity));
    motion = max(motion, relativeMotion(centrePixel + h * turned(vec2(-0.354, 0.354)), velocity));
    motion = max(motion, relativeMotion(centrePixel + h * turned(vec2(-0.354, -0.354)), velocity));
    motion = max(motion, relativeMotion(centrePixel + h * turned(vec2(0.354, -0.354)), velocity));
  }
  bool rectify = motion > kRelativeMotion;
  // The AO pixel whose G-buffer pixel (u_aoScale times it: ao/ao_resolution.glsl) is nearest the previous position.
  vec2 historyPixel = floor((previousUv * u_gbufferSize - 0.5) / u_aoScale + 0.5);
  vec4 history = texture2D(u_history, (historyPixel + 0.5) / u_aoSize);
  float historyCode = unpackDepthCode(history.gb);

  // 2. Rejection.
  vec2 historyUv = (gbufferPixelOf(historyPixel) + 0.5) / u_gbufferSize;
  vec2 previousRay = (historyUv * 2.0 - 1.0) * u_previousFarHalfExtent;
  float previousDepth = historyCode * (1.0 / 65535.0);
  vec3 Q = (u_previousViewToView *
            vec4(previousRay * (previousDepth * u_previousDepthToRay.x + u_previousDepthToRay.y),
                 previousDepth * u_previousDepthToRay.z + u_previousDepthToRay.w, 1.0)).xyz;
  bool inside = all(greaterThanEqual(historyPixel, vec2(0.0))) && all(lessThan(historyPixel, u_aoSize));
  bool kept = u_historyValid > 0.5 && inside && !isBackgroundCode(historyCode) &&
              abs(dot(n, Q - C)) <= u_planeTolerance;
  float frames = kept ? channelsToBytes(vec2(history.a)).x : 0.0;

  // 4. Accumulation.
  // Where something nearby moves, the mean also forgets faster: a history of m frames lags the moving object's
  // shadow by about m / 2 frames of its motion, held to kLagPixels.
  float maxFrames = rectify ? clamp(floor(2.0 * kLagPixels / motion), 1.0, u_maxFrames) : u_maxFrames;
  float m = min(frames + 1.0, maxFrames);
  float accumulated = current.r;
  if (kept) {
    float previous = channelsToBytes(vec2(history.r)).x * (1.0 / 255.0);
    if (rectify) {
      // 3. Rectification: the range of this frame's AO around the pixel (background neighbours, R = 1, left out).
      float low = current.r, high = current.r;
      for (int y = -1; y <= 1; y++) {
        for (int x = -1; x <= 1; x++) {
          vec4 tap = texture2D(u_aoRaw, (clamp(aoPixel + vec2(float(x), float(y)), vec2(0.0), u_aoSize - 1.0) + 0.5) /
                                            u_aoSize);
          if (!isBackgroundCode(unpackDepthCode(tap.gb))) {
            low = min(low, tap.r);
            high = max(high, tap.r);
          }
        }
      }
      previous = clamp(previous, low, high);
    }
    accumulated = previous + (current.r - previous) / m;
  }
  float level = floor(clamp(accumulated, 0.0, 1.0) * 255.0 + fract(interleavedGradientNoise(aoPixel) + u_ditherOffset));
  gl_FragColor = vec4((min(level, 255.0) + 0.25) * (1.0 / 255.0), bytesToChannels(depthBytes),
                      bytesToChannels(vec2(m)).x);
}
