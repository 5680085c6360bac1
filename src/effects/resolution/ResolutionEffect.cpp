#include "effects/resolution/ResolutionEffect.h"

#include "frame/FramePlan.h"
#include "frame/PassContext.h"
#include "gl/PipelineState.h"

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

ResolutionEffect::Variant::Variant(gl::Program built)
    : program(std::move(built)),
      color(program.uniform("u_color")),
      size(program.uniform("u_size")),
      texel(program.uniform("u_texel")),
      sharpness(program.optionalUniform("u_sharpness")) {}

const ResolutionEffect::Variant& ResolutionEffect::variant(const ResolutionSettings& settings) {
  const std::string name = upscaleVariantName(settings);
  auto it = variants_.find(name);
  if (it == variants_.end()) it = variants_.emplace(name, Variant(resources_.build(spec(settings)))).first;
  return it->second;
}

void ResolutionEffect::plan(FramePlanner& planner) {
  if (!planner.frame().upscaled()) return;
  const ResolutionSettings settings = planner.settings().of<ResolutionSettings>();
  PassDecl pass;
  pass.name = "upscale";
  pass.reads = {kFinalImageTarget};
  pass.writes = {{kOutputTarget, TargetSize::full(), PassDecl::Write::Depth::None, ""}};
  pass.run = [this, settings](PassContext& context) {
    const gl::Texture2D& input = context.texture(kFinalImageTarget);
    const glm::vec2 size(static_cast<float>(input.width()), static_cast<float>(input.height()));
    const Variant& v = variant(settings);
    context.bindForWriting(kOutputTarget);
    input.bind(0);
    v.program.use();
    gl::Program::set(v.color, 0);
    gl::Program::set(v.size, size);
    gl::Program::set(v.texel, 1.0f / size);
    if (v.sharpness >= 0) gl::Program::set(v.sharpness, settings.sharpness);
    resources_.triangle.draw();
    gl::restoreBaselineState();
  };
  planner.add(std::move(pass));
}

}  // namespace obscura
