// The opaque frame's blurred levels for transmission (src/effects/transparency/TransparencyEffect.h,
// transparency/composite.glsl): each level the 2 x 2 box mean of the one before, decoded, averaged in linear colour
// and encoded again (RGB9E5 texels cannot be filtered by the hardware: docs/architecture.md). Level 1 reads the
// opaque frame ("scene-color"). Texels beyond the frame's edge repeat the edge (clamped reads), so the padded
// levels hold no stray colour.
#include "lib/precision.glsl"
#include "lib/hdr.glsl"

uniform sampler2D u_source;     // the frame, or the level before, RGB9E5, NEAREST
uniform vec4 u_sourceRect;      // origin (texels) and size (texels holding the frame) of the source in its texture
uniform vec2 u_sourceSize;      // the source texture's size in texels
uniform vec2 u_targetOrigin;    // where this level starts in the target (window coordinates)

vec3 sourceTexel(vec2 texel) {
  vec2 t = clamp(texel, vec2(0.0), u_sourceRect.zw - 1.0);
  return decodeHdr(texture2D(u_source, (u_sourceRect.xy + t + 0.5) / u_sourceSize));
}

void main() {
  vec2 texel = floor(gl_FragCoord.xy - u_targetOrigin) * 2.0;
  vec3 sum = sourceTexel(texel) + sourceTexel(texel + vec2(1.0, 0.0)) + sourceTexel(texel + vec2(0.0, 1.0)) +
             sourceTexel(texel + vec2(1.0, 1.0));
  gl_FragColor = encodeHdr(0.25 * sum);
}
