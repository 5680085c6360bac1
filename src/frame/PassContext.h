#pragma once
// What a pass sees while it draws (PassDecl::run): the frame, the settings, the scene, and its targets by name,
// bound to the physical targets the frame plan lent it (or the output framebuffer, for the frame's result).
#include <functional>
#include <string>
#include <vector>

#include "frame/EffectEntry.h"
#include "frame/FrameContext.h"
#include "frame/FramePlan.h"
#include "frame/FrameSettings.h"
#include "frame/FullscreenPass.h"
#include "frame/RenderTargetPool.h"
#include "gpu/GpuScene.h"

namespace obscura {

// Where the frame's result goes: the caller's framebuffer (0: the window's or canvas's own).
struct OutputTarget {
  GLuint framebuffer = 0;
  int width = 1, height = 1;
  // Only this rectangle (GL window coordinates: x right, y up from the bottom) of the output is drawn; an empty
  // one means all of it. Split screen draws its two halves as two frames.
  struct Region {
    int x = 0, y = 0, width = 0, height = 0;
  } region;
};

class PassContext {
 public:
  PassContext(const FramePlan& plan, int pass, RenderTargetPool& pool, const FrameContext& frame,
              const FrameSettings& settings, const GpuScene& scene, const OutputTarget& output,
              const EffectResources& resources)
      : plan_(plan), pass_(pass), pool_(pool), frame_(frame), settings_(settings), scene_(scene), output_(output),
        resources_(resources) {}

  const FrameContext& frame() const { return frame_; }
  const FrameCamera& camera() const { return frame_.camera; }
  const FrameSettings& settings() const { return settings_; }
  const GpuScene& scene() const { return scene_; }

  // The colour texture of a target this pass reads. Throws PipelineError for one it did not declare (or an optional
  // read no running pass wrote: ask has() first).
  const gl::Texture2D& texture(const std::string& target) const;
  // The colour texture of a pooled target this pass writes, for a later draw of the same pass to read back (bloom's
  // level 2, which is also the frame's `bloom-bright`).
  const gl::Texture2D& writtenTexture(const std::string& target) const;
  // Whether a declared optional read is there this frame.
  bool has(const std::string& target) const;
  // Binds the framebuffer this pass writes `target` into and sets the viewport to cover it. For the frame's result,
  // that is the output framebuffer, scissored to the output's region.
  void bindForWriting(const std::string& target) const;
  // Binds one framebuffer writing several pooled targets of the same size at once (EXT_draw_buffers:
  // gl_FragData[i] goes to targets[i]), with the depth renderbuffer of the first that has one.
  void bindForWriting(const std::vector<std::string>& targets) const;
  // The size of a target this pass reads or writes, in pixels, and one texel's size in uv units (1 / size).
  glm::ivec2 size(const std::string& target) const;
  glm::vec2 texelSize(const std::string& target) const { return 1.0f / glm::vec2(size(target)); }
  // The program of `spec` (the Renderer's, built on first use); by name, its spec made only the first time.
  const gl::Program& program(const ProgramSpec& spec) const { return resources_.program(spec); }
  const gl::Program& program(const std::string& name, const std::function<ProgramSpec()>& spec) const {
    return resources_.programs.get(name, spec);
  }
  const EffectResources& resources() const { return resources_; }
  // This pass as the plan resolved it.
  const PlannedPass& pass() const { return plan_.passes()[static_cast<size_t>(pass_)]; }
  // The per-pixel stages fused into this pass (frame/Stage.h), in order, and the target a stage head writes its
  // colour into: its own, or the last fused stage's output.
  const std::vector<StageDecl>& stages() const { return pass().stages; }
  const std::string& stageOutput() const { return pass().stageOutput; }
  const std::string& stagesName() const { return pass().stagesName; }  // fusedProgramName("", stages())
  // A full-screen draw of `spec`'s program into `target`, which it binds for writing (frame/FullscreenPass.h).
  FullscreenDraw draw(const ProgramSpec& spec, const std::string& target) const {
    bindForWriting(target);
    return FullscreenDraw(program(spec), resources_.triangle, this);
  }
  // The same into the framebuffer bound already (a history target, an effect's own storage).
  FullscreenDraw draw(const ProgramSpec& spec) const {
    return FullscreenDraw(program(spec), resources_.triangle, this);
  }
  // For a pass whose result where nothing was drawn is one known value (the AO's white): clears `target`, bound for
  // writing, to `outside`, and scissors the pass's draws to the pixels the scene may cover (GpuScene::coveredRect,
  // mapped to the target's size, widened by a pixel); neither where the scene may cover every pixel. A CPU
  // rasteriser pays a full-screen pass's arithmetic at every pixel, the background's too: a branch runs both its
  // sides (docs/benchmarks.md, issue 26).
  void limitToScene(const std::string& target, const glm::vec4& outside) const;
  // The pixels of `target` the scene may cover: FrameContext::sceneBounds mapped to the target's size and widened by
  // a pixel, within the output's region where `target` is the output; x, y, width, height in GL window coordinates.
  glm::ivec4 sceneRect(const std::string& target) const;
  // For a pass that draws the pixels around the scene's bounds with a program of their own (nothing was drawn there:
  // the lighting's background, FXAA's copy): calls `drawBand` scissored to each band around sceneRect(target) (below,
  // above, left, right; the empty ones left out), then scissors the pass's next draws to the bounds until finish().
  void drawAroundScene(const std::string& target, const std::function<void()>& drawBand) const;
  // Calls `draw` depth-tested with `depthFunc`, writing depth where `writeDepth`, then puts back what it set: the
  // depth test off, depth writes on, no program (the draws put back their own streams and textures). The geometry
  // passes' draws: the scene's (drawScene) and the lines'.
  void drawDepthTested(GLenum depthFunc, bool writeDepth, const std::function<void()>& draw) const;
  // The scene through this frame's view (GpuScene::draw, which puts back its own state: restoreAfterDraw),
  // depth-tested as drawDepthTested.
  void drawScene(GLenum depthFunc, bool writeDepth, const GpuScene::ProgramChoice& choose,
                 const GpuScene::DrawOptions& options = {}) const {
    drawDepthTested(depthFunc, writeDepth, [&] { scene_.draw(frame_.camera.view, choose, options); });
  }
  // Restores what the pass context changed (the scissor of the output's region or of limitToScene): called after
  // every pass.
  void finish() const;
  // Whether this pass writes `target` into the output framebuffer.
  bool writesOutput(const std::string& target) const;
  // Whether `target` is written with another target's depth attached (else its own, or none).
  bool sharesDepth(const std::string& target) const;
  // A history target of this pass (see RenderTargetPool::History).
  RenderTargetPool::History& history(const std::string& name, const TargetSize& size, GLenum filter) const {
    return pool_.history(name, size, filter);
  }

 private:
  const TargetVersion& readVersion(const std::string& target) const;
  const TargetVersion& writeVersion(const std::string& target) const;
  // `rect` clipped to the output's region where `target` is the output.
  glm::ivec4 withinOutputRegion(const std::string& target, const glm::ivec4& rect) const;
  // Scissors this pass's draws into `target` to `rect` (within the output's region) until finish(); where that is
  // all of the target, turns the test off instead.
  void scissor(const std::string& target, const glm::ivec4& rect) const;
  // Whether `rect` holds every pixel of `target`.
  bool coversTarget(const std::string& target, const glm::ivec4& rect) const;

  const FramePlan& plan_;
  int pass_;
  RenderTargetPool& pool_;
  const FrameContext& frame_;
  const FrameSettings& settings_;
  const GpuScene& scene_;
  const OutputTarget& output_;
  const EffectResources& resources_;
  mutable bool scissored_ = false;
};

}  // namespace obscura
