// What every obscurance estimator shares (shaders_es2/ao/sao.frag, gtao.frag): the G-buffer and its depth hierarchy,
// the centre pixel's surface, its projected radius and its fitted parameters, the per-pixel rotation, the surface
// point a tap reads, and the output layout. Each estimator's file is only its own sampling and integral.
//
// Compile-time constants:
//   DEPTH_HIERARCHY    0: every tap reads the G-buffer
//                      1: far taps read levels 1..MAX_MIP_LEVEL, each its own texture (core GLES 2)
//                      2: far taps read levels of one mipmapped texture with texture2DLodEXT (extension path)
//                      3: every tap reads levels 0..5, regions of one atlas texture (one fetch, no branch)
//   MAX_MIP_LEVEL, LOG_MAX_OFFSET   the hierarchy's depth and the SAO paper's level choice (see tapPoint)
//   ESTIMATOR_KNOTS, FIRST_KNOT_PIXELS  the knots of the fitted parameters (AoSettings.h)
//   AO_LAYERS          1: the G-buffer's depth; 2: also the second depth layer (ao.layers 2), through tapLayers
//   NORMALS_FROM_DEPTH 1: the centre's normal reconstructed from its neighbours' depths (gbuffer.normals
//                      reconstructed: lib/normal_from_depth.glsl), the stored one where that falls back
//
// Output: R = ambient visibility A, GB = the centre's 16-bit depth code (the blur's key), A = 1.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/reconstruct.glsl"
#include "ao/ao_resolution.glsl"
#include "ao/hierarchy_pick.glsl"
#include "lib/normal_from_depth.glsl"

uniform sampler2D u_gbuffer;
uniform vec2 u_aoSize;          // this pass's target size: the G-buffer's, or half of it (floor)
// Pixels per metre at depth z: x / z + y, at G-buffer resolution. Perspective (height / (2 tan(fovy / 2)), 0),
// orthographic (0, height / (2 ymag)): FrameCamera::projScale.
uniform vec2 u_projScale;
uniform float u_radius;         // r, scene units
uniform float u_invRadius;      // 1 / r
// The estimator's parameters at the knots h_j = FIRST_KNOT_PIXELS * 2^j pixels of projected radius (AoSettings.h):
// x = sigma * 5 / s (SAO 2012) or sigma * 2 / s (Alchemy 2011), y = beta as a fraction of r, z = contrast k,
// w = GTAO's one-layer occluder thickness as a fraction of r (the other estimators ignore it).
uniform vec4 u_estimatorKnots[ESTIMATOR_KNOTS];
uniform float u_maxRadiusPixels;
// Temporal AO's per-frame offsets (effects/ao/AoTemporal.h: frameOffset), as fractions: x of the taps' rotation (a
// turn), y of their distance jitter. (0, 0) without ao.temporal.
uniform vec2 u_frameOffset;
#if DEPTH_HIERARCHY == 1
uniform sampler2D u_level1;
uniform sampler2D u_level2;
uniform sampler2D u_level3;
uniform sampler2D u_level4;
uniform sampler2D u_level5;
#elif DEPTH_HIERARCHY == 2
uniform sampler2D u_depthMips;  // mip level j holds hierarchy level j + 1
uniform vec2 u_depthMipsSize;   // size of its mip level 0 (a power of two)
#elif DEPTH_HIERARCHY == 3
uniform sampler2D u_depthAtlas;  // level 0 at the origin, levels 1 .. 5 in a column right of it
uniform vec2 u_depthAtlasSize;
uniform vec4 u_atlasLevelRows;   // first rows of levels 2 .. 5 (level 1 starts at row 0)
#endif
#if AO_LAYERS == 2 && DEPTH_HIERARCHY != 3
uniform sampler2D u_secondLayer;  // the second layer's depth in BA (effects/ao/DepthPeelPass.h), for G-buffer taps
#endif

varying vec2 v_uv;
varying vec3 v_farRay;

const float kTwoPi = 6.28318530718;

// Interleaved gradient noise (Jimenez 2014): an arithmetic per-pixel hash in [0, 1).
float interleavedGradientNoise(vec2 pixel) {
  float inner = 0.06711056 * pixel.x + 0.00583715 * pixel.y;
  return fract(52.9829189 * fract(inner));
}

// The per-pixel rotation of the taps, turned by u_frameOffset.x of a turn: each frame of the temporal AO
// (ao.temporal, effects/ao/AoTemporal.h) samples new directions; 0 without it, which leaves the angle as it was.
float rotationAngle(vec2 pixel) { return kTwoPi * fract(interleavedGradientNoise(pixel) + u_frameOffset.x); }

// A per-pixel jitter of the tap distances in [0, 1), shifted by u_frameOffset.y per frame (as the rotation).
float radialJitter(vec2 pixel) { return fract(interleavedGradientNoise(pixel) + u_frameOffset.y); }

// The texel a tap at G-buffer pixel `tapPixel`, 2^log2TapDistance pixels from the centre, reads, and the G-buffer
// pixel whose depth it holds (`pixel`). BA: that pixel's depth code; with AO_LAYERS 2, RG: its second layer's.
// SAO paper, sec. 3.3: a tap at distance h reads level m = clamp(floor(log2 h) - LOG_MAX_OFFSET, 0, MAX_MIP_LEVEL),
// so taps within 2^(LOG_MAX_OFFSET + 1) pixels read full resolution and each farther octave reads a level half as
// fine. Neighbouring pixels' far taps then land in the same few texels (cache hits), and the cost per pixel stops
// growing with the projected radius. Level m holds the real depth of one pixel per 2^m x 2^m block (no averaging)
// and that pixel's place in the block (with AO_LAYERS 2, its closed form: ao/hierarchy_pick.glsl), so the point is
// rebuilt on that pixel's own ray.
vec4 tapTexel(vec2 tapPixel, float log2TapDistance, out vec2 pixel) {
  pixel = tapPixel;
  vec4 texel;
#if DEPTH_HIERARCHY == 0
  texel = texture2D(u_gbuffer, (pixel + 0.5) / u_gbufferSize);
#if AO_LAYERS == 2
  texel.rg = texture2D(u_secondLayer, (pixel + 0.5) / u_gbufferSize).ba;
#endif
#else
  float level = clamp(floor(log2TapDistance) - float(LOG_MAX_OFFSET), 0.0, float(MAX_MIP_LEVEL));
  float scale = exp2(level);
  vec2 size = max(floor(u_gbufferSize / scale), vec2(1.0));  // floor(size0 / 2^m), at least 1
  // SAO: ssP >> mipLevel, clamped to the level.
  vec2 levelPixel = min(floor(tapPixel / scale), size - 1.0);
#if DEPTH_HIERARCHY == 3
  // Branch-free: the level's region of the atlas (x: 0 for level 0, else the G-buffer's width; y: its first row).
  vec2 origin = vec2(step(0.5, level) * u_gbufferSize.x,
                     dot(u_atlasLevelRows, vec4(equal(vec4(level), vec4(2.0, 3.0, 4.0, 5.0)))));
  texel = texture2D(u_depthAtlas, (origin + levelPixel + 0.5) / u_depthAtlasSize);
#else
  if (level < 0.5) {
    vec2 uv = (pixel + 0.5) / u_gbufferSize;
#if AO_LAYERS == 2
    texel = vec4(texture2D(u_secondLayer, uv).ba, texture2D(u_gbuffer, uv).ba);
#else
    texel = vec4(0.0, 0.0, texture2D(u_gbuffer, uv).ba);  // RG: no offset in the block
#endif
  } else {
    vec2 uv = (levelPixel + 0.5) / size;
#if DEPTH_HIERARCHY == 1
    if (level < 1.5) texel = texture2D(u_level1, uv);
    else if (level < 2.5) texel = texture2D(u_level2, uv);
    else if (level < 3.5) texel = texture2D(u_level3, uv);
    else if (level < 4.5) texel = texture2D(u_level4, uv);
    else texel = texture2D(u_level5, uv);
#else
    // Mip level j of a power-of-two texture is u_depthMipsSize / 2^j texels; hierarchy level j + 1 fills its corner.
    texel = texture2DLodEXT(u_depthMips, uv * size * (0.5 * scale) / u_depthMipsSize, level - 1.0);
#endif
  }
#endif
  // The picked pixel: its block's corner plus its place in the block (0 at level 0).
#if AO_LAYERS == 2
  pixel = min(levelPixel * scale + hierarchyPickOffset(levelPixel, level), u_gbufferSize - 1.0);
#else
  pixel = levelPixel * scale + channelsToBytes(texel.rg);
#endif
#endif
  return texel;
}

// The surface point (view space) a tap reads: the first layer's; `pixel`: the G-buffer pixel whose depth it holds.
vec3 tapPoint(vec2 tapPixel, float log2TapDistance, out vec2 pixel) {
  vec4 texel = tapTexel(tapPixel, log2TapDistance, pixel);
  return viewPositionOnRay(farPlaneRay((pixel + 0.5) / u_gbufferSize), unpackLinearDepth(texel.ba));
}

vec3 tapPoint(vec2 tapPixel, float log2TapDistance) {
  vec2 pixel;
  return tapPoint(tapPixel, log2TapDistance, pixel);
}

#if AO_LAYERS == 2
// Both layers' points on the tap's pixel ray: `front` as tapPoint, `back` the second layer's (the far plane's where
// nothing lies behind: an occluder that does not end).
void tapLayers(vec2 tapPixel, float log2TapDistance, out vec3 front, out vec3 back) {
  vec2 pixel;
  vec4 texel = tapTexel(tapPixel, log2TapDistance, pixel);
  vec3 ray = farPlaneRay((pixel + 0.5) / u_gbufferSize);
  front = viewPositionOnRay(ray, unpackLinearDepth(texel.ba));
  back = viewPositionOnRay(ray, unpackLinearDepth(texel.rg));
}
#endif

// The centre of this AO pixel: its G-buffer pixel, view-space point and normal, and the radius projected to pixels
// at its depth, clamped (SAO paper sec. 3.2). False on the background.
struct AoCentre {
  vec2 aoPixel;
  vec2 pixel;       // G-buffer pixel
  vec2 depthBytes;  // the centre's depth code, as the output's GB
  vec3 position;    // C, view space
  vec3 normal;      // n
  float diskRadius; // h, G-buffer pixels
};

bool aoCentre(out AoCentre c) {
  c.aoPixel = floor(v_uv * u_aoSize);  // integer pixels from the highp varying: gl_FragCoord is only mediump
  c.pixel = gbufferPixelOf(c.aoPixel);
  vec2 uv = (c.pixel + 0.5) / u_gbufferSize;
  vec4 centre = texture2D(u_gbuffer, uv);
  c.depthBytes = centre.ba;
  float code = unpackDepthCode(centre.ba);
  if (isBackgroundCode(code)) return false;
  c.position = viewPositionOnRay(farPlaneRay(uv), code * (1.0 / 65535.0));
#if NORMALS_FROM_DEPTH
  c.normal = normalFromDepth(u_gbuffer, u_gbufferSize, c.pixel, code, decodeNormal(centre.rg));
#else
  c.normal = decodeNormal(centre.rg);
#endif
  c.diskRadius = min(u_radius * (u_projScale.x / -c.position.z + u_projScale.y), u_maxRadiusPixels);
  return true;
}

// This pixel's parameters (x: intensity scale, y: bias as a fraction of r, z: contrast, w: thickness): the knots'
// tent weights at t = log2(h / h_0), held at the ends (EstimatorKnots::interpolate).
vec4 estimatorAt(float log2DiskRadius) {
  float knot = clamp(log2DiskRadius - log2(float(FIRST_KNOT_PIXELS)), 0.0, float(ESTIMATOR_KNOTS - 1));
  vec4 estimator = vec4(0.0);
  for (int j = 0; j < ESTIMATOR_KNOTS; j++)
    estimator += u_estimatorKnots[j] * max(0.0, 1.0 - abs(knot - float(j)));
  return estimator;
}

// A = max(0, 1 - sigma' O)^k for the estimator's obscurance O (sigma' = the knot's intensity scale).
vec4 aoOutput(AoCentre c, float obscurance, vec4 estimator) {
  float visibility = pow(max(0.0, 1.0 - obscurance * estimator.x), estimator.z);
  return vec4(visibility, bytesToChannels(channelsToBytes(c.depthBytes)), 1.0);
}
