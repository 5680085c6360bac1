#pragma once
// Per-pass GPU time from EXT_disjoint_timer_query (WebGL 1 and OpenGL ES 2 alike): one TIME_ELAPSED query around
// each pass, read back a few frames later, since results are never ready within the frame (WebGL only delivers them
// after control returns to the browser). When the GPU reports a disjoint event (a clock change, a context switch)
// every result in flight is discarded. Without the extension it measures nothing and the viewers show frame times
// only.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gl/GlCaps.h"
#include "gl/GlLoader.h"
#include "renderer/Renderer.h"

namespace obscura {

class GpuPassTimer : public PassTimer {
 public:
  static constexpr int kFramesInFlight = 4;
  // A measured frame costs a WebGL call at each end of every pass and two per pass to read it back (on the page's
  // default frame about a sixth of the render call's host time in Chromium: docs/benchmarks.md, "The timer
  // sampled"): the stats show times a few times a second, so one drawn frame in four is measured.
  static constexpr int kMeasureEvery = 4;

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
  // Around each drawn frame: beginFrame() collects results, then measures the frame's passes if kMeasureEvery frames
  // have begun since the last measured one, or if `measure` says so (dynamic resolution steers by every frame's time;
  // the page measures the first frame after a pause, so that the stats show what a change did), and if its query slot
  // is free again. `tag` comes back with the frame's results (lastResultTag: the render scale it was drawn at).
  void beginFrame(double tag = 0.0, bool measure = false);
  void endFrame();
  // A pass that runs twice in one frame (split screen runs the frame twice) is measured the first time.
  void begin(const std::string& pass) override;
  void end(const std::string& pass) override;

  // GPU milliseconds per pass of the newest frame whose results came back, in framePassNames() order (a pass that
  // did not run reads as a negative value); false before the first one.
  bool hasResult() const { return hasResult_; }
  const std::vector<double>& lastResult() const { return lastResult_; }
  // The tag of that frame, and how many frames' results have come back so far (a new result: the count moved).
  double lastResultTag() const { return lastResultTag_; }
  std::uint64_t results() const { return results_; }

 private:
  struct Functions;
  struct Frame {
    std::vector<GLuint> queries;
    std::vector<bool> used;
    bool pending = false;
    double tag = 0.0;
  };
  bool collect(Frame& frame);

  bool available_ = false;
  std::uint32_t generation_ = 0;
  std::unique_ptr<Functions> functions_;
  std::vector<Frame> frames_;
  int current_ = 0;  // the slot of the frame being recorded
  bool recording_ = false;
  int unmeasured_ = kMeasureEvery - 1;  // frames begun since the last measured one (the first frame is measured)
  int measuring_ = -1;  // the pass whose query is open
  bool hasResult_ = false;
  std::vector<double> lastResult_;
  double lastResultTag_ = 0.0;
  std::uint64_t results_ = 0;
};

}  // namespace obscura
