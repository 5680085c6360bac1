// The signed circle of confusion in RGBA8 (CPU mirror: src/encoding/CocPacking.h, which explains the codes). Needs
// lib/packing.glsl. `range` is the largest |C| the effect draws, in pixels: C is stored as C / range.

// dof-coc: 16 bits in RG, high byte first; B, A zero.
vec4 packCoc(float coc, float range) {
  float code = floor(clamp(coc / range, -1.0, 1.0) * 32767.0 + 0.5) + 32768.0;
  float high = floor(code * (1.0 / 256.0));
  return vec4(bytesToChannels(vec2(high, code - high * 256.0)), bytesToChannels(vec2(0.0)));
}

float unpackCoc(vec4 texel, float range) {
  vec2 bytes = channelsToBytes(texel.rg);
  return (bytes.x * 256.0 + bytes.y - 32768.0) * (range / 32767.0);
}

// dof-half's alpha: 8 bits, for the gather passes' weights.
float packHalfCoc(float coc, float range) {
  return (floor(clamp(coc / range, -1.0, 1.0) * 127.0 + 0.5) + 128.25) * (1.0 / 255.0);
}

float unpackHalfCoc(float channel, float range) {
  return (floor(channel * 255.0 + 0.5) - 128.0) * (range / 127.0);
}
