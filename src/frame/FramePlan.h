#pragma once
// One frame's passes, resolved: the effects' declarations (frame/Effect.h) turned into the order things run in, which
// contents each read sees, which passes are needed at all, where the result goes and which physical target holds
// each piece of contents. Plain logic without GL, so the CPU tests check it (tests/test_frame_plan.cpp).
//
// Rules, in the order they are applied:
//   1. Passes run in the order declared (effects in table order, then the frame's view pass).
//   2. Each write makes a new version of its target; a read binds to the latest earlier version. A required read
//      with no earlier version is a PipelineError naming the pass, its effect and the target.
//   3. Liveness, backwards from the frame's result: a pass runs if it is `keep`, or a running pass reads one of its
//      versions, or it writes the result. Optional reads never keep a writer alive, and are dropped when theirs
//      does not run.
//   4. Alternatives: each running pass takes the first of its alternatives whose conditions hold.
//   4b. Per-pixel stages fuse: a stage pass (PassDecl::stage) whose colour input is written by a stage head
//      (PassDecl::stageHead: the lighting, or another stage pass), and read by it alone, runs inside the head's
//      program, which then writes the stage's output, when everything else the stage reads is written before the
//      head runs, its uniforms fit the head's remaining vectors and its textures the head's remaining texture
//      units, and (where the head cannot draw into the output framebuffer) its output is not the frame's result
//      drawn there. Stage after stage, a chain fuses into one pass; the stages' passes do not run ("done by" the
//      head: PlannedPass::absorbed).
//   5. The result (the frame's final image, or the debug view's output) is written straight into the output
//      framebuffer by its writer, unless a running pass also reads that version; then a present pass copies it.
//   6. Every other version gets a pooled slot: slots are keyed by size, filter and own depth, and a slot is free
//      again once the last pass reading what it holds has run. A pass never writes the slot it reads from.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "frame/Effect.h"
#include "frame/FrameContext.h"
#include "frame/FrameSettings.h"

namespace obscura {

// What a pooled slot must be: RenderTargetPool makes one physical target per distinct key and index.
struct SlotKey {
  TargetSize size;
  GLenum filter = GL_NEAREST;
  bool ownDepth = false;
  int index = 0;  // the n-th slot of this kind in use at once
  bool operator<(const SlotKey& o) const;
  bool operator==(const SlotKey& o) const;
};

// The contents one write leaves in a target.
struct TargetVersion {
  std::string target;
  int writer = -1;               // pass index
  TargetSize size;
  GLenum filter = GL_NEAREST;
  PassDecl::Write::Depth depth = PassDecl::Write::Depth::None;
  int depthVersion = -1;         // Depth::Shared: the version whose slot's depth renderbuffer is attached
  bool external = false;         // storage the effect keeps itself (not pooled)
  bool history = false;          // this frame's side of a history target (PassDecl::Write::history; not pooled)
  bool output = false;           // written into the output framebuffer
  int lastReader = -1;           // pass index, -1: none
  std::optional<SlotKey> slot;   // pooled storage
};

struct PlannedPass {
  PassDecl decl;
  std::string effect;            // the table row that declared it ("" for the frame's own view pass)
  bool live = false;
  std::map<std::string, int> reads;   // target (or alias) -> version: required reads, and optional ones whose
                                      // writer runs
  std::map<std::string, int> writes;  // target -> version
  std::vector<std::string> absorbed;  // passes whose work this one does: the stages fused into it, in order, or the
                                      // pass an alternative absorbed (PassDecl::Alternative::absorbing)
  std::vector<StageDecl> stages;      // those stages
  std::string stageOutput;            // a stage head's colour target: its own, or its last fused stage's output
  // fusedProgramName("", stages) (frame/Stage.h), made with the plan: the passes name their fused program by it
  // every frame, and a cached plan need not format it again.
  std::string stagesName;
};

// Collects one frame's passes. Effects add theirs in FramePlanner's hands (Effect::plan).
class FramePlanner {
 public:
  // `targets`: every target the effects may write (EffectInfo::targets), by name.
  FramePlanner(const FrameSettings& settings, const FrameContext& frame,
               const std::map<std::string, TargetInfo>& targets)
      : settings_(settings), frame_(frame), targets_(targets) {}

  const FrameSettings& settings() const { return settings_; }
  const FrameContext& frame() const { return frame_; }

  // The effect whose passes follow (the Renderer sets it before calling Effect::plan).
  void beginEffect(const std::string& effect) { effect_ = effect; }
  // Whether per-pixel stages fuse (rule 4b; RendererOptions::fuseStages).
  void setFuseStages(bool fuse) { fuseStages_ = fuse; }
  // The target the frame's debug view shows ("" for the final image). An effect that is off still plans the passes
  // that view needs (showsTargetOf).
  void setViewTarget(const std::string& target) { viewTarget_ = target; }
  const std::string& viewTarget() const { return viewTarget_; }
  bool showsTargetOf(const EffectInfo& effect) const;
  void add(PassDecl pass);
  // Marks a write of the last added pass as external: storage the effect keeps itself (the depth hierarchy's
  // atlas or mip chain), tracked for ordering and liveness only.
  void markExternal(const std::string& target);
  // From here on, reads of `name` see the latest version of `target` (the AO without a blur is the raw AO).
  void alias(const std::string& name, const std::string& target);
  // Whether a pass added so far writes `target` (or an alias names it): a later effect reads what an earlier one
  // chose to make this frame without knowing that effect (the lighting reads "ao" when the AO runs).
  bool declares(const std::string& target) const;

 private:
  friend class FramePlan;
  struct Entry {
    std::string effect;
    PassDecl decl;                            // empty name: an alias entry
    std::vector<std::string> externalWrites;
    std::string aliasName, aliasTarget;
  };

  const FrameSettings& settings_;
  const FrameContext& frame_;
  const std::map<std::string, TargetInfo>& targets_;
  std::string effect_;
  std::string viewTarget_;
  bool fuseStages_ = true;
  std::vector<Entry> entries_;
};

// The frame's name for its final image: the display-encoded colour the last colour effect writes.
inline constexpr const char* kFinalImageTarget = "display-color";
// The reserved target name of the output framebuffer (what a view pass writes).
inline constexpr const char* kOutputTarget = "output";

class FramePlan {
 public:
  // Resolves the planner's passes. `result`: the target whose latest version is the frame's image (written into the
  // output), or kOutputTarget when a pass writes the output itself (a debug view). `presentPass`, when the result's
  // last writer cannot write the output itself (a running pass reads that version too, or it is retained), is
  // appended to copy it; it must read `result` and write kOutputTarget. `retain`: targets whose latest versions
  // must stay in their pooled targets after the frame (their writers run; nothing reuses their targets). Throws
  // PipelineError; InputError for a retained target no pass writes.
  static FramePlan resolve(FramePlanner&& planner, const std::string& result,
                           const std::function<PassDecl()>& presentPass, const std::vector<std::string>& retain = {});

  const std::vector<PlannedPass>& passes() const { return passes_; }
  const std::vector<TargetVersion>& versions() const { return versions_; }
  // Every slot this frame uses (for the pool).
  std::vector<SlotKey> slots() const;
  // The version a retained target holds after the frame; -1 if it was not retained.
  int retainedVersion(const std::string& target) const;

 private:
  std::vector<PlannedPass> passes_;
  std::vector<TargetVersion> versions_;
  std::map<std::string, int> retained_;
};

}  // namespace obscura
