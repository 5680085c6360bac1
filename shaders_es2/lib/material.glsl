// glTF base colour and alpha test, shared by the G-buffer and lighting passes so both discard the same fragments.
// BASE_COLOR_TEXTURE 1: the material has a base-colour texture; 0: the factor alone (no sample, no decoding).
// PBR_TEXTURES 1: the metallic-roughness, normal, occlusion and emissive textures are sampled (a slot the material
// lacks is bound to a neutral 1x1 texture: gpu/GpuScene.h), each at its own KHR_texture_transform'ed coordinates
// from the vertex stage (geometry.vert); 0: their factors alone.
// VERTEX_COLORS 1 (gpu/VertexKind.h): COLOR_0 from the vertex stage multiplies the base colour, alpha too (glTF 2.0
// 3.9.2), so the alpha test and blending see it.
// MATERIAL_LAYERS 1: KHR_materials_ior, _specular (the dielectric's Fresnel terms) and _clearcoat (Surface's layer
// fields; the lighting shades them). TRANSMISSION 1: KHR_materials_transmission's factor (effects/transparency).
// ALPHA_MASK is the including shader's (the variant that discards). src/gpu/MaterialKind.h sets them.
#ifndef BASE_COLOR_TEXTURE
#error "define BASE_COLOR_TEXTURE (MaterialKind::defines() on the CPU)"
#endif
#ifndef PBR_TEXTURES
#define PBR_TEXTURES 0
#endif
#ifndef VERTEX_COLORS
#define VERTEX_COLORS 0
#endif
#ifndef MATERIAL_LAYERS
#define MATERIAL_LAYERS 0
#endif
#ifndef TRANSMISSION
#define TRANSMISSION 0
#endif
#if VERTEX_COLORS
varying vec4 v_color;  // COLOR_0, linear
#endif

uniform vec4 u_baseColorFactor;
uniform float u_alphaCutoff;           // alphaMode MASK cutoff; negative for OPAQUE / BLEND

#if BASE_COLOR_TEXTURE
uniform sampler2D u_baseColorTexture;

// Linear base colour: glTF textures are sRGB-encoded, decoded here with the usual 2.2 power (no EXT_sRGB needed).
vec4 baseColorOfMaterial(vec2 uv) {
  vec4 texel = texture2D(u_baseColorTexture, uv);
  return u_baseColorFactor * vec4(pow(texel.rgb, vec3(2.2)), texel.a);
}
#else
vec4 baseColorOfMaterial(vec2 uv) { return u_baseColorFactor; }
#endif
#if VERTEX_COLORS
vec4 baseColor(vec2 uv) { return baseColorOfMaterial(uv) * v_color; }
#else
vec4 baseColor(vec2 uv) { return baseColorOfMaterial(uv); }
#endif

// True when alphaMode MASK removes this fragment (glTF: alpha < cutoff is fully transparent).
bool alphaMasked(vec2 uv) { return u_alphaCutoff >= 0.0 && baseColor(uv).a < u_alphaCutoff; }

#ifdef MATERIAL_SURFACE
// The rest of the glTF metallic-roughness material, for the lighting pass (MATERIAL_SURFACE: the shader reads it).
uniform vec4 u_metallicRoughness;  // metallic factor, roughness factor, normal scale, occlusion strength
uniform vec3 u_emissive;           // emissiveFactor * KHR_materials_emissive_strength, linear

struct Surface {
  vec3 base;         // linear base colour
  float metallic;
  float roughness;   // perceptual (glTF's), alpha = roughness^2
  float occlusion;   // the baked occlusion, strength applied: 1 + strength (texel - 1)
  vec3 emissive;     // linear radiance
};

#if MATERIAL_LAYERS
// The dielectric's Fresnel at normal and grazing incidence (KHR_materials_ior and _specular):
// rgb min(((ior - 1) / (ior + 1))^2 specularColor, 1) specular, a specular (Material in scene/Scene.h).
uniform vec4 u_specular;
uniform float u_clearcoat;           // KHR_materials_clearcoat's factor (0: no coat)
uniform float u_clearcoatRoughness;  // its perceptual roughness
#endif
#if TRANSMISSION
uniform float u_transmission;        // KHR_materials_transmission's factor
#endif

#if PBR_TEXTURES
uniform sampler2D u_metallicRoughnessTexture;  // B metallic, G roughness (linear)
uniform sampler2D u_normalTexture;             // tangent-space normal, (x, y, z) * 0.5 + 0.5
uniform sampler2D u_occlusionTexture;          // R occlusion
uniform sampler2D u_emissiveTexture;           // sRGB
varying vec4 v_uvMetallicNormal;               // the metallic-roughness and normal textures' coordinates
varying vec4 v_uvOcclusionEmissive;            // the occlusion and emissive textures' coordinates
varying vec4 v_viewTangent;                    // xyz view-space tangent, w the bitangent's sign

Surface surfaceAt(vec2 uv) {
  Surface s;
  s.base = baseColor(uv).rgb;
  vec4 mr = texture2D(u_metallicRoughnessTexture, v_uvMetallicNormal.xy);
  s.metallic = u_metallicRoughness.x * mr.b;
  s.roughness = u_metallicRoughness.y * mr.g;
  s.occlusion = 1.0 + u_metallicRoughness.w * (texture2D(u_occlusionTexture, v_uvOcclusionEmissive.xy).r - 1.0);
  s.emissive = u_emissive * pow(texture2D(u_emissiveTexture, v_uvOcclusionEmissive.zw).rgb, vec3(2.2));
  return s;
}

// The normal texture's normal in view space (glTF 2.0 3.9.3: scaled X and Y, then normalised), around the
// geometric normal n (unit, facing the viewer) and the interpolated tangent frame (Gram-Schmidt against n, as
// MikkTSpace's per-pixel reconstruction does).
vec3 perturbedNormal(vec3 n, bool frontFacing) {
  vec3 t = v_viewTangent.xyz - n * dot(n, v_viewTangent.xyz);
  float tLength = length(t);
  if (tLength < 1e-6) return n;
  t /= tLength;
  vec3 b = cross(n, t) * (v_viewTangent.w < 0.0 ? -1.0 : 1.0);
  // A back face's n was turned towards the viewer (so b, its cross product, turned too): the whole frame turns, as
  // in the glTF sample viewer, so the back face shows the front's perturbation mirrored.
  if (!frontFacing) t = -t;
  vec3 m = texture2D(u_normalTexture, v_uvMetallicNormal.zw).xyz * 2.0 - 1.0;
  m.xy *= u_metallicRoughness.z;
  return normalize(t * m.x + b * m.y + n * m.z);
}
#else
Surface surfaceAt(vec2 uv) {
  Surface s;
  s.base = baseColor(uv).rgb;
  s.metallic = u_metallicRoughness.x;
  s.roughness = u_metallicRoughness.y;
  s.occlusion = 1.0;
  s.emissive = u_emissive;
  return s;
}
vec3 perturbedNormal(vec3 n, bool frontFacing) { return n; }
#endif
#endif
