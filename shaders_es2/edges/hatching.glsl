// Hatching (edges.style hatching; src/effects/edges/Hatching.h: the method and the CPU mirror): tonal strokes in
// world space, projected triplanarly onto the surface, their density following the display luma in bands, drawn
// before the edges' lines. Needs lib/precision.glsl, lib/packing.glsl, lib/srgb.glsl and lib/reconstruct.glsl
// (FAR_RAY 1) first.
#define MAX_HATCH_LAYERS 15

uniform sampler2D u_gbuffer;       // normal in RG, depth code in BA
uniform mat3 u_viewToWorld;        // the camera's rotation: view-space directions to world
uniform vec3 u_cameraWorld;        // the camera's position in the world
uniform vec2 u_pixelWorld;         // a pixel's size in the world at view depth z (negative): x z + y
uniform float u_hatchSpacing;      // pixels between strokes
uniform float u_hatchBands;        // the luma's bands: the darkest has bands - 1 layers of strokes, the lightest none

// Layer k's stroke direction in its plane: 45, 135, 0 and 90 degrees, the next four turned by 22.5 degrees, and so on.
vec2 hatchDirection(float k) {
  float m = mod(k, 4.0);
  float angle = (m < 0.5 ? 0.7853982 : (m < 1.5 ? 2.3561945 : (m < 2.5 ? 0.0 : 1.5707963))) +
                0.3926991 * floor(k * 0.25);
  return vec2(cos(angle), sin(angle));
}

// The coverage of strokes one pixel wide, `spacing` pixels apart, along `direction` at coordinate q (world units) in
// a plane whose strokes lie `period` world units apart, shifted by `phase` world units.
float strokeCoverage(vec2 q, vec2 direction, float period, float spacing, float phase) {
  float s = (dot(q, direction) + phase) / period;
  float distanceInPixels = abs(fract(s + 0.5) - 0.5) * spacing;
  return clamp(1.0 - distanceInPixels, 0.0, 1.0);
}

// The strokes of layer k on the surface at world position p with world normal n, for a pixel of `pixel` world units:
// the period is the spacing's power-of-two octave in world units, cross-faded into the next octave (every other
// stroke of it), so strokes stay about u_hatchSpacing pixels apart at any distance and stay on the surface.
float layerCoverage(vec3 p, vec3 weights, float k, float pixel) {
  float octave = log2(u_hatchSpacing * pixel);
  float lower = floor(octave);
  float blend = octave - lower;
  float fine = exp2(lower), coarse = fine * 2.0;
  vec2 direction = hatchDirection(k);
  // Each layer's strokes offset by its own distance in the world, the same for both octaves: the coarse octave's
  // strokes are every other stroke of the fine one's, so the cross-fade thins the strokes out.
  float phase = 0.37 * k;
  // Triplanar: the plane facing each world axis, weighted by the normal's component along it.
  float x = weights.x > 1e-3 ? mix(strokeCoverage(p.zy, direction, fine, fine / pixel, phase),
                                   strokeCoverage(p.zy, direction, coarse, coarse / pixel, phase), blend) : 0.0;
  float y = weights.y > 1e-3 ? mix(strokeCoverage(p.xz, direction, fine, fine / pixel, phase),
                                   strokeCoverage(p.xz, direction, coarse, coarse / pixel, phase), blend) : 0.0;
  float z = weights.z > 1e-3 ? mix(strokeCoverage(p.xy, direction, fine, fine / pixel, phase),
                                   strokeCoverage(p.xy, direction, coarse, coarse / pixel, phase), blend) : 0.0;
  return dot(weights, vec3(x, y, z));
}

// The display colour of a geometry pixel hatched by its display colour's luma; the background is left as it is.
vec3 hatch(vec3 display, vec2 uv, vec3 farRay, vec3 strokeColor) {
  vec4 g = texture2D(u_gbuffer, uv);
  float code = unpackDepthCode(g.ba);
  if (isBackgroundCode(code)) return display;
  vec3 view = viewPositionOnRay(farRay, code * (1.0 / 65535.0));
  vec3 p = u_viewToWorld * view + u_cameraWorld;
  vec3 n = u_viewToWorld * decodeNormal(g.rg);
  vec3 n4 = n * n;
  n4 *= n4;
  vec3 weights = n4 / (n4.x + n4.y + n4.z);
  float pixel = max(u_pixelWorld.x * view.z + u_pixelWorld.y, 1e-6);
  float y = fxaaLuma(display);
  float layers = u_hatchBands - 1.0 - min(floor(y * u_hatchBands), u_hatchBands - 1.0);
  float paper = 1.0;  // the paper left uncovered: 1 - the union of the layers' strokes
  for (int k = 0; k < MAX_HATCH_LAYERS; k++) {
    if (float(k) >= layers) break;
    paper *= 1.0 - layerCoverage(p, weights, float(k), pixel);
  }
  return mix(strokeColor, vec3(1.0), paper);  // white paper
}
