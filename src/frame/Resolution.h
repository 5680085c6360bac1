#pragma once
// The frame's resolution: the size the effects render at, and how their result reaches the display.
//
// resolution.scale s (0.25 .. 1) renders the G-buffer and every effect at round(s W) x round(s H) of a W x H output;
// one pass at the output's size then upscales the finished image into the output (effects/resolution: the
// `upscale` pass, or FXAA's pass doing both where FXAA runs, since FXAA is the last pass already). The upscale is
// bilinear, or edge-adaptive (`edge`: an EASU-like filter, shaders_es2/lib/upscale.glsl) with an optional RCAS-like
// sharpening. At scale 1 nothing of this runs and the frame is as it always was.
//
// Dynamic resolution (resolution.dynamic; platform/DynamicResolution.h) lets an interactive front end choose the
// scale each frame between resolution.min-scale and resolution.scale to hold resolution.target-ms; the Renderer
// then takes that scale (FrameOptions::renderScale) instead of resolution.scale. The page's canvas follows the
// device pixel ratio up to resolution.max-pixel-ratio (platform/WebCanvas).
//
// These are the frame's settings, not one effect's: the Renderer sizes the frame by them, the resolution effect
// draws the upscale, and FXAA fuses it, so they live here, below the effects, where each of them may read them.
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "frame/Parameters.h"

namespace obscura {

enum class UpscaleFilter { Bilinear = 0, Edge = 1 };
const char* upscaleFilterName(UpscaleFilter filter);  // "bilinear", "edge"

struct ResolutionSettings : ParameterAccess<ResolutionSettings> {
  // The render scale, per side; with `dynamic`, the largest the controller may choose.
  float scale = 1.0f;
  UpscaleFilter upscale = UpscaleFilter::Edge;
  // RCAS-like sharpening of the edge upscale, 0 (off) .. 1 (most): the negative lobe's weight, limited per pixel as
  // RCAS limits it and clamped to the local minimum and maximum (lib/upscale.glsl). 0.75: the least error against the
  // full-size frame at scale 0.5 (docs/resolution.md: 0.789 x bilinear's, against 0.800 at 0.5 and 0.791 at 1).
  float sharpness = 0.75f;
  // Dynamic resolution: off here (the command line, the API, tests: frames at a known size); the page turns it on
  // (its own default, web/app.js).
  bool dynamic = false;
  float targetMs = 33.3f;  // the frame time dynamic resolution holds (30 frames a second)
  float minScale = 0.5f;   // the smallest scale it may choose
  // The largest device pixel ratio the page's canvas takes (three.js applications usually cap it at 2): a phone at
  // DPR 3 draws 2 x 2 device pixels per CSS pixel, not 3 x 3.
  float maxPixelRatio = 2.0f;
  // Quick start: a Renderer's first frame is a cheap one (the lit scene without the effects that add passes of their
  // own: renderer/Renderer.h, quickStartSettings) and the programs of the frame asked for are warmed over the next
  // frames, each drawing the cheap frame again, until the full frame follows. Off here (the command line, tests:
  // every frame the one asked for); the page turns it on (web/app.js, createObscura's quickStart).
  bool quickStart = false;

  static const std::vector<Parameter<ResolutionSettings>>& parameters();
  void validate() const { validateParameters("resolution"); }
};

// The defines of shaders_es2/lib/upscale.glsl for these settings: UPSCALE 1 (bilinear) or 2 (edge), and
// UPSCALE_SHARPEN 1 where the edge upscale sharpens (sharpness above 0).
std::vector<std::pair<std::string, std::string>> upscaleShaderDefines(const ResolutionSettings& settings);
// Its program names' suffix: "bilinear", "edge", "edge,sharpen".
std::string upscaleVariantName(const ResolutionSettings& settings);
// Every variant (for the shader checks): bilinear, edge, edge with sharpening.
std::vector<ResolutionSettings> upscaleVariants();

// The size the effects render at for an output of `output` pixels at render scale `scale`: each side
// round(side x scale), at least 1 and at most the output's.
glm::ivec2 renderSize(glm::ivec2 output, float scale);

}  // namespace obscura
