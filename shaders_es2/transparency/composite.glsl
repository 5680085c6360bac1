// The transparent layer's fragment stage (src/effects/transparency/TransparencyEffect.h), the BLENDED form of
// lighting/lighting.frag: the surface lit as the lighting pass lights the opaque layer (PBR, the environment, the
// sun and the punctual lights; no AO: the AO belongs to the opaque layer), fogged by its own distance, then
// composited over what lies behind it in linear HDR colour, c = a c_s + (1 - a) c_behind (glTF's alphaMode BLEND,
// straight alpha; OPAQUE with transmission: a = 1).
//
// u_behind holds, in RGB9E5 (NEAREST; each texel decoded before it is filtered), at [0, W) x [0, H) the frame's
// colour behind the batch being drawn (copied before the batch: earlier, farther transparent surfaces included), and
// from x = W' on the opaque frame's blurred levels 1 .. TRANSMISSION_LEVELS (box filtered, each half the one before),
// W' x H' the frame rounded up to a multiple of 2^TRANSMISSION_LEVELS: level 1 at (W', 0), level k >= 2 at
// (W' (1.5 - 2^(1 - k)), H' / 2), each (W' / 2^k) x (H' / 2^k).
//
// TRANSMISSION 1 (KHR_materials_transmission, thin-walled: no refraction offset, as the extension's sample viewer
// does without KHR_materials_volume): the light from behind, at the blur level log2(W) roughness clamp(2 ior - 2,
// 0, 1) (applyIorToRoughness), passes through the share of the diffuse lobe the transmission factor takes, tinted
// by the base colour and less what the surface's specular reflects: T (1 - metallic) (1 - (F0 A + F90 B)) base.
uniform sampler2D u_behind;
uniform vec4 u_behindLayout;  // W, H (the frame, pixels), the texture's width and height (no levels: under 1.5 W')
#if TRANSMISSION
uniform float u_transmissionIor;  // clamp(2 ior - 2, 0, 1): how much of the roughness blurs what shows through
#endif
#if BLENDED_FOG
#include "lib/fog.glsl"
#endif

vec2 behindTextureSize() { return u_behindLayout.zw; }
// W' x H': the frame rounded up to a multiple of 2^TRANSMISSION_LEVELS, which the levels halve exactly.
vec2 paddedFrame() {
  float step = exp2(float(TRANSMISSION_LEVELS));
  return ceil(u_behindLayout.xy / step) * step;
}

// The copy behind this pixel (`pixel`: the frame's pixel coordinates of the fragment).
vec3 behindAt(vec2 pixel) {
  return decodeHdr(texture2D(u_behind, (floor(pixel) + 0.5) / behindTextureSize()));
}

#if TRANSMISSION
vec3 levelTexel(vec2 origin, vec2 texel) {
  return decodeHdr(texture2D(u_behind, (origin + texel + 0.5) / behindTextureSize()));
}

// Level k (1 .. TRANSMISSION_LEVELS) filtered bilinearly by hand at the frame's pixel coordinates `pixel`.
vec3 blurredLevel(float k, vec2 pixel) {
  float scale = exp2(-k);
  vec2 padded = paddedFrame();
  vec2 origin = k < 1.5 ? vec2(padded.x, 0.0) : vec2(padded.x * (1.5 - exp2(1.0 - k)), 0.5 * padded.y);
  vec2 last = ceil(u_behindLayout.xy * scale) - 1.0;  // the level's last texel holding the frame
  vec2 c = pixel * scale - 0.5;
  vec2 t = floor(c);
  vec2 w = c - t;
  vec2 t0 = clamp(t, vec2(0.0), last), t1 = clamp(t + 1.0, vec2(0.0), last);
  vec3 bottom = mix(levelTexel(origin, t0), levelTexel(origin, vec2(t1.x, t0.y)), w.x);
  vec3 top = mix(levelTexel(origin, vec2(t0.x, t1.y)), levelTexel(origin, t1), w.x);
  return mix(bottom, top, w.y);
}

// What shows through a surface of this roughness at `pixel`: the copy behind it (level 0, sharp) blended towards the
// blurred levels of the opaque frame.
vec3 transmittedLight(vec2 pixel, float roughness) {
  // Without room for the levels beside the copy (a frame near the largest texture), the copy alone: no blur.
  float levels = u_behindLayout.z >= 1.5 * paddedFrame().x ? float(TRANSMISSION_LEVELS) : 0.0;
  float lod = clamp(log2(u_behindLayout.x) * roughness * u_transmissionIor, 0.0, levels);
  float k = floor(lod);
  float f = lod - k;
  vec3 below = k < 0.5 ? behindAt(pixel) : blurredLevel(k, pixel);
  if (f <= 0.0) return below;
  return mix(below, blurredLevel(min(k + 1.0, levels), pixel), f);
}
#endif

void main() {
  vec4 base = baseColor(v_texcoord);
#if ALPHA_MASK
  // A transmissive material cut out by MASK: cut where glTF says, opaque elsewhere.
  if (base.a < u_alphaCutoff) discard;
  float alpha = 1.0;
#else
  // u_alphaCutoff is -1 for BLEND (alpha composites), -2 for OPAQUE (a transmissive surface: alpha ignored).
  float alpha = u_alphaCutoff < -1.5 ? 1.0 : base.a;
#endif
  vec2 pixel = (v_clipPosition.xy / v_clipPosition.w * 0.5 + 0.5) * u_behindLayout.xy;
#if UNLIT
  vec3 color = base.rgb;
#else
  Surface surface = surfaceAt(v_texcoord);
  vec3 g = normalize(v_viewNormal);
  if (!gl_FrontFacing) g = -g;
  vec3 n = perturbedNormal(g, gl_FrontFacing);
  vec3 color = shade(base.rgb, surface.metallic, surface.roughness, v_viewPosition, n, g, surface.occlusion,
                     surface.emissive);
#if TRANSMISSION
  {
    float roughness = clamp(surface.roughness, PBR_MIN_ROUGHNESS, 1.0);
    float metallic = clamp(surface.metallic, 0.0, 1.0);
    vec3 v = -eyeRayDirection(v_viewPosition);  // parallel rays under an orthographic camera
    vec2 scaleBias = splitSumScaleBias(roughness, clamp(dot(n, v), 1e-4, 1.0));
    vec3 f0, f90;
    fresnelColors(base.rgb, metallic, f0, f90);
    vec3 specularAlbedo = f0 * scaleBias.x + f90 * scaleBias.y;
    color += u_transmission * (1.0 - metallic) * (vec3(1.0) - specularAlbedo) * base.rgb *
             transmittedLight(pixel, roughness);
  }
#endif
#endif
#if BLENDED_FOG
  vec3 eyeToSurface = eyeRay(v_viewPosition);  // from the eye, or from its plane (orthographic)
  color = mix(u_fogColor, color, fogFactor(eyeToSurface, v_viewPosition - eyeToSurface, false));
#endif
  gl_FragColor = encodeHdr(mix(behindAt(pixel), color, alpha));
}
