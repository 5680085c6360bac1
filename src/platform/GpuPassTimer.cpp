#include "platform/GpuPassTimer.h"

#include <algorithm>

#include "gl/GlObjects.h"

namespace obscura {

struct GpuPassTimer::Functions {
  PFNGLGENQUERIESEXTPROC genQueries = nullptr;
  PFNGLDELETEQUERIESEXTPROC deleteQueries = nullptr;
  PFNGLBEGINQUERYEXTPROC beginQuery = nullptr;
  PFNGLENDQUERYEXTPROC endQuery = nullptr;
  PFNGLGETQUERYOBJECTUIVEXTPROC getQueryObjectuiv = nullptr;
  PFNGLGETQUERYOBJECTUI64VEXTPROC getQueryObjectui64v = nullptr;  // optional: 32-bit nanoseconds suffice per pass
};

GpuPassTimer::GpuPassTimer(const gl::GlCaps& caps, gl::ProcLoader loader) : generation_(gl::contextGeneration()) {
  if (!caps.timerQuery || !loader) return;
  auto f = std::make_unique<Functions>();
  f->genQueries = reinterpret_cast<PFNGLGENQUERIESEXTPROC>(loader("glGenQueriesEXT"));
  f->deleteQueries = reinterpret_cast<PFNGLDELETEQUERIESEXTPROC>(loader("glDeleteQueriesEXT"));
  f->beginQuery = reinterpret_cast<PFNGLBEGINQUERYEXTPROC>(loader("glBeginQueryEXT"));
  f->endQuery = reinterpret_cast<PFNGLENDQUERYEXTPROC>(loader("glEndQueryEXT"));
  f->getQueryObjectuiv = reinterpret_cast<PFNGLGETQUERYOBJECTUIVEXTPROC>(loader("glGetQueryObjectuivEXT"));
  f->getQueryObjectui64v = reinterpret_cast<PFNGLGETQUERYOBJECTUI64VEXTPROC>(loader("glGetQueryObjectui64vEXT"));
  if (!f->genQueries || !f->deleteQueries || !f->beginQuery || !f->endQuery || !f->getQueryObjectuiv) return;
  functions_ = std::move(f);
  for (Frame& frame : frames_) functions_->genQueries(kPassCount, frame.queries.data());
  available_ = true;
}

GpuPassTimer::~GpuPassTimer() {
  if (functions_ && generation_ == gl::contextGeneration())
    for (Frame& frame : frames_) functions_->deleteQueries(kPassCount, frame.queries.data());
}

bool GpuPassTimer::collect(Frame& frame) {
  for (int p = 0; p < kPassCount; ++p) {
    if (!frame.used[p]) continue;
    GLuint ready = 0;
    functions_->getQueryObjectuiv(frame.queries[p], GL_QUERY_RESULT_AVAILABLE_EXT, &ready);
    if (!ready) return false;
  }
  for (int p = 0; p < kPassCount; ++p) {
    lastResult_[p] = -1.0;
    if (!frame.used[p]) continue;
    double nanoseconds = 0.0;
    if (functions_->getQueryObjectui64v) {
      GLuint64 value = 0;
      functions_->getQueryObjectui64v(frame.queries[p], GL_QUERY_RESULT_EXT, &value);
      nanoseconds = static_cast<double>(value);
    } else {
      GLuint value = 0;
      functions_->getQueryObjectuiv(frame.queries[p], GL_QUERY_RESULT_EXT, &value);
      nanoseconds = static_cast<double>(value);
    }
    lastResult_[p] = nanoseconds * 1e-6;
  }
  frame.pending = false;
  hasResult_ = true;
  return true;
}

void GpuPassTimer::collectResults() {
  if (!available_) return;
  // Reading GPU_DISJOINT_EXT also clears it; a disjoint event makes every result in flight meaningless.
  GLint disjoint = 0;
  glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
  for (int age = 1; age <= kFramesInFlight; ++age) {
    Frame& frame = frames_[(current_ + age) % kFramesInFlight];  // oldest first
    if (!frame.pending) continue;
    if (disjoint) frame.pending = false;
    else if (!collect(frame)) break;  // later frames cannot be ready before this one
  }
}

void GpuPassTimer::beginFrame() {
  recording_ = false;
  if (!available_) return;
  collectResults();
  current_ = (current_ + 1) % kFramesInFlight;
  Frame& frame = frames_[current_];
  if (frame.pending) return;  // results of this slot have not come back yet: skip measuring this frame
  frame.used.fill(false);
  recording_ = true;
}

void GpuPassTimer::endFrame() {
  // A frame that measured no pass (the renderer failed before its first) has no times to report.
  Frame& frame = frames_[current_];
  if (recording_) frame.pending = std::find(frame.used.begin(), frame.used.end(), true) != frame.used.end();
  recording_ = false;
}

void GpuPassTimer::begin(Pass pass) {
  if (!recording_) return;
  Frame& frame = frames_[current_];
  functions_->beginQuery(GL_TIME_ELAPSED_EXT, frame.queries[static_cast<int>(pass)]);
  frame.used[static_cast<int>(pass)] = true;
}

void GpuPassTimer::end(Pass) {
  if (recording_) functions_->endQuery(GL_TIME_ELAPSED_EXT);
}

}  // namespace obscura
