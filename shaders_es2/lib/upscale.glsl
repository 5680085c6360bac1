// The upscale of the frame's result into the output (frame/Resolution.h): the display colour rendered at
// u_size = round(s W) x round(s H) texels, read at the output pixel's position, `uv` in [0, 1]^2 over the image.
// The includer declares `uniform sampler2D u_color` (the display colour, NEAREST, clamped to the edge; RGB sRGB, A
// its luma as FXAA reads it) after lib/precision.glsl. Every fetch is at a texel centre, NEAREST: the filters weight
// the texels by hand (on CPU rasterisers a LINEAR fetch costs four texels wherever it lands; FxaaEffect.h).
//
// UPSCALE 1: bilinear, the four texels around the point.
// UPSCALE 2: edge-adaptive, after AMD's FidelityFX Super Resolution 1.0 EASU (Lottes 2021, ffx_fsr1.h, MIT
//   licence; written here from its description for GLSL ES 1.00):
//   1. twelve texels around the point: the 2 x 2 quad f g / j k that holds it and the eight beside the quad's sides,
//             b c
//           e f g h
//           i j k l
//             n o
//   2. the local edge, from the luma: at each texel of the quad the gradient by central differences (x: east -
//      west, y: south - north), weighted bilinearly by the point's place in the quad, gives the edge's direction
//      (across it); how much of each difference is one-sided (|east - west| / max(|east - centre|, |centre -
//      west|), squared) gives its strength, 0 (flat or a lone line) .. 1 (a clean step);
//   3. a kernel over the twelve texels: Lanczos 2 approximated by the polynomial (25/16 (2/5 x^2 - 1)^2 - 9/16)
//      (w x^2 - 1)^2, its window w from 1/2 (no edge: a soft lobe) down to 0.21 (a strong edge: a sharp one), with
//      x the tap's distance in the edge's frame: distances across the edge grow by up to sqrt 2 (on diagonals) and
//      those along it shrink by up to 1/2 as the edge grows stronger, so the kernel reaches along the edge and not
//      across it;
//   4. deringing: the result clamped to the quad's smallest and largest colour, as EASU does.
//   UPSCALE_SHARPEN 1 adds an RCAS-like sharpening (FSR's robust contrast-adaptive sharpening): the result pulled
//   away from its four neighbours at one source texel (bilinear from the same twelve texels: no more fetches, and
//   no second pass over the output as RCAS takes) by a negative lobe of weight u_sharpness x up to 0.1875 (RCAS's
//   limit 1/4 - 1/16), as large as RCAS's hitMin and hitMax let it be without leaving [0, 1] (one lobe for the three
//   channels, so that the hue holds), then clamped to the quad's range like the upscale itself: it steepens edges and
//   never rings beyond them.
#ifndef UPSCALE_SHARPEN
#define UPSCALE_SHARPEN 0
#endif
// The quad's colour range below which the edge upscale is the bilinear one (step 0): two levels of 255.
#ifndef UPSCALE_FLAT
#define UPSCALE_FLAT (2.0 / 255.0)
#endif

#if UPSCALE_SHARPEN
uniform float u_sharpness;  // 0 .. 1
#endif

// The texel (x, y) from the quad's top left `base` (texel units, at the centre of texel f), `texel` = 1 / size.
vec4 upscaleTap(vec2 base, float x, float y, vec2 texel) { return texture2D(u_color, (base + vec2(x, y)) * texel); }

vec3 upscaleBilinear(vec2 uv, vec2 size, vec2 texel) {
  vec2 p = uv * size - 0.5;
  vec2 f = fract(p);
  vec2 base = floor(p) + 0.5;
  vec3 a = upscaleTap(base, 0.0, 0.0, texel).rgb;
  vec3 b = upscaleTap(base, 1.0, 0.0, texel).rgb;
  vec3 c = upscaleTap(base, 0.0, 1.0, texel).rgb;
  vec3 d = upscaleTap(base, 1.0, 1.0, texel).rgb;
  return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

// One quad texel's share of the edge: w its bilinear weight, lumas north, west, centre, east, south.
void easuEdge(inout vec2 direction, inout float strength, float w, float north, float west, float centre, float east,
              float south) {
  float dx = east - west;
  float dy = south - north;
  float sx = clamp(abs(dx) / max(max(abs(east - centre), abs(centre - west)), 1.0 / 32768.0), 0.0, 1.0);
  float sy = clamp(abs(dy) / max(max(abs(south - centre), abs(centre - north)), 1.0 / 32768.0), 0.0, 1.0);
  direction += vec2(dx, dy) * w;
  strength += (sx * sx + sy * sy) * w;
}

// One tap of the kernel: `offset` from the point to the texel's centre, in texels.
void easuTap(inout vec3 sum, inout float weight, vec2 offset, vec2 direction, vec2 stretch, float window,
             float clip, vec3 color) {
  vec2 v = vec2(dot(offset, direction), dot(offset, vec2(-direction.y, direction.x))) * stretch;
  float d2 = min(dot(v, v), clip);
  float base = 0.4 * d2 - 1.0;
  float lobe = window * d2 - 1.0;
  float w = (1.5625 * base * base - 0.5625) * (lobe * lobe);
  sum += color * w;
  weight += w;
}

vec3 upscaleEdge(vec2 uv, vec2 size, vec2 texel) {
  vec2 p = uv * size - 0.5;
  vec2 f = fract(p);
  vec2 base = floor(p) + 0.5;
  vec4 tf = upscaleTap(base, 0.0, 0.0, texel);
  vec4 g = upscaleTap(base, 1.0, 0.0, texel);
  vec4 j = upscaleTap(base, 0.0, 1.0, texel);
  vec4 k = upscaleTap(base, 1.0, 1.0, texel);
  vec3 low = min(min(tf.rgb, g.rgb), min(j.rgb, k.rgb));
  vec3 high = max(max(tf.rgb, g.rgb), max(j.rgb, k.rgb));
  // 0. Flat: the result is clamped to the quad's range (step 4), so where that range is within UPSCALE_FLAT, the
  // filter's result and the bilinear one differ by less: bilinear, without the eight other texels and the kernel.
  // Most of a frame is this smooth; a GPU or llvmpipe skips the rest there (CPU rasterisers that run both sides of
  // a branch do not save).
  vec3 range = high - low;
  if (max(range.r, max(range.g, range.b)) < UPSCALE_FLAT)
    return mix(mix(tf.rgb, g.rgb, f.x), mix(j.rgb, k.rgb, f.x), f.y);
  vec4 b = upscaleTap(base, 0.0, -1.0, texel);
  vec4 c = upscaleTap(base, 1.0, -1.0, texel);
  vec4 e = upscaleTap(base, -1.0, 0.0, texel);
  vec4 h = upscaleTap(base, 2.0, 0.0, texel);
  vec4 i = upscaleTap(base, -1.0, 1.0, texel);
  vec4 l = upscaleTap(base, 2.0, 1.0, texel);
  vec4 n = upscaleTap(base, 0.0, 2.0, texel);
  vec4 o = upscaleTap(base, 1.0, 2.0, texel);

  // 2. The edge at the point ("north" is -1 in y here, whichever way the image's rows run: the filter is symmetric).
  vec2 direction = vec2(0.0);
  float strength = 0.0;
  easuEdge(direction, strength, (1.0 - f.x) * (1.0 - f.y), b.a, e.a, tf.a, g.a, j.a);
  easuEdge(direction, strength, f.x * (1.0 - f.y), c.a, tf.a, g.a, h.a, k.a);
  easuEdge(direction, strength, (1.0 - f.x) * f.y, tf.a, i.a, j.a, k.a, n.a);
  easuEdge(direction, strength, f.x * f.y, g.a, j.a, k.a, l.a, o.a);
  float length2 = dot(direction, direction);
  direction = length2 < 1.0 / 32768.0 ? vec2(1.0, 0.0) : direction * inversesqrt(length2);
  strength *= 0.5;
  strength *= strength;
  // 1 along an axis, sqrt 2 along a diagonal: a diagonal edge's taps lie farther along it.
  float diagonal = 1.0 / max(abs(direction.x), abs(direction.y));
  // The kernel's frame: x across the edge (the gradient's direction), y along it.
  vec2 stretch = vec2(1.0 + (diagonal - 1.0) * strength, 1.0 - 0.5 * strength);
  float window = 0.5 - 0.29 * strength;
  float clip = 1.0 / window;

  // 3. The kernel.
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  easuTap(sum, weight, vec2(0.0, -1.0) - f, direction, stretch, window, clip, b.rgb);
  easuTap(sum, weight, vec2(1.0, -1.0) - f, direction, stretch, window, clip, c.rgb);
  easuTap(sum, weight, vec2(-1.0, 0.0) - f, direction, stretch, window, clip, e.rgb);
  easuTap(sum, weight, vec2(0.0, 0.0) - f, direction, stretch, window, clip, tf.rgb);
  easuTap(sum, weight, vec2(1.0, 0.0) - f, direction, stretch, window, clip, g.rgb);
  easuTap(sum, weight, vec2(2.0, 0.0) - f, direction, stretch, window, clip, h.rgb);
  easuTap(sum, weight, vec2(-1.0, 1.0) - f, direction, stretch, window, clip, i.rgb);
  easuTap(sum, weight, vec2(0.0, 1.0) - f, direction, stretch, window, clip, j.rgb);
  easuTap(sum, weight, vec2(1.0, 1.0) - f, direction, stretch, window, clip, k.rgb);
  easuTap(sum, weight, vec2(2.0, 1.0) - f, direction, stretch, window, clip, l.rgb);
  easuTap(sum, weight, vec2(0.0, 2.0) - f, direction, stretch, window, clip, n.rgb);
  easuTap(sum, weight, vec2(1.0, 2.0) - f, direction, stretch, window, clip, o.rgb);

  // 4. Deringing.
  vec3 color = clamp(sum / weight, low, high);

#if UPSCALE_SHARPEN
  // The four neighbours one texel away, bilinear from the twelve texels.
  vec3 west = mix(mix(e.rgb, tf.rgb, f.x), mix(i.rgb, j.rgb, f.x), f.y);
  vec3 east = mix(mix(g.rgb, h.rgb, f.x), mix(k.rgb, l.rgb, f.x), f.y);
  vec3 north = mix(mix(b.rgb, c.rgb, f.x), mix(tf.rgb, g.rgb, f.x), f.y);
  vec3 south = mix(mix(j.rgb, k.rgb, f.x), mix(n.rgb, o.rgb, f.x), f.y);
  vec3 low4 = min(min(west, east), min(north, south));
  vec3 high4 = max(max(west, east), max(north, south));
  // RCAS's limits: the most negative lobe that keeps (lobe (sum of 4) + c) / (4 lobe + 1) within [0, 1] given the
  // neighbours' range, per channel; the least of the channels' is taken.
  vec3 hitLow = min(low4, color) / max(4.0 * high4, vec3(1.0 / 32768.0));
  vec3 hitHigh = (1.0 - max(high4, color)) / min(4.0 * low4 - 4.0, vec3(-1.0 / 32768.0));
  vec3 lobes = max(-hitLow, hitHigh);
  float lobe = max(-0.1875, min(max(lobes.r, max(lobes.g, lobes.b)), 0.0)) * u_sharpness;
  color = clamp((lobe * (west + east + north + south) + color) / (4.0 * lobe + 1.0), low, high);
#endif
  return color;
}

#if UPSCALE == 1
vec3 upscale(vec2 uv, vec2 size, vec2 texel) { return upscaleBilinear(uv, size, texel); }
#else
vec3 upscale(vec2 uv, vec2 size, vec2 texel) { return upscaleEdge(uv, size, texel); }
#endif
