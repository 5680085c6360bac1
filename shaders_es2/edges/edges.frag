// Edges from the G-buffer (src/effects/edges/EdgesEffect.h: the method, the equations and the CPU mirror), three
// passes:
//   EDGES_PASS 1 detect: each pixel against its four neighbours -> "edges-mask" (R profile, G crease, B colour edge)
//                  profile  min(D_x, D_y) < -t_d, D = z_c (1/z_a + 1/z_b) - 2 (eq. 1: 0 on any plane, the relative
//                           depth jump at a profile's near side; 1/z = 0 for the background)
//                  crease   a neighbour not nearer whose normal is more than the crease angle away
//                  colour   (COLOR_EDGES) a neighbour's display luma above this pixel's by more than t_c
//   EDGES_PASS 2 rows: the distance to the nearest edge pixel of the row within EDGE_RADIUS -> "edges-distance"
//   EDGES_PASS 3 draw: d = min_j sqrt(g(y + j)^2 + j^2), coverage strength clamp(width / 2 + 1/2 - d, 0, 1) (eq. 2),
//                  the line colour mixed over the display colour (TOON: quantised into bands first; HATCHING:
//                  strokes in bands of its luma first, edges/hatching.glsl)
#include "lib/precision.glsl"
#include "lib/packing.glsl"
#include "lib/srgb.glsl"

uniform vec2 u_texel;  // 1 / the frame's size

varying vec2 v_uv;

#if EDGES_PASS == 1
uniform sampler2D u_gbuffer;     // normal in RG, depth code in BA, NEAREST
uniform float u_near;
uniform float u_depthScale;      // (far - near) / 65535: z = near + code * scale
uniform float u_inverseOrthographicDepth;  // 1 / L for an orthographic camera (EdgesEffect.h); 0: perspective
uniform float u_depthThreshold;  // t_d
uniform float u_normalCos;       // cos of the crease angle
#if COLOR_EDGES
uniform sampler2D u_color;       // display-color: its alpha is the display luma
uniform float u_colorThreshold;  // t_c
#endif

float viewDepth(float code) { return isBackgroundCode(code) ? 0.0 : u_near + code * u_depthScale; }
float reciprocal(float z) { return z > 0.0 ? 1.0 / z : 0.0; }

// Eq. 1 for the pixel of depth code `code` between neighbours of codes a and b: perspective, or orthographic (a
// uniform branch; EdgesEffect.h).
float secondDifference(float code, float a, float b) {
  float z = viewDepth(code);
  if (u_inverseOrthographicDepth > 0.0) {
    if (isBackgroundCode(a) || isBackgroundCode(b)) return -1e30;
    return (2.0 * z - viewDepth(a) - viewDepth(b)) * u_inverseOrthographicDepth;
  }
  return z * (reciprocal(viewDepth(a)) + reciprocal(viewDepth(b))) - 2.0;
}

// The crease test against one neighbour: only the pixel on the nearer side (or both, at equal depth codes) marks it.
float crease(vec3 normal, float code, vec4 other) {
  float otherCode = unpackDepthCode(other.ba);
  if (isBackgroundCode(otherCode) || otherCode < code) return 0.0;
  return dot(normal, decodeNormal(other.rg)) < u_normalCos ? 1.0 : 0.0;
}

void main() {
  vec4 centre = texture2D(u_gbuffer, v_uv);
  float code = unpackDepthCode(centre.ba);
  if (isBackgroundCode(code)) {
    gl_FragColor = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  vec4 left = texture2D(u_gbuffer, v_uv - vec2(u_texel.x, 0.0));
  vec4 right = texture2D(u_gbuffer, v_uv + vec2(u_texel.x, 0.0));
  vec4 below = texture2D(u_gbuffer, v_uv - vec2(0.0, u_texel.y));
  vec4 above = texture2D(u_gbuffer, v_uv + vec2(0.0, u_texel.y));
  float dx = secondDifference(code, unpackDepthCode(left.ba), unpackDepthCode(right.ba));
  float dy = secondDifference(code, unpackDepthCode(below.ba), unpackDepthCode(above.ba));
  float profile = min(dx, dy) < -u_depthThreshold ? 1.0 : 0.0;
  vec3 normal = decodeNormal(centre.rg);
  float creased = max(max(crease(normal, code, left), crease(normal, code, right)),
                      max(crease(normal, code, below), crease(normal, code, above)));
  float colored = 0.0;
#if COLOR_EDGES
  float luma = texture2D(u_color, v_uv).a;
  float brightest = max(max(texture2D(u_color, v_uv - vec2(u_texel.x, 0.0)).a,
                            texture2D(u_color, v_uv + vec2(u_texel.x, 0.0)).a),
                        max(texture2D(u_color, v_uv - vec2(0.0, u_texel.y)).a,
                            texture2D(u_color, v_uv + vec2(0.0, u_texel.y)).a));
  colored = brightest - luma > u_colorThreshold ? 1.0 : 0.0;
#endif
  gl_FragColor = vec4(profile, creased, colored, 1.0);
}

#elif EDGES_PASS == 2
uniform sampler2D u_mask;  // edges-mask

void main() {
  float nearest = float(EDGE_RADIUS + 1);
  for (int i = -EDGE_RADIUS; i <= EDGE_RADIUS; i++) {
    vec3 flags = texture2D(u_mask, v_uv + vec2(float(i) * u_texel.x, 0.0)).rgb;
    if (max(flags.r, max(flags.g, flags.b)) > 0.5) nearest = min(nearest, abs(float(i)));
  }
  gl_FragColor = vec4(bytesToChannels(vec2(nearest, 0.0)), 0.0, 1.0);
}

#else
#if HATCHING
#include "lib/reconstruct.glsl"
#include "edges/hatching.glsl"
varying vec3 v_farRay;
#endif
uniform sampler2D u_distance;  // edges-distance
uniform sampler2D u_color;     // display-color
uniform float u_halfWidth;     // width / 2 + 1/2
uniform vec3 u_lineColor;      // the display (sRGB-encoded) line colour
uniform float u_strength;
uniform float u_alphaIsOne;    // 1: the output framebuffer; 0: luma in alpha for FXAA
#if TOON
uniform float u_bands;

vec3 toonShade(vec3 srgb) {
  float y = fxaaLuma(srgb);
  float level = (min(floor(y * u_bands), u_bands - 1.0) + 0.5) / u_bands;
  return y < 1e-4 ? srgb : min(srgb * (level / y), 1.0);
}
#endif

void main() {
  float nearest2 = float((EDGE_RADIUS + 1) * (EDGE_RADIUS + 1));
  for (int j = -EDGE_RADIUS; j <= EDGE_RADIUS; j++) {
    float g = channelsToBytes(texture2D(u_distance, v_uv + vec2(0.0, float(j) * u_texel.y)).rg).x;
    nearest2 = min(nearest2, g * g + float(j * j));
  }
  float coverage = u_strength * clamp(u_halfWidth - sqrt(nearest2), 0.0, 1.0);
  vec3 color = texture2D(u_color, v_uv).rgb;
#if TOON
  color = toonShade(color);
#endif
#if HATCHING
  color = hatch(color, v_uv, v_farRay, u_lineColor);
#endif
  color = mix(color, u_lineColor, coverage);
  gl_FragColor = vec4(color, mix(fxaaLuma(color), 1.0, u_alphaIsOne));
}
#endif
