// glTF base colour and alpha test, shared by the G-buffer and lighting passes so both discard the same fragments.
// BASE_COLOR_TEXTURE 1: the material has a base-colour texture; 0: the factor alone (no sample, no decoding).
// ALPHA_MASK is the including shader's (the variant that discards). src/core/MaterialKind.h sets both.
#ifndef BASE_COLOR_TEXTURE
#error "define BASE_COLOR_TEXTURE (MaterialKind::defines() on the CPU)"
#endif

uniform vec4 u_baseColorFactor;
uniform float u_alphaCutoff;           // alphaMode MASK cutoff; negative for OPAQUE / BLEND

#if BASE_COLOR_TEXTURE
uniform sampler2D u_baseColorTexture;

// Linear base colour: glTF textures are sRGB-encoded, decoded here with the usual 2.2 power (no EXT_sRGB needed).
vec4 baseColor(vec2 uv) {
  vec4 texel = texture2D(u_baseColorTexture, uv);
  return u_baseColorFactor * vec4(pow(texel.rgb, vec3(2.2)), texel.a);
}
#else
vec4 baseColor(vec2 uv) { return u_baseColorFactor; }
#endif

// True when alphaMode MASK removes this fragment (glTF: alpha < cutoff is fully transparent).
bool alphaMasked(vec2 uv) { return u_alphaCutoff >= 0.0 && baseColor(uv).a < u_alphaCutoff; }
