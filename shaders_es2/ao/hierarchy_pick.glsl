// The pixel of its 2^m x 2^m block that texel p of depth hierarchy level m keeps (depth_hierarchy.frag), in closed
// form. The rotated-grid pick p_(k-1) = 2 p_k + (p_k.y mod 2, p_k.x mod 2) keeps each level's parities: followed from
// level m down to 0 it adds, with a = p.y mod 2 and b = p.x mod 2, the bits a, b, a, b, ... to x and b, a, b, a, ...
// to y, most significant first, so the offset in the block is
//     (a E_m + b O_m, b E_m + a O_m),   E_m = floor(2^(m+1) / 3) (the bits of even rank), O_m = 2^m - 1 - E_m.
// The chained form also clamps each step to the finer level's size; this one clamps once, to the G-buffer. The two
// differ only on a level's last row or column of an odd-sized level. CPU mirror: SaoKernel::hierarchyPickOffset.
// With ao.layers 2 the hierarchy's texels hold the second layer's depth where the chained form kept this offset.
vec2 hierarchyPickOffset(vec2 levelPixel, float level) {
  float a = mod(levelPixel.y, 2.0), b = mod(levelPixel.x, 2.0);
  float even = floor(exp2(level + 1.0) * (1.0 / 3.0));
  float odd = exp2(level) - 1.0 - even;
  return vec2(a * even + b * odd, b * even + a * odd);
}
