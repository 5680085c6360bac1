// One level of SAO's depth hierarchy (McGuire, Mara, Luebke 2012, sec. 3.3): level m keeps, for each texel p, the
// packed depth of ONE texel of level m - 1, picked on a rotated grid,
//     p_(m-1) = 2 p_m + (p_m.y mod 2, p_m.x mod 2),   clamped to level m - 1,
// never an average of depths (an average is a depth where no surface is).
//
// Every level is made from level 0 (the G-buffer) by following that pick down the levels. This is the same texel
// the chain level 0 -> 1 -> ... -> m would select, but no pass samples the texture it renders into: WebGL 1 treats
// sampling any level of a texture attached to the bound framebuffer as a feedback loop.
//
// Output: BA = the picked texel's 16-bit depth code (same layout as the G-buffer); RG = where that texel lies in
// its 2^m x 2^m block (0 .. 2^m - 1 per axis), so the SAO pass rebuilds each far tap at the exact pixel whose
// depth it read: a real surface point, where the SAO reference code reuses the tap's own pixel ray (off the
// surface by the depth slope across the block, which darkens planes seen at grazing angles).
//
// AO_LAYERS 2 (ao.layers 2): RG = the second layer's depth code at the picked pixel (effects/ao/DepthPeelPass.h), so
// a tap reads both layers in one fetch; the pick is then the closed form of ao/hierarchy_pick.glsl, which the
// estimator computes again instead of reading it.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "ao/hierarchy_pick.glsl"

uniform sampler2D u_gbuffer;
uniform vec2 u_gbufferSize;  // level-0 size in pixels
uniform float u_level;       // m >= 1
#if AO_LAYERS == 2
uniform sampler2D u_secondLayer;
#endif

varying vec2 v_uv;
varying vec3 v_farRay;

// Size of hierarchy level k: floor(size0 / 2^k), at least 1 (floor(floor(x/2)/2) = floor(x/4), so halving each
// level is the same as dividing level 0).
vec2 levelSize(float k) { return max(floor(u_gbufferSize / exp2(k)), vec2(1.0)); }

void main() {
  // The output is the viewport of level m; v_uv spans it.
  vec2 levelPixel = floor(v_uv * levelSize(u_level));
#if AO_LAYERS == 2
  vec2 pick = min(levelPixel * exp2(u_level) + hierarchyPickOffset(levelPixel, u_level), u_gbufferSize - 1.0);
  vec2 pickUv = (pick + 0.5) / u_gbufferSize;
  gl_FragColor = vec4(bytesToChannels(channelsToBytes(texture2D(u_secondLayer, pickUv).ba)),
                      bytesToChannels(channelsToBytes(texture2D(u_gbuffer, pickUv).ba)));
#else
  vec2 p = levelPixel;
  for (int step = 0; step < MAX_MIP_LEVEL; step++) {
    float k = u_level - float(step);  // going from level k to level k - 1
    if (k < 0.5) break;
    p = min(2.0 * p + vec2(mod(p.y, 2.0), mod(p.x, 2.0)), levelSize(k - 1.0) - 1.0);
  }
  vec2 depthChannels = texture2D(u_gbuffer, (p + 0.5) / u_gbufferSize).ba;
  gl_FragColor = vec4(bytesToChannels(p - levelPixel * exp2(u_level)), bytesToChannels(channelsToBytes(depthChannels)));
#endif
}
