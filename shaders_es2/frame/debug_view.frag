// The debug views: one named target's bytes decoded and shown as they are (no tone curve, no sRGB encoding, no
// antialiasing), so tools read back the values themselves (obscura-compare reads --view ao's linear AO).
//   VIEW_DECODING 0 grey: R (AO)                   3 mask: G-buffer geometry white, background black
//                 1 normals: n * 0.5 + 0.5         4 HDR colour: lib/hdr.glsl decoded, clamped to [0, 1]
//                 2 depth: G-buffer linear depth   5 colour: RGB as stored
//                                                  6 count: R * 32 (a count / 255: 1 -> 32/255, 8 and more white)
//                                                  7 velocity: RG = 0.5 + 64 v (uv units, clamped), B = 0.5
//                 8 normals from depth: lib/normal_from_depth.glsl, n * 0.5 + 0.5 (black where it falls back)
// The target may be smaller than the view (half-resolution AO): sampled NEAREST at the view's uv.
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/hdr.glsl"

uniform sampler2D u_source;

varying vec2 v_uv;
#if VIEW_DECODING == 8
#include "lib/reconstruct.glsl"
#include "lib/normal_from_depth.glsl"
uniform vec2 u_sourceSize;
varying vec3 v_farRay;
#endif

void main() {
  vec4 texel = texture2D(u_source, v_uv);
#if VIEW_DECODING == 0
  gl_FragColor = vec4(vec3(texel.r), 1.0);
#elif VIEW_DECODING == 1
  gl_FragColor = isBackgroundCode(unpackDepthCode(texel.ba)) ? vec4(0.0, 0.0, 0.0, 1.0)
                                                            : vec4(decodeNormal(texel.rg) * 0.5 + 0.5, 1.0);
#elif VIEW_DECODING == 2
  gl_FragColor = vec4(vec3(unpackLinearDepth(texel.ba)), 1.0);
#elif VIEW_DECODING == 3
  gl_FragColor = isBackgroundCode(unpackDepthCode(texel.ba)) ? vec4(0.0, 0.0, 0.0, 1.0) : vec4(1.0);
#elif VIEW_DECODING == 4
  gl_FragColor = vec4(clamp(decodeHdr(texel), 0.0, 1.0), 1.0);
#elif VIEW_DECODING == 5
  gl_FragColor = vec4(texel.rgb, 1.0);
#elif VIEW_DECODING == 7
  gl_FragColor = vec4(clamp(0.5 + 64.0 * unpackVelocity(texel), 0.0, 1.0), 0.5, 1.0);
#elif VIEW_DECODING == 8
  float code = unpackDepthCode(texel.ba);
  vec3 n = normalFromDepth(u_source, u_sourceSize, floor(v_uv * u_sourceSize), code, vec3(-1.0));
  gl_FragColor = isBackgroundCode(code) ? vec4(0.0, 0.0, 0.0, 1.0) : vec4(n * 0.5 + 0.5, 1.0);
#else
  // Bytes written as (b + 0.25) / 255, so rounding and truncating targets both store 32 per count (lib/packing.glsl).
  gl_FragColor = vec4(vec3(min((floor(texel.r * 255.0 + 0.5) * 32.0 + 0.25) * (1.0 / 255.0), 1.0)), 1.0);
#endif
}
