// The diagnostic views: AO (blurred or raw) as grey, view-space normals as colour, linear depth as grey, geometry mask.
//   VIEW_MODE 0: AO texture R channel (background white)
//   VIEW_MODE 1: G-buffer normal, n * 0.5 + 0.5 (background black)
//   VIEW_MODE 2: G-buffer linear depth (background white)
//   VIEW_MODE 3: geometry mask (geometry white, background black)
#include "lib/precision.glsl"
#include "lib/packing.glsl"

uniform sampler2D u_source;   // the AO texture (mode 0) or the G-buffer (modes 1, 2, 3)

varying vec2 v_uv;

void main() {
  vec4 texel = texture2D(u_source, v_uv);
#if VIEW_MODE == 0
  gl_FragColor = vec4(vec3(texel.r), 1.0);
#elif VIEW_MODE == 1
  gl_FragColor = isBackgroundCode(unpackDepthCode(texel.ba)) ? vec4(0.0, 0.0, 0.0, 1.0)
                                                            : vec4(decodeNormal(texel.rg) * 0.5 + 0.5, 1.0);
#elif VIEW_MODE == 2
  gl_FragColor = vec4(vec3(unpackLinearDepth(texel.ba)), 1.0);
#else
  gl_FragColor = isBackgroundCode(unpackDepthCode(texel.ba)) ? vec4(0.0, 0.0, 0.0, 1.0) : vec4(1.0);
#endif
}
