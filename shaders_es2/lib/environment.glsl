// Image-based ambient light (src/environment/Environment.h holds the method, the CPU side and the mirrors of every
// function here; docs/lighting.md the measurements). Needs lib/precision.glsl and lib/hdr.glsl first. Directions are
// world space, y up; the environment is equirectangular, u = atan(x, -z) / 2 pi + 1/2, v = acos(y) / pi.
//
//   vec3 environmentIrradiance(vec3 n)      E(n) / pi from the nine spherical-harmonic terms (Ramamoorthi & Hanrahan
//                                           2001, eq. 13): the radiance a white Lambertian surface reflects.
//   vec3 environmentSpecular(vec3 r, float roughness)
//                                           the prefiltered radiance (GGX, split sum: Karis 2013) towards r, levels
//                                           for roughness 0, 0.2, .., 1: half floats through the hardware's filter
//                                           (ENVIRONMENT_HALF_FLOAT), or RGB9E5 texels filtered by hand, or from
//                                           ENVIRONMENT_FILTERED_FROM on RGBM texels through the hardware's filter.
//   vec2 environmentBrdf(float roughness, float nDotV)
//                                           the split sum's (A, B) from a 32 x 32 table integrated on the CPU
//                                           (Karis 2013's IntegrateBRDF), bilinear: its bytes are plain linear values
//                                           (in the filtered texture, below its levels).
// lighting.frag's ambientLight combines them into the ambient term, with the material and the occlusion.
//
// ENVIRONMENT_HALF_FLOAT 1 (OES_texture_half_float_linear): u_environment holds every level as half floats, LINEAR,
// stacked in an atlas of ENVIRONMENT_HALF_FLOAT_SIZE texels, each inside a border that wraps in u and clamps in v
// (environmentHalfFloatOrigin): one fetch per level, nothing to decode. It is highp: a lowp sampler may clamp what
// it returns to 2, and the sky's sun is 40. Otherwise u_environment holds RGB9E5 texels, NEAREST, filtered by hand:
// ENVIRONMENT_LOD 1: the levels are mip levels of u_environment (EXT_shader_texture_lod's texture2DLodEXT at integer
// levels); 0: they lie side by side in one atlas (level 0 left, 1 .. 5 stacked to its right), read with texture2D.
// Both fetch the same texel centres, NEAREST, so both give the same values (tests/test_environment.cpp).
// ENVIRONMENT_SKY_CUBE 1 (with ENVIRONMENT_HALF_FLOAT): environmentSky(ray), the background, reads u_sky, a cube map
// of level 0; otherwise it is environmentSpecular(ray, 0).
// ENVIRONMENT_FILTERED_FROM: the first level read from u_environmentFiltered (GpuEnvironment::filteredFrom: 2, or
// ENVIRONMENT_LEVELS for none, where the environment's range makes RGBM under the filter too coarse).

#if ENVIRONMENT_HALF_FLOAT
uniform highp sampler2D u_environment;  // LINEAR; half floats
#else
uniform sampler2D u_environment;     // NEAREST; RGB9E5 texels (lib/hdr.glsl)
#endif
// LINEAR: levels ENVIRONMENT_FILTERED_LEVEL .. 5 as RGBM texels (encoding/EnvironmentEncoding.h) inside borders that
// wrap in u and clamp in v, and the (A, B) table; ENVIRONMENT_FILTERED_SIZE texels (environmentFilteredOrigin).
uniform sampler2D u_environmentFiltered;
uniform float u_environmentFilteredScale;  // the RGBM levels' scale times the intensity
// E(n) / pi = the sum of nine RGB coefficients times 1, x, y, z, xy, yz, xz, x^2 - y^2, z^2: their 27 floats in
// order, packed in 7 vec4 (7 fragment uniform vectors where 9 vec3 would take 9: GpuEnvironment::irradianceUniform).
uniform vec4 u_shIrradiance[7];
uniform float u_environmentIntensity;

const float ENVIRONMENT_PI = 3.14159265;
const float ENVIRONMENT_MAX_LEVEL = float(ENVIRONMENT_LEVELS - 1);

vec3 environmentIrradiance(vec3 n) {
  vec4 p0 = u_shIrradiance[0], p1 = u_shIrradiance[1], p2 = u_shIrradiance[2], p3 = u_shIrradiance[3];
  vec4 p4 = u_shIrradiance[4], p5 = u_shIrradiance[5], p6 = u_shIrradiance[6];
  vec3 e = p0.xyz + vec3(p0.w, p1.xy) * n.x + vec3(p1.zw, p2.x) * n.y + p2.yzw * n.z + p3.xyz * (n.x * n.y) +
           vec3(p3.w, p4.xy) * (n.y * n.z) + vec3(p4.zw, p5.x) * (n.x * n.z) + p5.yzw * (n.x * n.x - n.y * n.y) +
           p6.xyz * (n.z * n.z);
  return max(e, 0.0) * u_environmentIntensity;
}

vec2 environmentUv(vec3 d) {
  // atan(0, 0) is undefined: straight up or down, any u is the same place.
  float u = abs(d.x) + abs(d.z) > 0.0 ? atan(d.x, -d.z) * (0.5 / ENVIRONMENT_PI) + 0.5 : 0.5;
  return vec2(u, acos(clamp(d.y, -1.0, 1.0)) * (1.0 / ENVIRONMENT_PI));
}

// A level's size in texels: 512 x 256 / 2^level, rounded (exp2 need not be exact).
vec2 environmentLevelSize(float level) {
  return floor(vec2(ENVIRONMENT_WIDTH, ENVIRONMENT_HEIGHT) * exp2(-level) + 0.5);
}

#if !ENVIRONMENT_HALF_FLOAT
// Texel (x, y) of a level, both whole numbers inside it, decoded.
vec3 environmentTexel(vec2 texel, float level, vec2 size) {
#if ENVIRONMENT_LOD
  return decodeHdr(texture2DLodEXT(u_environment, (texel + 0.5) / size, level));
#else
  vec2 origin = level < 0.5 ? vec2(0.0)
                            : vec2(ENVIRONMENT_WIDTH, floor(ENVIRONMENT_HEIGHT * (1.0 - exp2(1.0 - level)) + 0.5));
  return decodeHdr(texture2D(u_environment, (origin + texel + 0.5) /
                                                vec2(ENVIRONMENT_WIDTH * 1.5, ENVIRONMENT_HEIGHT)));
#endif
}

// Bilinear between the level's texel centres around uv, wrapping in u and clamping in v (the hardware's filter would
// blend encoded bytes).
vec3 environmentLevelByHand(vec2 uv, float level) {
  vec2 size = environmentLevelSize(level);
  vec2 p = uv * size - 0.5;
  vec2 p0 = floor(p);
  vec2 f = p - p0;
  float x0 = mod(p0.x, size.x);
  float x1 = mod(p0.x + 1.0, size.x);
  float y0 = clamp(p0.y, 0.0, size.y - 1.0);
  float y1 = clamp(p0.y + 1.0, 0.0, size.y - 1.0);
  vec3 top = mix(environmentTexel(vec2(x0, y0), level, size), environmentTexel(vec2(x1, y0), level, size), f.x);
  vec3 bottom = mix(environmentTexel(vec2(x0, y1), level, size), environmentTexel(vec2(x1, y1), level, size), f.x);
  return mix(top, bottom, f.y) * u_environmentIntensity;
}
#endif

// A level of the filtered texture: one fetch through the hardware's bilinear filter, inside the level's border, and
// RGBM's decoding. Level k >= 2 begins at y = 1 + the bordered heights of levels 2 .. k - 1: 128 - 2^(9 - k) + 2 (k - 2).
vec3 environmentLevelFiltered(vec2 uv, float level) {
  vec2 size = environmentLevelSize(level);
  vec2 origin = vec2(1.0, 128.0 - exp2(9.0 - level) + 2.0 * level - 3.0);
  vec4 t = texture2D(u_environmentFiltered, (origin + uv * size) / ENVIRONMENT_FILTERED_SIZE);
  return t.rgb * (t.a * u_environmentFilteredScale);
}

#if ENVIRONMENT_HALF_FLOAT
// A level of the half-float atlas: one fetch through the hardware's filter, inside the level's border. Level k
// begins at y = 513 - 2^(9 - k) + 2 k.
vec3 environmentLevelHalfFloat(vec2 uv, float level) {
  vec2 size = environmentLevelSize(level);
  vec2 origin = vec2(1.0, 513.0 - floor(exp2(9.0 - level) + 0.5) + 2.0 * level);
  return texture2D(u_environment, (origin + uv * size) / ENVIRONMENT_HALF_FLOAT_SIZE).rgb * u_environmentIntensity;
}
#endif

vec3 environmentLevel(vec2 uv, float level) {
#if ENVIRONMENT_HALF_FLOAT
  return environmentLevelHalfFloat(uv, level);
#else
#if ENVIRONMENT_FILTERED_FROM < ENVIRONMENT_LEVELS
  if (level >= float(ENVIRONMENT_FILTERED_FROM)) return environmentLevelFiltered(uv, level);
#endif
  return environmentLevelByHand(uv, level);
#endif
}

vec3 environmentSpecular(vec3 r, float roughness) {
  vec2 uv = environmentUv(normalize(r));
  float lod = clamp(roughness, 0.0, 1.0) * ENVIRONMENT_MAX_LEVEL;
  float level = floor(lod);
  float f = lod - level;
  vec3 c = environmentLevel(uv, level);
  // A whole level (roughness 0, 0.2, .., 1) reads one level.
  if (f > 0.0) c = mix(c, environmentLevel(uv, level + 1.0), f);
  return c;
}

#if ENVIRONMENT_SKY_CUBE
// The background's cube map (environment/Environment.h: skyCubeFaces): level 0 resampled onto six faces of half
// floats, LINEAR. `ray`: any length, in the environment's frame.
uniform highp samplerCube u_sky;
vec3 environmentSky(vec3 ray) { return textureCube(u_sky, ray).rgb * u_environmentIntensity; }
#else
vec3 environmentSky(vec3 ray) { return environmentSpecular(ray, 0.0); }
#endif

// The split sum's BRDF term: specular reflectance = F0 A + B. The table's texel centres span (0.5 .. 31.5) / 32 of
// its 32 x 32; its border clamps beyond them.
vec2 environmentBrdf(float roughness, float nDotV) {
  vec2 p = ENVIRONMENT_BRDF_ORIGIN + vec2(nDotV, roughness) * ENVIRONMENT_BRDF_SIZE;
  return texture2D(u_environmentFiltered, p / ENVIRONMENT_FILTERED_SIZE).rg;
}

