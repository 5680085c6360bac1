// One run of the separable TileMax (frame/TileMaxPasses.h): the K source texels along u_step that this pass's texel
// stands for, at most MAX_TILE (constant loop bounds, GLSL ES 1.00 Appendix A; the host clamps K to it). Needs
// varying vec2 v_uv. motion_blur.frag (passes 1, 2) and dof.frag (passes 3, 4) reduce the run each their own way:
//
//   vec2 first = tileRunFirst();
//   for (int i = 0; i < MAX_TILE; i++) {
//     vec4 texel;
//     if (!tileRunTexel(first, i, texel)) break;
//     ...
//   }
uniform sampler2D u_source;
uniform vec2 u_sourceSize;  // texels
uniform vec2 u_step;        // (1, 0): along rows (the first pass); (0, 1): along columns (the second)
uniform float u_tile;       // K
uniform vec2 u_targetSize;  // the texels this pass writes

// The centre of the run's first texel, in source texels.
vec2 tileRunFirst() { return floor(v_uv * u_targetSize) * (vec2(1.0) + u_step * (u_tile - 1.0)) + 0.5; }

// Texel i of the run, or false past its end (K texels, clipped to the source).
bool tileRunTexel(vec2 first, int i, out vec4 texel) {
  vec2 p = first + u_step * float(i);
  if (float(i) >= u_tile || p.x > u_sourceSize.x || p.y > u_sourceSize.y) return false;
  texel = texture2D(u_source, p / u_sourceSize);
  return true;
}
