// Auto exposure (effects/auto_exposure/AutoExposureEffect.h): the log-average luminance of the HDR scene colour,
// reduced to one texel by explicit decode, average and encode passes (a mipmap would average the bytes, not the
// values), adapted over time against a 1 x 1 history. CPU mirror: src/encoding/ExposureMetering.h.
//
// EXPOSURE_STAGE
//   0 meter    scene-color -> the meter grid: per 8 x 8 pixels, the weighted mean of log2 luminance and the weight
//              (black pixels weigh nothing)
//   1 reduce   a grid -> the next, per 16 x 16 texels, averaged by their weights
//   2 bins     the scattered histogram (128 x 64, counts in bytes) -> 128 x 1 bins, 16-bit counts
//   3 adapt    the last grid (<= 16 x 16) or the bins -> the adapted log-average and the exposure (1 x 1)
//   4 count    the histogram's points (auto_exposure/histogram.vert): the count its vertex chose
// METERING (stages 0 and 3): 0 average, 1 centre-weighted, 2 percentile (ExposureMetering::Metering).
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/exposure.glsl"

#if EXPOSURE_STAGE == 0
#include "lib/hdr.glsl"

uniform sampler2D u_color;  // scene-color, HDR-encoded
uniform vec2 u_frameSize;   // pixels
uniform vec2 u_centreScale; // uv - 0.5 to units of half the frame's height: (2 width / height, 2)

void main() {
  vec2 origin = floor(gl_FragCoord.xy) * 8.0;
  float sumWeight = 0.0, sumLog = 0.0;
  for (int y = 0; y < 8; y++) {
    for (int x = 0; x < 8; x++) {
      vec2 p = origin + vec2(float(x), float(y)) + 0.5;
      // Pixels past the frame's right or top edge (a partial block) weigh nothing; the fetch stays inside.
      float inside = (p.x < u_frameSize.x && p.y < u_frameSize.y) ? 1.0 : 0.0;
      vec2 uv = min(p, u_frameSize - 0.5) / u_frameSize;
      vec3 c = decodeHdr(texture2D(u_color, uv));
      float y709 = dot(c, vec3(0.2126, 0.7152, 0.0722));
      // Black (below 2^-16: an empty background, a shadow without ambient light) says nothing about the exposure.
      float lit = y709 >= EXPOSURE_BLACK ? 1.0 : 0.0;
      float l = clamp(log2(max(y709, EXPOSURE_BLACK)), EXPOSURE_MIN_LOG2, -EXPOSURE_MIN_LOG2);
#if METERING == 1
      vec2 d = (uv - 0.5) * u_centreScale;
      float w = inside * lit * exp(-2.0 * dot(d, d));
#else
      float w = inside * lit;
#endif
      sumWeight += w;
      sumLog += w * l;
    }
  }
  float mean = sumWeight > 0.0 ? sumLog / sumWeight : 0.0;
  gl_FragColor = vec4(packLog2(mean), packWeight(sumWeight * (1.0 / 64.0)));
}

#elif EXPOSURE_STAGE == 1

uniform sampler2D u_source;
uniform vec2 u_sourceSize;  // texels

void main() {
  vec2 origin = floor(gl_FragCoord.xy) * 16.0;
  float sumWeight = 0.0, sumLog = 0.0;
  for (int y = 0; y < 16; y++) {
    for (int x = 0; x < 16; x++) {
      vec2 p = origin + vec2(float(x), float(y)) + 0.5;
      float inside = (p.x < u_sourceSize.x && p.y < u_sourceSize.y) ? 1.0 : 0.0;
      vec4 t = texture2D(u_source, min(p, u_sourceSize - 0.5) / u_sourceSize);
      float w = inside * unpackWeight(t.ba);
      sumWeight += w;
      sumLog += w * unpackLog2(t.rg);
    }
  }
  float mean = sumWeight > 0.0 ? sumLog / sumWeight : 0.0;
  gl_FragColor = vec4(packLog2(mean), packWeight(sumWeight * (1.0 / 256.0)));
}

#elif EXPOSURE_STAGE == 2

uniform sampler2D u_histogram;  // 128 x 64: one count per byte

void main() {
  float u = gl_FragCoord.x * (1.0 / 128.0);
  float count = 0.0;
  for (int row = 0; row < 64; row++) {
    vec4 bytes = floor(texture2D(u_histogram, vec2(u, (float(row) + 0.5) * (1.0 / 64.0))) * 255.0 + 0.5);
    count += bytes.r + bytes.g + bytes.b + bytes.a;
  }
  gl_FragColor = vec4(packLinearDepth(count * (1.0 / 65535.0)), 0.0, 0.0);
}

#elif EXPOSURE_STAGE == 3

uniform sampler2D u_source;   // METERING 2: the 128 bins; otherwise the last grid (at most 16 x 16)
#if METERING != 2
uniform vec2 u_sourceSize;    // texels
#endif
uniform sampler2D u_history;  // the previous frame's result (1 x 1)
uniform float u_hasHistory;   // 0: none (the first frame, or after a drop): take the metered value as it is
uniform vec2 u_fraction;      // the step towards the metered value, 1 - e^(-speed dt): x brighter, y darker
uniform vec2 u_percentiles;   // METERING 2: the fractions of the samples between which they are averaged
uniform vec3 u_exposure;      // the EV range (min, max) and the compensation

// The metered log2 luminance and its weight (0: nothing lit was metered).
vec2 metered() {
#if METERING == 2
  float total = 0.0;
  for (int bin = 0; bin < 128; bin++)
    total += unpackDepthCode(texture2D(u_source, vec2((float(bin) + 0.5) * (1.0 / 128.0), 0.5)).rg);
  float from = total * u_percentiles.x, to = total * u_percentiles.y;
  float below = 0.0, sum = 0.0, weight = 0.0;
  for (int bin = 0; bin < 128; bin++) {
    float count = unpackDepthCode(texture2D(u_source, vec2((float(bin) + 0.5) * (1.0 / 128.0), 0.5)).rg);
    float inside = max(0.0, min(below + count, to) - max(below, from));
    sum += inside * (EXPOSURE_MIN_LOG2 + (float(bin) + 0.5) * (EXPOSURE_RANGE / 128.0));
    weight += inside;
    below += count;
  }
  return vec2(weight > 0.0 ? sum / weight : 0.0, weight);
#else
  float sumWeight = 0.0, sumLog = 0.0;
  for (int y = 0; y < 16; y++) {
    for (int x = 0; x < 16; x++) {
      vec2 p = vec2(float(x), float(y)) + 0.5;
      float inside = (p.x < u_sourceSize.x && p.y < u_sourceSize.y) ? 1.0 : 0.0;
      vec4 t = texture2D(u_source, min(p, u_sourceSize - 0.5) / u_sourceSize);
      float w = inside * unpackWeight(t.ba);
      sumWeight += w;
      sumLog += w * unpackLog2(t.rg);
    }
  }
  return vec2(sumWeight > 0.0 ? sumLog / sumWeight : 0.0, sumWeight);
#endif
}

void main() {
  // log2(0.18): the key the log-average is exposed to (ExposureMetering::kKeyLog2).
  const float key = -2.4739311;
  vec2 measured = metered();
  float previous = u_hasHistory > 0.5 ? unpackLog2(texture2D(u_history, vec2(0.5)).rg) : key;
  // A frame with nothing lit keeps the exposure it had (EV 0 without history).
  float target = measured.y > 0.0 ? measured.x : previous;
  float adapted = target;
  if (u_hasHistory > 0.5) adapted = previous + (target - previous) * (target > previous ? u_fraction.x : u_fraction.y);
  float ev = clamp(key - adapted, u_exposure.x, u_exposure.y) + u_exposure.z;
  gl_FragColor = vec4(packLog2(adapted), packLog2(ev));
}

#elif EXPOSURE_STAGE == 4

varying vec4 v_count;

void main() { gl_FragColor = v_count; }

#else
#error "unknown EXPOSURE_STAGE"
#endif
