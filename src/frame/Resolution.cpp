#include "frame/Resolution.h"

#include <algorithm>
#include <cmath>

namespace obscura {

const char* upscaleFilterName(UpscaleFilter filter) {
  return filter == UpscaleFilter::Bilinear ? "bilinear" : "edge";
}

const std::vector<Parameter<ResolutionSettings>>& ResolutionSettings::parameters() {
  using S = ResolutionSettings;
  static const std::vector<Parameter<S>> table = {
      numberParameter<S>("scale", 0.25, 1, "of the output, per side",
                         "render scale: the effects run at this fraction of the output's width and height, and one "
                         "pass upscales the result (with dynamic: the largest scale chosen)",
                         &S::scale)
          .shapesPlan()  // the targets' size, and the upscale pass below 1
          .primary(),
      choiceParameter<S, UpscaleFilter>("upscale",
                                        "how the scaled frame reaches the output: bilinear, or edge-adaptive "
                                        "(EASU-like: sharp along edges)",
                                        &S::upscale,
                                        {{"bilinear", UpscaleFilter::Bilinear}, {"edge", UpscaleFilter::Edge}})
          .primary(),
      numberParameter<S>("sharpness", 0, 1, "",
                         "edge upscale: RCAS-like sharpening (0 off), limited to the local minimum and maximum",
                         &S::sharpness)
          .shapesPlan(),  // above 0 the upscale's program sharpens (upscaleVariantName)
      switchParameter<S>("dynamic",
                         "dynamic resolution: the viewers choose the scale each frame (between min-scale and scale) "
                         "to hold target-ms; obscura-render and the API render at scale",
                         &S::dynamic)
          .primary(),
      numberParameter<S>("target-ms", 4, 1000, "ms", "dynamic resolution: the frame time it holds", &S::targetMs),
      numberParameter<S>("min-scale", 0.25, 1, "of the output, per side",
                         "dynamic resolution: the smallest scale it chooses", &S::minScale),
      numberParameter<S>("max-pixel-ratio", 0.5, 8, "device pixels per CSS pixel",
                         "the page's canvas follows the device pixel ratio up to this (phones at 3 draw 2)",
                         &S::maxPixelRatio),
      switchParameter<S>("quick-start",
                         "start-up: the first frame is a cheap one (the lit scene, without AO, antialiasing and the "
                         "lens and camera effects) while the rest of the frame's programs are warmed over the next "
                         "frames; then the full frame (the page: on)",
                         &S::quickStart)};
  return table;
}

namespace {
bool sharpens(const ResolutionSettings& settings) {
  return settings.upscale == UpscaleFilter::Edge && settings.sharpness > 0.0f;
}
}  // namespace

std::vector<std::pair<std::string, std::string>> upscaleShaderDefines(const ResolutionSettings& settings) {
  return {{"UPSCALE", settings.upscale == UpscaleFilter::Bilinear ? "1" : "2"},
          {"UPSCALE_SHARPEN", sharpens(settings) ? "1" : "0"}};
}

std::string upscaleVariantName(const ResolutionSettings& settings) {
  return std::string(upscaleFilterName(settings.upscale)) + (sharpens(settings) ? ",sharpen" : "");
}

std::vector<ResolutionSettings> upscaleVariants() {
  ResolutionSettings bilinear, edge, sharpened;
  bilinear.upscale = UpscaleFilter::Bilinear;
  edge.upscale = sharpened.upscale = UpscaleFilter::Edge;
  edge.sharpness = 0.0f;
  sharpened.sharpness = 1.0f;
  return {bilinear, edge, sharpened};
}

glm::ivec2 renderSize(glm::ivec2 output, float scale) {
  const float s = std::clamp(scale, 0.0f, 1.0f);
  auto side = [s](int n) {
    return std::clamp(static_cast<int>(std::lround(static_cast<double>(n) * s)), 1, std::max(n, 1));
  };
  return {side(output.x), side(output.y)};
}

}  // namespace obscura
