#include "effects/resolution/ResolutionEffect.h"

#include "frame/FramePlan.h"
#include "frame/PassContext.h"
#include "frame/FullscreenPass.h"

namespace obscura {
namespace {

ProgramSpec spec(const ResolutionSettings& settings) {
  std::vector<std::pair<std::string, std::string>> defines = upscaleShaderDefines(settings);
  defines.emplace_back("FAR_RAY", "0");
  return ProgramSpec{"upscale[" + upscaleVariantName(settings) + "]", "lib/fullscreen.vert",
                     "resolution/upscale.frag", defines, {}};
}

}  // namespace

EffectInfo ResolutionEffect::info() { return {"resolution", "Resolution", false, false, {"upscale"}, {}}; }

std::vector<ProgramSpec> ResolutionEffect::programSpecs() {
  std::vector<ProgramSpec> specs;
  for (const ResolutionSettings& settings : upscaleVariants()) specs.push_back(spec(settings));
  return specs;
}

void ResolutionEffect::plan(FramePlanner& planner) {
  if (!planner.frame().upscaled()) return;
  planner.add(fullscreenPass("upscale", spec(planner.settings().of<ResolutionSettings>()),
                             {{"u_color", kFinalImageTarget}}, {kOutputTarget},
                             [](FullscreenDraw& draw, const PassContext& context) {
                               const glm::vec2 texel = context.texelSize(kFinalImageTarget);
                               draw.set("u_size", 1.0f / texel);
                               draw.set("u_texel", texel);
                               // The edge upscale's sharpening (its variants with UPSCALE_SHARPEN).
                               if (draw.program().has("u_sharpness"))
                                 draw.set("u_sharpness", context.settings().of<ResolutionSettings>().sharpness);
                             }));
}

}  // namespace obscura
