#include "frame/FullscreenPass.h"

#include "frame/PassContext.h"

namespace obscura {

FullscreenDraw::FullscreenDraw(const gl::Program& program, const FullscreenTriangle& triangle,
                               const PassContext* context)
    : program_(program), triangle_(triangle), context_(context) {
  program_.use();
}

FullscreenDraw::~FullscreenDraw() {
  for (size_t unit = units_.size(); unit-- > 0;) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  glUseProgram(0);
}

int FullscreenDraw::unit(std::string_view sampler) const {
  for (const auto& [name, unit] : units_)
    if (name == sampler) return unit;
  return -1;
}

FullscreenDraw& FullscreenDraw::texture(std::string_view sampler, GLuint texture) {
  int u = unit(sampler);
  if (u < 0) {
    u = static_cast<int>(units_.size());
    units_.emplace_back(std::string(sampler), u);
    program_.set(sampler, u);
  }
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + u));
  glBindTexture(GL_TEXTURE_2D, texture);
  if (u != 0) glActiveTexture(GL_TEXTURE0);
  return *this;
}

FullscreenDraw& FullscreenDraw::texture(std::string_view sampler, const gl::Texture2D& texture) {
  return this->texture(sampler, texture.id());
}

FullscreenDraw& FullscreenDraw::read(std::string_view sampler, const std::string& target) {
  if (!context_) throw PipelineError("a full-screen draw outside a pass reads target '" + target + "'");
  return texture(sampler, context_->texture(target));
}

void FullscreenDraw::draw() const { triangle_.draw(); }

PassDecl fullscreenPass(std::string name, ProgramSpec program, std::vector<TextureInput> inputs, PassDecl::Write output,
                        std::function<void(FullscreenDraw&, const PassContext&)> uniforms,
                        std::vector<TextureInput> optionalInputs) {
  PassDecl pass;
  pass.name = std::move(name);
  for (const TextureInput& input : inputs) pass.reads.push_back(input.target);
  for (const TextureInput& input : optionalInputs) pass.optionalReads.push_back(input.target);
  pass.writes = {output};
  pass.programs = {program.name};
  pass.run = [program = std::move(program), inputs = std::move(inputs), optionalInputs = std::move(optionalInputs),
              target = output.target, uniforms = std::move(uniforms)](PassContext& context) {
    FullscreenDraw draw = context.draw(program, target);
    for (const TextureInput& input : inputs) draw.read(input.sampler, input.target);
    for (const TextureInput& input : optionalInputs)
      if (context.has(input.target)) draw.read(input.sampler, input.target);
    if (uniforms) uniforms(draw, context);
    draw.draw();
  };
  return pass;
}

}  // namespace obscura
