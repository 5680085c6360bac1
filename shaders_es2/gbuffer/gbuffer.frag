// G-buffer pass: one RGBA8 target. RG = octahedral view-space normal, BA = 16-bit linear depth.
// GBUFFER_OUTPUT 0: that target alone. 2: with EXT_draw_buffers, the material's base colour too (gl_FragData[1],
// sRGB-encoded, A = 1), which the deferred lighting reads: the scene is drawn once. 1: the base colour alone (the
// base-color view on a context without several render targets).
// ALPHA_MASK 1: the variant for alphaMode MASK materials, which discards cut-out fragments. Opaque materials use the
// variant without discard, so the depth test may run before the fragment shader (early depth rejection).
// GBUFFER_SHADING_NORMAL 1 (RendererOptions::gbufferShadingNormals, PBR_TEXTURES materials): the normal is the
// shading normal, the normal texture applied as the lighting pass applies it (lib/material.glsl).
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#if GBUFFER_SHADING_NORMAL
#define MATERIAL_SURFACE 1
#endif
#include "lib/material.glsl"
#include "lib/srgb.glsl"

#if GBUFFER_OUTPUT != 0 && !BASE_COLOR_TEXTURE && !VERTEX_COLORS
// A material with no base-colour texture and no vertex colours has one base colour: its sRGB encoding is derived on
// the host (GpuScene: linearToSrgb of the factor), not by a pow at every fragment (3.5 ms of the pass at 1280 x 720
// on SwiftShader: docs/benchmarks.md).
uniform vec3 u_baseColorSrgb;
#endif
uniform float u_near;
uniform float u_depthRange;  // far - near

varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
varying vec2 v_texcoord;

void main() {
#if ALPHA_MASK
  if (alphaMasked(v_texcoord)) discard;
#endif
  vec3 n = normalize(v_viewNormal);
  // Double-sided materials show their back faces: turn the normal towards the viewer.
  if (!gl_FrontFacing) n = -n;
#if GBUFFER_SHADING_NORMAL
  n = perturbedNormal(n, gl_FrontFacing);
#endif
  float linearDepth = (-v_viewPosition.z - u_near) / u_depthRange;
  vec4 gbuffer = vec4(encodeNormal(n), packLinearDepth(linearDepth));
#if GBUFFER_OUTPUT == 0
  gl_FragColor = gbuffer;
#else
#if BASE_COLOR_TEXTURE || VERTEX_COLORS
  vec4 base = vec4(linearToSrgb(baseColor(v_texcoord).rgb), 1.0);
#else
  vec4 base = vec4(u_baseColorSrgb, 1.0);
#endif
#if GBUFFER_OUTPUT == 1
  gl_FragColor = base;
#else
  gl_FragData[0] = gbuffer;
  gl_FragData[1] = base;
#endif
#endif
}
