#pragma once
// The plumbing of an image-space pass, written once: one full-screen draw of a program, and the declaration of a pass
// made of one such draw.
//
// FullscreenDraw puts its program in use, binds textures by sampler name to units 0, 1, ... (a sampler named again
// keeps its unit), sets uniforms by name (gl/Program.h: resolved when the program was linked, uploaded only when the
// value changes), draws the triangle, and on destruction unbinds what it bound and the program, which leaves the
// baseline GL state (gl/PipelineState.h) for the next pass. A pass that changes more state (blending, depth,
// stencil) restores that itself.
//
// fullscreenPass() declares a pass of one draw: its program (chosen when the plan is made), the targets it reads by
// sampler, the target it writes, and the uniforms it sets each frame from the pass context. A one-pass effect is its
// maths (the shader and its settings' derived constants) plus this declaration:
//
//   planner.add(fullscreenPass("edges-h", distanceSpec(radius), {{"u_mask", "edges-mask"}}, {"edges-distance"},
//                              [](FullscreenDraw& draw, const PassContext& context) {
//                                draw.set("u_texel", context.texelSize("edges-distance"));
//                              }));
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "frame/Effect.h"
#include "frame/FullscreenTriangle.h"
#include "gl/Program.h"
#include "gl/RenderTarget.h"
#include "gl/ShaderLibrary.h"

namespace obscura {

class PassContext;

class FullscreenDraw {
 public:
  // `context`: the pass's, for reading its targets by name (read()); may be null for a draw outside a frame.
  FullscreenDraw(const gl::Program& program, const FullscreenTriangle& triangle, const PassContext* context = nullptr);
  ~FullscreenDraw();
  FullscreenDraw(const FullscreenDraw&) = delete;
  FullscreenDraw& operator=(const FullscreenDraw&) = delete;

  // Binds `texture` to `sampler`'s unit (the next free one the first time) and sets the sampler to it.
  FullscreenDraw& texture(std::string_view sampler, const gl::Texture2D& texture);
  FullscreenDraw& texture(std::string_view sampler, GLuint texture);
  // The texture of a target the pass reads (PassContext::texture), bound to `sampler`.
  FullscreenDraw& read(std::string_view sampler, const std::string& target);
  // A uniform by name (gl::Program::set: a value, or an array and its count).
  template <typename... Value>
  FullscreenDraw& set(std::string_view uniform, const Value&... value) {
    program_.set(uniform, value...);
    return *this;
  }
  const gl::Program& program() const { return program_; }
  // The unit `sampler` is bound to, or -1.
  int unit(std::string_view sampler) const;
  // Draws the triangle into the framebuffer bound, with the textures and uniforms set so far.
  void draw() const;

 private:
  const gl::Program& program_;
  const FullscreenTriangle& triangle_;
  const PassContext* context_;
  std::vector<std::pair<std::string, int>> units_;  // sampler -> unit
};

// What a full-screen pass reads: a target, bound to a sampler.
struct TextureInput {
  std::string sampler;
  std::string target;
};

// A pass of one full-screen draw of `program` into `output`, reading `inputs` (required reads, bound in order) and
// `optionalInputs` (bound when some running pass writes them: PassContext::has), with `uniforms` set each frame.
PassDecl fullscreenPass(std::string name, ProgramSpec program, std::vector<TextureInput> inputs, PassDecl::Write output,
                        std::function<void(FullscreenDraw&, const PassContext&)> uniforms = {},
                        std::vector<TextureInput> optionalInputs = {});

}  // namespace obscura
