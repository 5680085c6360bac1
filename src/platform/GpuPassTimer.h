#pragma once
// Per-pass GPU time from EXT_disjoint_timer_query (WebGL 1 and OpenGL ES 2 alike): one TIME_ELAPSED query around
// each pass, read back a few frames later, since results are never ready within the frame (WebGL only delivers them
// after control returns to the browser). When the GPU reports a disjoint event (a clock change, a context switch)
// every result in flight is discarded. Without the extension it measures nothing and the viewers show frame times
// only.
#include <array>
#include <cstdint>
#include <memory>

#include "core/Renderer.h"
#include "gl/GlCaps.h"
#include "gl/GlLoader.h"

namespace obscura {

class GpuPassTimer : public PassTimer {
 public:
  static constexpr int kPassCount = static_cast<int>(Pass::Count);
  static constexpr int kFramesInFlight = 4;

  // `loader` resolves the extension's entry points in the current context (glfwGetProcAddress on the desktop,
  // emscripten_webgl1_get_proc_address on the web).
  GpuPassTimer(const gl::GlCaps& caps, gl::ProcLoader loader);
  ~GpuPassTimer() override;  // deletes its queries, unless they belong to an abandoned (lost) context
  GpuPassTimer(const GpuPassTimer&) = delete;
  GpuPassTimer& operator=(const GpuPassTimer&) = delete;

  bool available() const { return available_; }

  // Reads the results that have come back (oldest frame first). A viewer that skips drawing while nothing changes
  // calls it on every tick anyway, so the last drawn frame's times still arrive.
  void collectResults();
  // Around each drawn frame: beginFrame() collects results, then measures the frame's passes if its query slot is
  // free again.
  void beginFrame();
  void endFrame();
  void begin(Pass pass) override;
  void end(Pass pass) override;

  // GPU milliseconds per pass of the newest frame whose results came back (a pass that did not run reads as a
  // negative value); false before the first one.
  bool hasResult() const { return hasResult_; }
  const std::array<double, kPassCount>& lastResult() const { return lastResult_; }

 private:
  struct Functions;
  struct Frame {
    std::array<GLuint, kPassCount> queries{};
    std::array<bool, kPassCount> used{};
    bool pending = false;
  };
  bool collect(Frame& frame);

  bool available_ = false;
  std::uint32_t generation_ = 0;
  std::unique_ptr<Functions> functions_;
  std::array<Frame, kFramesInFlight> frames_;
  int current_ = 0;  // the slot of the frame being recorded
  bool recording_ = false;
  bool hasResult_ = false;
  std::array<double, kPassCount> lastResult_{};
};

}  // namespace obscura
