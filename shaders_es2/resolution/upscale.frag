// The resolution effect's pass (src/effects/resolution/ResolutionEffect.h): the frame's result, rendered below the
// output's size, upscaled into the output by lib/upscale.glsl (UPSCALE 1 bilinear, 2 edge-adaptive; UPSCALE_SHARPEN
// with the edge upscale). Where FXAA runs, its pass does this instead (shaders_es2/fxaa/fxaa.frag, UPSCALE), and this
// pass does not run.
#include "lib/precision.glsl"

uniform sampler2D u_color;  // display colour at the scaled size: RGB sRGB, A its luma; NEAREST
uniform vec2 u_size;        // its size, texels
uniform vec2 u_texel;       // 1 / u_size

varying vec2 v_uv;          // over the output

#include "lib/upscale.glsl"

void main() { gl_FragColor = vec4(upscale(v_uv, u_size, u_texel), 1.0); }
