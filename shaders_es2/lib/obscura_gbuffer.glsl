// Obscura's G-buffer, for the caller's own fragment shaders (public, installed as <prefix>/share/obscura/glsl/
// obscura_gbuffer.glsl; the text is also obscura::api::gbufferGlsl() and, in the browser, obscura.gbufferGlsl).
// GLSL ES 1.00 / WebGL 1, self-contained: paste or concatenate it after the caller's precision statement (the depth
// packing needs highp float in the fragment shader, which Obscura requires of every context), then write
//
//   gl_FragColor = obscuraGBuffer(normalize(v_viewNormal), -v_viewPosition.z, u_near, u_far);
//
// with the view-space normal (unit length, facing the viewer for a double-sided face) and the view-space depth
// (positive distance along -z) of the fragment, and the near and far planes of the projection the pass draws with
// (the camera given to Renderer::ambientOcclusion). Draw into Renderer::beginGBuffer()'s framebuffer (cleared to the
// background), depth test on (GL_LESS), no blending.
//
// The layout (docs/api.md, "The G-buffer layout"; the same bytes as Obscura's own G-buffer pass, shaders_es2/
// gbuffer.frag, lib/packing.glsl; CPU mirrors encoding/NormalEncoding and encoding/LinearDepthPacking):
//   RG  the view-space normal, octahedral (Cigolle et al. 2014), each axis round(127 p + 127) in 0 .. 254;
//   BA  16-bit linear depth code round(65535 (z - near) / (far - near)), high byte in B, low byte in A;
//       65535 (B = A = 1.0) marks the background.
// Bytes are written as (b + 0.25) / 255, so a target that rounds and one that truncates both store b.
// Stable within a major version of Obscura: a change of layout is a major change (CHANGELOG.md).

vec2 obscuraBytesToChannels(vec2 bytes) { return (bytes + 0.25) * (1.0 / 255.0); }

// The normal's two bytes, as channels: octahedral projection folded over the lower hemisphere.
vec2 obscuraEncodeNormal(vec3 n) {
  vec2 p = n.xy * (1.0 / (abs(n.x) + abs(n.y) + abs(n.z)));
  if (n.z < 0.0) p = (1.0 - abs(p.yx)) * vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
  return obscuraBytesToChannels(floor(p * 127.0 + 127.5));
}

// Linear depth in [0, 1] as two bytes, high first, as channels. Exact in highp: the code is below 2^24.
vec2 obscuraPackLinearDepth(float linearDepth) {
  float code = floor(clamp(linearDepth, 0.0, 1.0) * 65535.0 + 0.5);
  float high = floor(code * (1.0 / 256.0));
  return obscuraBytesToChannels(vec2(high, code - high * 256.0));
}

// The G-buffer texel of a fragment: `viewNormal` unit length in view space, `viewDepth` = -z_view.
vec4 obscuraGBuffer(vec3 viewNormal, float viewDepth, float near, float far) {
  return vec4(obscuraEncodeNormal(viewNormal), obscuraPackLinearDepth((viewDepth - near) / (far - near)));
}
