// Tone mapping as a per-pixel stage (src/effects/tonemap/TonemapEffect.h; the stage: src/frame/Stage.h): linear HDR
// colour exposed and mapped by the curve TONEMAP_OPERATOR selects (lib/tonemap.glsl: u_exposure), encoded sRGB for
// the RGBA8 display target (the stage's output encoding puts the luma FXAA reads in alpha). CPU mirror:
// src/encoding/ToneMapping.h (ToneMapInUse::displayColor).
#include "lib/tonemap.glsl"

vec3 tonemapStage(vec3 linear, StagePixel pixel) { return linearToSrgb(toneMap(linear)); }
