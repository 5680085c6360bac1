// FXAA 3.11, quality path (Timothy Lottes, NVIDIA 2011, "FXAA_QUALITY__PRESET"), written for GLSL ES 1.00.
//
// Input: the display colour (sRGB-encoded, as FXAA expects: its thresholds are in perceptual units) with its luma in
// alpha, in a NEAREST target. Every pixel reads the 3x3 texel centres; only edge pixels read between texels (the
// search and the final resample), and they filter by hand (bilinear(): four texels). Lottes reads everything through
// LINEAR filtering, which costs a GPU nothing at texel centres, but on the CPU rasterisers WebGL 1 often runs on
// (llvmpipe, SwiftShader) a LINEAR fetch filters four texels wherever it lands: NEAREST took this pass from about 47
// to 35 ms on llvmpipe at 1280x720, and changed nothing measurable on SwiftShader (docs/benchmarks.md).
//
// FXAA_CLASSIFY 1: step 1 alone, for a target with a stencil buffer (src/effects/fxaa/FxaaEffect.h): pixels below the
// threshold are written as they are and their stencil cleared; edge pixels are discarded and keep stencil 1, and the
// full pass (FXAA_CLASSIFY 0) then runs on them only. Both variants share step 1's arithmetic, so they agree on
// which pixels are edges, and the image is the same as the full pass's alone.
//
// Per pixel:
//   1. local contrast: the luma range of the pixel and its 4 neighbours; below max(EDGE_THRESHOLD_MIN,
//      EDGE_THRESHOLD * max luma) the pixel is left alone (most of the image);
//   2. edge orientation from the 3x3 lumas' second differences (horizontal vs vertical), and the side of the pixel
//      the edge lies on (the neighbour with the larger gradient);
//   3. the search: from the half-pixel point between the pixel and that neighbour, step along the edge in both
//      directions until the luma there leaves the edge's mean by a quarter of its gradient. Steps grow with
//      distance (the preset's table, u_searchSteps, 1 pixel first; the last, long step is taken without a read);
//      the loop bound FXAA_SEARCH_STEPS is a compile-time constant and the loop ends once both ends are found;
//   4. the pixel is resampled towards the edge by the offset that puts its coverage where the nearer end implies,
//      or by the subpixel term (the 3x3 average's distance from the pixel, smoothed: (3 - 2c) c^2, squared, times
//      SUBPIX), whichever is larger.
//
// FXAA_PASS_THROUGH 1 (with FXAA_CLASSIFY 1): every pixel as step 1 leaves one below the threshold, the pass's draw
// around the scene's bounds on screen (src/effects/fxaa/FxaaEffect.cpp).
//
// UPSCALE 1 or 2 (frame/Resolution.h: the frame rendered below the output's size, FxaaEffect.h): the pass writes the
// output at its own size and also upscales (lib/upscale.glsl, UPSCALE 1 bilinear, 2 edge). Each output pixel runs
// steps 1 to 4 on the source texel under it (u_texel is the source's), then reads the upscale at its own point,
// moved by the resample offset of step 4 (zero where step 1 leaves the texel alone), so FXAA's work and the
// upscale's are done in one pass over the output.
#ifndef UPSCALE
#define UPSCALE 0
#endif
#ifndef FXAA_PASS_THROUGH
#define FXAA_PASS_THROUGH 0
#endif

#include "lib/precision.glsl"

uniform sampler2D u_color;          // RGB display colour, A its luma; NEAREST
uniform vec2 u_texel;               // 1 / size
uniform float u_edgeThreshold;      // 0.063 .. 0.333; default 0.166
uniform float u_edgeThresholdMin;   // 0.0312 .. 0.0833; default 0.0833
#if !FXAA_CLASSIFY || UPSCALE
uniform vec2 u_size;                // pixels (the source's, as the upscale's own pass takes it)
#endif
#if !FXAA_CLASSIFY
uniform float u_subpix;             // 0 (sharp) .. 1 (soft); Lottes' default 0.75
uniform float u_searchSteps[FXAA_SEARCH_STEPS];  // the preset's step lengths, pixels
#endif

varying vec2 v_uv;

#if UPSCALE
#include "lib/upscale.glsl"
vec3 upscaled(vec2 offset) { return upscale(v_uv + offset, u_size, u_texel); }
#endif

float lumaOff(vec2 uv, float x, float y) { return texture2D(u_color, uv + vec2(x, y) * u_texel).a; }

#if !FXAA_CLASSIFY
// What a LINEAR fetch at uv would return (clamped to the edge like it), from the four texels around uv.
vec4 bilinear(vec2 uv) {
  vec2 p = uv * u_size - 0.5;
  vec2 f = fract(p);
  vec2 t = (floor(p) + 0.5) * u_texel;
  vec4 a = texture2D(u_color, t);
  vec4 b = texture2D(u_color, t + vec2(u_texel.x, 0.0));
  vec4 c = texture2D(u_color, t + vec2(0.0, u_texel.y));
  vec4 d = texture2D(u_color, t + u_texel);
  return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

float lumaAt(vec2 uv) { return bilinear(uv).a; }
#endif

void main() {
#if UPSCALE
  vec2 posM = (floor(v_uv / u_texel) + 0.5) * u_texel;  // the source texel under the output pixel
#else
  vec2 posM = v_uv;
#endif
  vec4 rgbyM = texture2D(u_color, posM);
  float lumaM = rgbyM.a;
  float lumaS = lumaOff(posM, 0.0, 1.0);
  float lumaE = lumaOff(posM, 1.0, 0.0);
  float lumaN = lumaOff(posM, 0.0, -1.0);
  float lumaW = lumaOff(posM, -1.0, 0.0);

  float rangeMax = max(max(lumaN, lumaW), max(lumaE, max(lumaS, lumaM)));
  float rangeMin = min(min(lumaN, lumaW), min(lumaE, min(lumaS, lumaM)));
  float range = rangeMax - rangeMin;
  bool edge = range >= max(u_edgeThresholdMin, rangeMax * u_edgeThreshold);
#if FXAA_PASS_THROUGH
  edge = false;  // (the compiler drops the lumas and the rest)
#endif
#if UPSCALE
  // Where the upscale reads: the pixel's own point, moved by step 4's offset on an edge. One upscale at the end,
  // not one in each branch: SwiftShader runs a branch's code whether or not a pixel takes it (a copy in each branch
  // cost this pass 76 ms at 1280 x 720, against 56 to 58 for one; docs/resolution.md).
  vec2 resample = vec2(0.0);
  if (edge) {
#else
  if (!edge) {
    gl_FragColor = vec4(rgbyM.rgb, 1.0);
    return;
  }
  {
#endif
#if FXAA_CLASSIFY
  discard;  // an edge: left to the full pass, which the stencil now lets through here
#else

  float lumaNW = lumaOff(posM, -1.0, -1.0);
  float lumaSE = lumaOff(posM, 1.0, 1.0);
  float lumaNE = lumaOff(posM, 1.0, -1.0);
  float lumaSW = lumaOff(posM, -1.0, 1.0);

  // 2. Orientation: second differences across rows (a horizontal edge) and across columns (a vertical one).
  float lumaNS = lumaN + lumaS;
  float lumaWE = lumaW + lumaE;
  float edgeHorz = abs(-2.0 * lumaW + lumaNW + lumaSW) + abs(-2.0 * lumaM + lumaNS) * 2.0 +
                   abs(-2.0 * lumaE + lumaNE + lumaSE);
  float edgeVert = abs(-2.0 * lumaS + lumaSW + lumaSE) + abs(-2.0 * lumaM + lumaWE) * 2.0 +
                   abs(-2.0 * lumaN + lumaNW + lumaNE);
  bool horzSpan = edgeHorz >= edgeVert;
  // The subpixel term's input: the 3x3 low-pass (edges weighted 2, corners 1) against the pixel.
  float subpixA = (lumaNS + lumaWE) * 2.0 + (lumaNW + lumaSW + lumaNE + lumaSE);

  float lengthSign = horzSpan ? u_texel.y : u_texel.x;
  if (!horzSpan) {
    lumaN = lumaW;
    lumaS = lumaE;
  }
  float gradientN = abs(lumaN - lumaM);
  float gradientS = abs(lumaS - lumaM);
  float lumaNN = lumaN + lumaM;
  float lumaSS = lumaS + lumaM;
  bool pairN = gradientN >= gradientS;
  float gradient = max(gradientN, gradientS);
  if (pairN) lengthSign = -lengthSign;
  float subpixC = clamp(abs(subpixA * (1.0 / 12.0) - lumaM) / range, 0.0, 1.0);

  // 3. The search, from the point half a pixel towards the edge.
  vec2 posB = posM;
  if (horzSpan) posB.y += lengthSign * 0.5;
  else posB.x += lengthSign * 0.5;
  vec2 offNP = horzSpan ? vec2(u_texel.x, 0.0) : vec2(0.0, u_texel.y);
  vec2 posN = posB - offNP * u_searchSteps[0];
  vec2 posP = posB + offNP * u_searchSteps[0];
  if (!pairN) lumaNN = lumaSS;
  float gradientScaled = gradient * 0.25;
  float lumaMM = lumaM - lumaNN * 0.5;
  float lumaEndN = lumaAt(posN) - lumaNN * 0.5;
  float lumaEndP = lumaAt(posP) - lumaNN * 0.5;
  bool doneN = abs(lumaEndN) >= gradientScaled;
  bool doneP = abs(lumaEndP) >= gradientScaled;
  for (int i = 1; i < FXAA_SEARCH_STEPS; i++) {
    if (doneN && doneP) break;
    if (!doneN) posN -= offNP * u_searchSteps[i];
    if (!doneP) posP += offNP * u_searchSteps[i];
    // Lottes takes the last (long) step without reading there: an edge still going on is assumed to go on.
    if (i == FXAA_SEARCH_STEPS - 1) break;
    if (!doneN) {
      lumaEndN = lumaAt(posN) - lumaNN * 0.5;
      doneN = abs(lumaEndN) >= gradientScaled;
    }
    if (!doneP) {
      lumaEndP = lumaAt(posP) - lumaNN * 0.5;
      doneP = abs(lumaEndP) >= gradientScaled;
    }
  }

  // 4. The resample offset.
  float dstN = horzSpan ? posM.x - posN.x : posM.y - posN.y;
  float dstP = horzSpan ? posP.x - posM.x : posP.y - posM.y;
  bool lumaMLTZero = lumaMM < 0.0;
  bool goodSpan = dstN < dstP ? (lumaEndN < 0.0) != lumaMLTZero : (lumaEndP < 0.0) != lumaMLTZero;
  float pixelOffset = 0.5 - min(dstN, dstP) / (dstN + dstP);
  float subpixF = (3.0 - 2.0 * subpixC) * subpixC * subpixC;
  float offset = max(goodSpan ? pixelOffset : 0.0, subpixF * subpixF * u_subpix);
#if UPSCALE
  resample = horzSpan ? vec2(0.0, offset * lengthSign) : vec2(offset * lengthSign, 0.0);
#else
  if (horzSpan) posM.y += offset * lengthSign;
  else posM.x += offset * lengthSign;
  gl_FragColor = vec4(bilinear(posM).rgb, 1.0);
#endif
#endif
  }
#if UPSCALE
  gl_FragColor = vec4(upscaled(resample), 1.0);
#endif
}
