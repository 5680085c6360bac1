// Scalable Ambient Obscurance (McGuire, Mara, Luebke, HPG 2012) from the one-texture G-buffer.
// CPU mirror: src/core/SaoKernel.h (equations and constants documented there).
//
// Compile-time constants (one program per variant, so every loop bound is constant as GLSL ES 1.00 requires):
//   NUM_SAMPLES        taps per pixel (s)
//   NUM_SPIRAL_TURNS   turns of the tap spiral (tau), coprime with NUM_SAMPLES
//   FALLOFF_SAO2012    1: SAO's smooth (r^2 - v.v)^3 falloff; 0: Alchemy 2011's hard cut at r
//   DEPTH_HIERARCHY    0: every tap reads the G-buffer
//                      1: far taps read levels 1..MAX_MIP_LEVEL, each its own texture (core GLES 2)
//                      2: far taps read levels of one mipmapped texture with texture2DLodEXT (extension path)
//                      3: every tap reads levels 0..5, regions of one atlas texture (one fetch, no branch)
//   MAX_MIP_LEVEL, LOG_MAX_OFFSET   the hierarchy's depth and the SAO paper's level choice (see tapDepthCode)
//
// Output: R = ambient visibility A, GB = the centre's 16-bit depth code (the blur's key), A = 1.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/reconstruct.glsl"
#include "lib/ao_resolution.glsl"

uniform sampler2D u_gbuffer;
uniform vec2 u_aoSize;          // this pass's target size: the G-buffer's, or half of it (floor)
uniform float u_projScale;      // pixels per metre at 1 m: height / (2 tan(fovy / 2)), at G-buffer resolution
uniform float u_radius;         // r, metres
uniform float u_bias;           // beta, metres
uniform float u_intensityScale; // sigma * 5 / s (SAO 2012) or sigma * 2 / s (Alchemy 2011)
uniform float u_contrast;       // k
uniform float u_maxRadiusPixels;
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

varying vec2 v_uv;
varying vec3 v_farRay;

const float kEpsilon = 0.01;  // SAO paper: large epsilon avoids over-darkening in cracks
const float kTwoPi = 6.28318530718;

// Interleaved gradient noise (Jimenez 2014): an arithmetic per-pixel hash in [0, 1).
float rotationAngle(vec2 pixel) {
  float inner = 0.06711056 * pixel.x + 0.00583715 * pixel.y;
  float noise = 52.9829189 * (inner - floor(inner));
  return kTwoPi * (noise - floor(noise));
}

// The surface point a tap at G-buffer pixel `tapPixel`, 2^log2TapDistance pixels from the centre, reads.
// SAO paper, sec. 3.3: a tap at distance h reads level m = clamp(floor(log2 h) - LOG_MAX_OFFSET, 0, MAX_MIP_LEVEL),
// so taps within 2^(LOG_MAX_OFFSET + 1) pixels read full resolution and each farther octave reads a level half as
// fine. Neighbouring pixels' far taps then land in the same few texels (cache hits), and the cost per pixel stops
// growing with the projected radius. Level m holds the real depth of one pixel per 2^m x 2^m block (no averaging)
// and that pixel's place in the block, so the point is rebuilt on that pixel's own ray.
vec3 tapPoint(vec2 tapPixel, float log2TapDistance) {
  vec2 pixel = tapPixel;
  vec4 texel;
#if DEPTH_HIERARCHY == 0
  texel = texture2D(u_gbuffer, (pixel + 0.5) / u_gbufferSize);
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
    texel = vec4(0.0, 0.0, texture2D(u_gbuffer, (pixel + 0.5) / u_gbufferSize).ba);  // RG: no offset in the block
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
  pixel = levelPixel * scale + channelsToBytes(texel.rg);
#endif
  return viewPositionOnRay(farPlaneRay((pixel + 0.5) / u_gbufferSize), unpackLinearDepth(texel.ba));
}

float tapObscurance(vec3 v, vec3 n) {
  float vv = dot(v, v);
  float vn = dot(v, n);
  float angular = max(vn - u_bias, 0.0) / (vv + kEpsilon);
#if FALLOFF_SAO2012
  float f = max(u_radius * u_radius - vv, 0.0) / (u_radius * u_radius);
  return f * f * f * angular;
#else
  return vv < u_radius * u_radius ? angular : 0.0;
#endif
}

void main() {
  // Integer pixel coordinates from the highp varying: gl_FragCoord is only mediump in GLSL ES 1.00 (exact to 2048).
  vec2 aoPixel = floor(v_uv * u_aoSize);
  vec2 pixel = gbufferPixelOf(aoPixel);
  vec2 uv = (pixel + 0.5) / u_gbufferSize;
  vec4 centre = texture2D(u_gbuffer, uv);
  float code = unpackDepthCode(centre.ba);
  if (isBackgroundCode(code)) {
    gl_FragColor = vec4(1.0);
    return;
  }
  vec3 C = viewPositionOnRay(farPlaneRay(uv), code * (1.0 / 65535.0));
  vec3 n = decodeNormal(centre.rg);

  // The world-space radius projected to pixels at the centre's depth, clamped (paper sec. 3.2).
  float diskRadius = min(u_projScale * u_radius / -C.z, u_maxRadiusPixels);
  float log2DiskRadius = log2(max(diskRadius, 1e-3));
  float spin = rotationAngle(aoPixel);

  float sum = 0.0;
  for (int i = 0; i < NUM_SAMPLES; i++) {
    float alpha = (float(i) + 0.5) * (1.0 / float(NUM_SAMPLES));
    float angle = alpha * (float(NUM_SPIRAL_TURNS) * kTwoPi) + spin;
    float tapDistance = alpha * diskRadius;
    // The texel holding the tap point; taps leaving the image read its edge, as in the SAO reference code.
    vec2 tapPixel = clamp(floor(pixel + 0.5 + tapDistance * vec2(cos(angle), sin(angle))), vec2(0.0),
                          u_gbufferSize - 1.0);
    // log2 of the tap distance from per-pixel and per-tap parts (the loop is unrolled: log2(alpha) folds away).
    sum += tapObscurance(tapPoint(tapPixel, log2(alpha) + log2DiskRadius) - C, n);
  }
  float visibility = pow(max(0.0, 1.0 - sum * u_intensityScale), u_contrast);
  gl_FragColor = vec4(visibility, bytesToChannels(channelsToBytes(centre.ba)), 1.0);
}
