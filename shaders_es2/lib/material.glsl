// glTF base colour and alpha test, shared by the G-buffer and lighting passes so both discard the same fragments.
uniform vec4 u_baseColorFactor;
uniform sampler2D u_baseColorTexture;  // 1x1 white when the material has none
uniform float u_alphaCutoff;           // alphaMode MASK cutoff; negative for OPAQUE / BLEND

// Linear base colour: glTF textures are sRGB-encoded, decoded here with the usual 2.2 power (no EXT_sRGB needed).
vec4 baseColor(vec2 uv) {
  vec4 texel = texture2D(u_baseColorTexture, uv);
  return u_baseColorFactor * vec4(pow(texel.rgb, vec3(2.2)), texel.a);
}

// True when alphaMode MASK removes this fragment (glTF: alpha < cutoff is fully transparent).
bool alphaMasked(vec2 uv) { return u_alphaCutoff >= 0.0 && baseColor(uv).a < u_alphaCutoff; }
