#pragma once
// The physical RGBA8 targets behind a frame plan's named targets (frame/FramePlan.h), kept from frame to frame:
//   - pooled slots, one render target per SlotKey (size relative to the frame, filter, own depth renderbuffer or
//     not), lent to whichever named target the plan puts there this frame; a slot no plan used for
//     kKeepUnusedFrames frames is released;
//   - framebuffers pairing one slot's colour with another's depth renderbuffer (a pass depth-testing against an
//     earlier pass's depth: the lighting against the G-buffer's);
//   - history targets: named pairs that survive frames (the previous frame's contents are read while the new ones
//     are written, then the two swap). They are dropped, with everything else, when the frame size changes, and on
//     dropHistory() (a scene change). A lost context drops the whole pool with its Renderer.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "frame/FramePlan.h"
#include "gl/GlCaps.h"
#include "gl/RenderTarget.h"

namespace obscura {

class RenderTargetPool {
 public:
  static constexpr int kKeepUnusedFrames = 8;

  // Targets with their own depth get a stencil buffer too where the context has packed depth + stencil (the
  // lighting pass uses it to shade each pixel once).
  explicit RenderTargetPool(const gl::GlCaps& caps) : depth24_(caps.depth24), stencil_(caps.packedDepthStencil) {}

  // Starts a frame of `size` pixels: a new size releases every target and the history.
  void beginFrame(glm::ivec2 size);
  // The target of a slot, made on first use at the frame's size.
  const gl::RenderTarget& slot(const SlotKey& key);
  // A framebuffer drawing into `color`'s texture with `depth`'s depth renderbuffer.
  GLuint sharedDepthFramebuffer(const SlotKey& color, const SlotKey& depth);
  // A framebuffer drawing into several slots' textures at once (EXT_draw_buffers: gl_FragData[i] into `colors[i]`),
  // with the depth renderbuffer of the first that has one.
  GLuint multipleTargetFramebuffer(const std::vector<SlotKey>& colors);
  // Releases slots unused for kKeepUnusedFrames frames.
  void endFrame();

  // A history target: `previous()` holds what the last frame wrote (valid() false when there is none: the first
  // frame after a drop), current() is what this frame writes. swap() at the end of the frame that wrote it.
  class History {
   public:
    const gl::RenderTarget& previous() const { return targets_[1 - current_]; }
    const gl::RenderTarget& current() const { return targets_[current_]; }
    bool valid() const { return valid_; }

   private:
    friend class RenderTargetPool;
    gl::RenderTarget targets_[2];
    int current_ = 0;
    bool valid_ = false;
    bool written_ = false;
  };
  History& history(const std::string& name, const TargetSize& size, GLenum filter);
  // A history target made already (this frame's writer asked for it), or null.
  const History* findHistory(const std::string& name) const;
  // Forgets every history target (a scene change: the previous frame shows another scene).
  void dropHistory();
  // How many times the history was dropped (size changes included), for stats and tests.
  int historyDrops() const { return historyDrops_; }

  // Live pooled targets (tests check reuse: a frame's plan needs fewer targets than it has named targets).
  size_t slotCount() const { return slots_.size(); }

 private:
  struct Slot {
    gl::RenderTarget target;
    std::uint64_t lastUsed = 0;
  };
  bool depth24_, stencil_;
  glm::ivec2 size_{0, 0};
  std::uint64_t frame_ = 0;
  std::map<SlotKey, Slot> slots_;
  std::map<std::pair<SlotKey, SlotKey>, gl::FramebufferHandle> sharedDepth_;
  std::map<std::vector<SlotKey>, gl::FramebufferHandle> multipleTargets_;
  std::map<std::string, History> history_;
  int historyDrops_ = 0;
};

}  // namespace obscura
