// Depth of field: a thin lens's circle of confusion, near and far fields gathered at half size by scatter as gather
// (Doerries 2018, sec. 3.2.6). effects/dof/DepthOfFieldEffect.h describes the passes; encoding/CocPacking.h the CoC's
// codes.
//
// C: the signed CoC, the blur disc's diameter in pixels of the full frame, negative in front of the focus. A tap's
// reach is measured in pixels of the half-size targets, where a disc of diameter C has the radius C / 4.
//
// DOF_PASS 1: the CoC from the G-buffer's depth.        5: the 3 x 3 tiles' largest near |C| (NeighborMax).
//          2: half-size colour and CoC.                  6: the near field.
//          3: tile columns' largest near |C|.            7: the far field.
//          4: tiles' largest near |C| (with 3: K x K).   8: the composite (a stage head: its colour goes to
//                                                           finishPixel, the stages fused after it).
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/hdr.glsl"
#include "dof/coc.glsl"

varying vec2 v_uv;

// The half-size fields hold linear HDR colour (the lens gathers light before the tone curve) as
// f = sqrt(c / (1 + c)) per channel in a byte (DepthOfFieldEffect.h: dofFieldEncode): invertible, a step of about
// 1/255 of sRGB's precision in the darks and mid-tones, up to 255 times display white. Each tap is decoded before the
// gather averages it.
vec3 toField(vec3 c) { return sqrt(c / (1.0 + c)); }
vec3 fromField(vec3 f) {
  vec3 f2 = f * f;
  return f2 / max(1.0 - f2, 1.0 / 255.0);
}

#if DOF_PASS == 1
uniform sampler2D u_gbuffer;
// (s, F, perspective): C = s (D - P) / (D (P - F)), s = A F H / h (pixel metres), F metres; perspective 0 (an
// orthographic camera, DepthOfFieldEffect.h): C = s (D - P) / (P (P - F)), linear in the distance from the focus.
uniform vec3 u_lens;
uniform float u_focus;      // P, metres (a fixed focus)
uniform float u_autofocus;  // 1: P is the depth at u_focusUv instead
uniform vec2 u_focusUv;
uniform vec2 u_depthRange;  // (near, far - near): view depth = near + linear depth (far - near)
uniform float u_range;      // the CoC range, pixels

float viewDepth(vec2 uv) {
  return u_depthRange.x + unpackDepthCode(texture2D(u_gbuffer, uv).ba) * (1.0 / 65535.0) * u_depthRange.y;
}

void main() {
  // The autofocus reads one texel of the G-buffer, the same for every pixel (no read-back to the CPU). The
  // background (code 65535) is at the far plane. A lens cannot focus nearer than its focal length.
  float focus = u_autofocus > 0.5 ? max(viewDepth(u_focusUv), 1.001 * u_lens.y) : u_focus;
  float depth = viewDepth(v_uv);
  // The thin lens (Samuelcik's deck: C = |A F (P - D) / (D (P - F))|), signed, in pixels.
  float coc = u_lens.x * (depth - focus) / (mix(focus, depth, u_lens.z) * (focus - u_lens.y));
  gl_FragColor = packCoc(coc, u_range);
}
#endif

#if DOF_PASS == 2
uniform sampler2D u_color;  // scene-color (HDR-encoded)
uniform sampler2D u_coc;    // dof-coc
uniform vec2 u_fullSize, u_halfSize;
uniform float u_range;

void main() {
  // The 2 x 2 block under this half-size texel: the mean colour, and the smallest (nearest) CoC, so that a block
  // holding any in-focus or near pixel does not join the far field (no in-focus colour spreads into the background's
  // blur) and a block touching the near field joins it.
  vec2 base = floor(v_uv * u_halfSize) * 2.0 + 0.5;
  vec3 sum = vec3(0.0);
  float smallest = 1e9;
  for (int y = 0; y < 2; y++) {
    for (int x = 0; x < 2; x++) {
      vec2 uv = (base + vec2(float(x), float(y))) / u_fullSize;
      sum += decodeHdr(texture2D(u_color, uv));
      smallest = min(smallest, unpackCoc(texture2D(u_coc, uv), u_range));
    }
  }
  gl_FragColor = vec4(toField(sum * 0.25), packHalfCoc(smallest, u_range));
}
#endif

#if DOF_PASS == 3 || DOF_PASS == 4
// Along rows (pass 3), then along columns (pass 4).
#include "lib/tile_run.glsl"
#if DOF_PASS == 3
uniform float u_range;
#endif

void main() {
  vec2 first = tileRunFirst();
  float largest = 0.0;  // bytes: the near |C| / range, rounded up
  for (int i = 0; i < MAX_TILE; i++) {
    vec4 texel;
    if (!tileRunTexel(first, i, texel)) break;
#if DOF_PASS == 3
    float b = ceil(clamp(-unpackCoc(texel, u_range) / u_range, 0.0, 1.0) * 255.0);
#else
    float b = floor(texel.r * 255.0 + 0.5);
#endif
    largest = max(largest, b);
  }
  gl_FragColor = vec4(bytesToChannels(vec2(largest, 0.0)), bytesToChannels(vec2(0.0)));
}
#endif

#if DOF_PASS == 5
uniform sampler2D u_tiles;
uniform vec2 u_tilesSize;  // texels (of the tiles read, and of the target written: the same)

void main() {
  vec2 centre = floor(v_uv * u_tilesSize) + 0.5;
  float largest = 0.0;
  for (int y = -1; y <= 1; y++) {
    for (int x = -1; x <= 1; x++) {
      // Outside the frame the nearest edge tile counts again (the texture clamps to its edge).
      largest = max(largest, texture2D(u_tiles, (centre + vec2(float(x), float(y))) / u_tilesSize).r);
    }
  }
  gl_FragColor = vec4(bytesToChannels(vec2(floor(largest * 255.0 + 0.5), 0.0)), bytesToChannels(vec2(0.0)));
}
#endif

#if DOF_PASS == 6 || DOF_PASS == 7
uniform sampler2D u_half;   // dof-half: RGB the colour as a field (toField), A the 8-bit CoC
uniform vec2 u_halfSize;
uniform float u_range;
#if DOF_PASS == 6
uniform sampler2D u_neighbors;
#else
uniform float u_maxRadius;  // the largest radius, full-frame pixels
#endif

#endif

#if DOF_PASS >= 6
// Per-pixel rotation of the taps (Jimenez 2014, interleaved gradient noise): the banding of T fixed taps becomes
// noise, which the bilinear upsampling of the composite softens.
float interleavedGradientNoise(vec2 pixel) {
  return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

// The golden angle, 2 pi (1 - 1 / phi): Vogel's spiral puts tap i at radius sqrt((i + 1/2) / T) of the disc, turned
// by it from tap i - 1, an even cover of the disc for any T.
const vec2 GOLDEN_TURN = vec2(-0.7373688, 0.6754903);  // (cos, sin) of 2.3999632

// The share of the disc one tap stands for, divided by the share of a sample's own blur disc one pixel of it
// scatters over: w = reach / r_s^2 here, times area / T (applied by the caller). `sampleRadius` in pixels of the
// target gathered from; a blur under half a pixel scatters over its own pixel only.
float scatterWeight(float sampleRadius, float dist) {
  return clamp(sampleRadius - dist + 0.5, 0.0, 1.0) / max(sampleRadius * sampleRadius, 0.25);
}
#endif

#if DOF_PASS == 6 || DOF_PASS == 7

void main() {
  vec2 p = floor(v_uv * u_halfSize) + 0.5;
#if DOF_PASS == 6
  // The near field: as wide as the largest near CoC of the tiles around, so that a foreground pixel's blur reaches
  // the in-focus pixels beside it.
  float nearest = floor(texture2D(u_neighbors, v_uv).r * 255.0 + 0.5) * (1.0 / 255.0) * u_range;
  if (nearest < 1.0) {
    gl_FragColor = vec4(0.0);
    return;
  }
  float radius = nearest * 0.25;
#else
  // The far field: within the pixel's own CoC; a pixel that is not far has none.
  vec4 centre = texture2D(u_half, p / u_halfSize);
  float own = unpackHalfCoc(centre.a, u_range);
  if (own <= 1.0) {
    gl_FragColor = vec4(0.0);
    return;
  }
  float radius = min(own * 0.25, u_maxRadius * 0.5);
#endif
  float angle = 6.2831853 * interleavedGradientNoise(p);
  vec2 direction = vec2(cos(angle), sin(angle));
  vec3 sum = vec3(0.0);
  float weights = 0.0;
  for (int i = 0; i < TAPS; i++) {
    vec2 offset = direction * (radius * sqrt((float(i) + 0.5) * (1.0 / float(TAPS))));
    direction = vec2(direction.x * GOLDEN_TURN.x - direction.y * GOLDEN_TURN.y,
                     direction.x * GOLDEN_TURN.y + direction.y * GOLDEN_TURN.x);
    vec2 q = floor(p + offset) + 0.5;  // the texel the tap lands on, and its true distance
    float dist = length(q - p);
    vec4 s = texture2D(u_half, q / u_halfSize);
    float c = unpackHalfCoc(s.a, u_range);
    vec3 color = fromField(s.rgb);
#if DOF_PASS == 6
    // Near samples only, each reaching as far as its own blur: those beyond SMALL_COC pixels (ramping in over the
    // next), whose blur the composite does not gather at full size.
    float w = clamp(-c - SMALL_COC, 0.0, 1.0) * scatterWeight(-c * 0.25, dist);
#else
    // Far samples only; one behind the centre reaches no further than the centre's own blur (it is hidden behind a
    // sharper surface), one in front as far as its own.
    float w = clamp(c - 1.0, 0.0, 1.0) * scatterWeight(min(c * 0.25, radius), dist);
#endif
    sum += w * color;
    weights += w;
  }
#if DOF_PASS == 6
  // Coverage: the sum of the scatter weights times the disc's area per tap (a disc under a pixel is one pixel).
  float coverage = min(weights * max(radius * radius, 0.25) * (1.0 / float(TAPS)), 1.0);
  vec3 color = weights > 0.0 ? sum / weights : vec3(0.0);
  gl_FragColor = vec4(toField(color * coverage), coverage);
#else
  gl_FragColor = vec4(weights > 0.0 ? toField(sum / weights) : centre.rgb, 1.0);
#endif
}
#endif

#if DOF_PASS == 8
uniform sampler2D u_color;  // scene-color, full size (HDR-encoded)
uniform sampler2D u_coc;    // dof-coc
uniform sampler2D u_near;   // dof-near, half size, LINEAR: premultiplied colour as a field, coverage
uniform sampler2D u_far;    // dof-far, half size, LINEAR: colour as a field where far (A 1), else zero
uniform sampler2D u_neighbors;  // dof-neighbors: the largest near |C| of the 3 x 3 tiles around
uniform vec2 u_fullSize;    // pixels
uniform float u_range;

// A small blur (a CoC up to SMALL_COC = 2.5 pixels) is gathered here at full size: the half-size fields would draw a
// blur of one or two pixels with their grid's coarseness (their 2 x 2 box and bilinear upsampling alone spread a
// pixel by about as much as such a disc). The taps are the 3 x 3 block (a disc of radius 1.25 reaches the next ring by
// a sliver only), each weighted as the fields' taps are (scatterWeight: the share of the pixel the sample's disc
// covers, over the disc's area): no noise, the disc's own shape, 9 taps.
// `coc`: the centre's signed CoC. A sample in front of the centre (nearer by half a pixel of CoC) reaches with its
// own blur (a foreground spreads over what is behind it); one at its depth or behind reaches no further than the
// centre's own blur (it is hidden behind a sharper surface). Samples under half a pixel of blur scatter nowhere but
// their own pixel, and the centre always counts.
vec3 smallBlur(vec2 p, vec3 sharp, float coc) {
  float centreWeight = scatterWeight(abs(coc) * 0.5, 0.0);
  vec3 sum = centreWeight * sharp;
  float weights = centreWeight;
  for (int y = -1; y <= 1; y++) {
    for (int x = -1; x <= 1; x++) {
      if (x == 0 && y == 0) continue;
      vec2 q = p + vec2(float(x), float(y));
      vec2 uv = q / u_fullSize;
      float c = unpackCoc(texture2D(u_coc, uv), u_range);
      float r = (c < coc - 0.5 ? abs(c) : min(abs(c), abs(coc))) * 0.5;
      float w = clamp(2.0 * abs(c) - 1.0, 0.0, 1.0) * scatterWeight(r, length(q - p));
      sum += w * decodeHdr(texture2D(u_color, uv));
      weights += w;
    }
  }
  return sum / weights;
}

void main() {
  vec3 sharp = decodeHdr(texture2D(u_color, v_uv));
  float coc = unpackCoc(texture2D(u_coc, v_uv), u_range);
  // The far field, filtered between its far texels only (premultiplied by 0 or 1): no in-focus colour enters.
  vec4 farField = texture2D(u_far, v_uv);
  vec3 farColor = farField.a > 0.002 ? fromField(farField.rgb / farField.a) : sharp;
  vec3 background = mix(sharp, farColor, clamp(coc - 1.0, 0.0, 1.0));
  // Small blurs at full size: a pixel whose |C| is at most SMALL_COC (handing over to the half-size fields over the
  // next pixel), and an in-focus pixel that a small near blur around may reach. Under half a pixel a pixel keeps its own
  // colour, and only a nearer neighbour's blur changes it: the focus plane stays as it is.
  float nearby = floor(texture2D(u_neighbors, v_uv).r * 255.0 + 0.5) * (1.0 / 255.0) * u_range;
  float size = abs(coc);
  if (size < SMALL_COC + 1.0 && (size > 0.5 || nearby > 0.5)) {
    vec2 p = floor(v_uv * u_fullSize) + 0.5;
    vec3 small = smallBlur(p, sharp, sign(coc) * min(size, SMALL_COC));
    background = coc > 0.0 ? mix(small, background, clamp(coc - SMALL_COC, 0.0, 1.0)) : small;
  }
  vec4 nearField = texture2D(u_near, v_uv);
  // The stages fused after the composite (the tone curve, ...: frame/Stage.h), or the HDR encoding alone.
  gl_FragColor = finishPixel(background * (1.0 - nearField.a) + fromField(nearField.rgb), stagePixel(v_uv));
}
#endif
