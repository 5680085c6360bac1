// Points and lines (effects/lines/LinesEffect.h), in two programs:
//   LINES_COPY 1: the lit colour copied as it is (its bytes: NEAREST at texel centres, no decoding needed), so the
//     points and lines can be drawn over it into the pass's own target;
//   LINES_COPY 0: a point or line fragment, unlit: its colour is emitted as linear HDR colour (lib/hdr.glsl), as
//     KHR_materials_unlit colours are, since a point or a line has no normal to light.
#include "lib/precision.glsl"
#ifndef LINES_COPY
#define LINES_COPY 0
#endif

#if LINES_COPY
uniform sampler2D u_color;  // scene-color
varying vec2 v_uv;

void main() { gl_FragColor = texture2D(u_color, v_uv); }
#else
#include "lib/hdr.glsl"

varying vec4 v_color;

void main() { gl_FragColor = encodeHdr(v_color.rgb); }
#endif
