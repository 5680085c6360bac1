// Temporal antialiasing's colour arithmetic (shaders_es2/taa/taa.frag). CPU mirror: src/effects/taa/TaaEffect.h
// (taaToYCoCg, taaFromYCoCg, taaToneWeight, taaToneUnweight, taaClipTowardsMean), held equal on the GPU by
// tests/test_taa.cpp.

// YCoCg (Malvar and Sullivan 2003, the lossy transform): Y = (R + 2G + B) / 4. The neighbourhood's box is tighter in
// it than in RGB, since luma and chroma vary apart (Karis 2014, "High quality temporal supersampling", slide 28).
vec3 taaToYCoCg(vec3 c) {
  return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}
vec3 taaFromYCoCg(vec3 c) { return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z); }

// Karis 2014's reversible tone map (slide 20): c / (1 + luma), here on YCoCg with Y as the luma. Averaging in it keeps
// a lone bright sample from dominating its neighbours (the HDR colour of a highlight is many times the display's),
// and its inverse is exact: t / (1 - t.Y) (t.Y < 1 for every finite colour).
vec3 taaToneWeight(vec3 ycocg) { return ycocg / (1.0 + max(ycocg.x, 0.0)); }
vec3 taaToneUnweight(vec3 t) { return t / max(1.0 - t.x, 1.0 / 65536.0); }

// Clips `history` towards `mean` onto the box mean +- extent (Salvi 2016, "An excursion in temporal supersampling":
// the box of variance clipping; clipping along the line to the mean as Pedersen 2016, Playdead's INSIDE, rather
// than clamping each axis, keeps the history's hue on the way to the mean).
vec3 taaClipTowardsMean(vec3 history, vec3 mean, vec3 extent) {
  vec3 offset = history - mean;
  vec3 units = abs(offset) / max(extent, vec3(1.0 / 65536.0));
  float largest = max(units.x, max(units.y, units.z));
  return largest > 1.0 ? mean + offset / largest : history;
}
