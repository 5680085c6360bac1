// Arithmetic packing into RGBA8 channels (GLSL ES 1.00 has no bitwise operators).
// CPU mirrors: src/encoding/LinearDepthPacking.h and src/encoding/NormalEncoding.h; tests hold them bit-exact.

// A byte b in [0, 255] is written as (b + 0.25) / 255: a target that rounds f * 255 to nearest and one that truncates
// it both store b. A texel t decodes to floor(t * 255 + 0.5) either way.
vec2 bytesToChannels(vec2 bytes) { return (bytes + 0.25) * (1.0 / 255.0); }
vec2 channelsToBytes(vec2 channels) { return floor(channels * 255.0 + 0.5); }

// 16-bit linear depth d = (-z_view - near) / (far - near): code = round(d * 65535), high byte, low byte.
// Exact in highp: code < 2^24 and the division by 256 is by a power of two.
vec2 packLinearDepth(float linearDepth) {
  float code = floor(clamp(linearDepth, 0.0, 1.0) * 65535.0 + 0.5);
  float high = floor(code * (1.0 / 256.0));
  return bytesToChannels(vec2(high, code - high * 256.0));
}

float unpackDepthCode(vec2 channels) {
  vec2 bytes = channelsToBytes(channels);
  return bytes.x * 256.0 + bytes.y;
}

float unpackLinearDepth(vec2 channels) { return unpackDepthCode(channels) * (1.0 / 65535.0); }

// Code 65535 (the far plane) marks pixels where nothing was drawn.
bool isBackgroundCode(float code) { return code > 65534.5; }

// Octahedral normal encoding (Cigolle et al. 2014), p in [-1, 1]^2 stored as round(127 p + 127): the axes and the
// poles are exact. Covers the whole sphere, so normals facing away from the viewer survive. Measured error: see
// src/encoding/NormalEncoding.h.
vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

vec2 encodeNormal(vec3 n) {
  vec2 p = n.xy * (1.0 / (abs(n.x) + abs(n.y) + abs(n.z)));
  if (n.z < 0.0) p = (1.0 - abs(p.yx)) * signNotZero(p);
  return bytesToChannels(floor(p * 127.0 + 127.5));
}

vec3 decodeNormal(vec2 channels) {
  vec2 p = (channelsToBytes(channels) - 127.0) * (1.0 / 127.0);
  vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(p.yx)) * signNotZero(p);
  return normalize(n);
}

// Gravas 2013, eq. 3.2.2: the normal weight ((n_a . n_b + 1) / 2)^10 of the blur and the upsampler, by squaring
// (three multiplies instead of pow's log and exp).
float normalSimilarity(vec3 a, vec3 b) {
  float w = max(dot(a, b) * 0.5 + 0.5, 0.0);
  float w2 = w * w;
  float w8 = w2 * w2;
  w8 *= w8;
  return w8 * w2;
}

// Screen-space velocity (encoding/VelocityPacking.h): each component, in units of the screen's size (uv, [-1, 1]),
// as a signed 16-bit code round(v * 32767) + 32768 in two bytes, high first: zero is exact (code 32768), the step is
// 1/32767 of the screen (0.06 px at 1920), and a motion across more than the whole screen clamps.
vec4 packVelocity(vec2 velocity) {
  vec2 code = floor(clamp(velocity, -1.0, 1.0) * 32767.0 + 0.5) + 32768.0;
  vec2 high = floor(code * (1.0 / 256.0));
  vec2 low = code - high * 256.0;
  return vec4(bytesToChannels(vec2(high.x, low.x)), bytesToChannels(vec2(high.y, low.y)));
}

vec2 unpackVelocity(vec4 texel) {
  vec2 x = channelsToBytes(texel.rg), y = channelsToBytes(texel.ba);
  return (vec2(x.x * 256.0 + x.y, y.x * 256.0 + y.y) - 32768.0) * (1.0 / 32767.0);
}
