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

namespace {

int passIndex(const std::string& pass) {
  const std::vector<std::string>& names = framePassNames();
  const auto it = std::find(names.begin(), names.end(), pass);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

}  // namespace

GpuPassTimer::GpuPassTimer(const gl::GlCaps& caps, gl::ProcLoader loader)
    : generation_(gl::contextGeneration()),
      frames_(kFramesInFlight),
      lastResult_(framePassNames().size(), -1.0) {
  const size_t passes = framePassNames().size();
  for (Frame& frame : frames_) {
    frame.queries.assign(passes, 0);
    frame.used.assign(passes, false);
  }
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
  for (Frame& frame : frames_) functions_->genQueries(static_cast<GLsizei>(passes), frame.queries.data());
  available_ = true;
}

GpuPassTimer::~GpuPassTimer() {
  if (functions_ && generation_ == gl::contextGeneration())
    for (Frame& frame : frames_)
      functions_->deleteQueries(static_cast<GLsizei>(frame.queries.size()), frame.queries.data());
}

bool GpuPassTimer::collect(Frame& frame) {
  const size_t passCount = frame.queries.size();
  for (size_t p = 0; p < passCount; ++p) {
    if (!frame.used[p]) continue;
    GLuint ready = 0;
    functions_->getQueryObjectuiv(frame.queries[p], GL_QUERY_RESULT_AVAILABLE_EXT, &ready);
    if (!ready) return false;
  }
  for (size_t p = 0; p < passCount; ++p) {
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
  lastResultTag_ = frame.tag;
  ++results_;
  return true;
}

void GpuPassTimer::collectResults() {
  if (!available_ || std::none_of(frames_.begin(), frames_.end(), [](const Frame& f) { return f.pending; })) return;
  // Reading GPU_DISJOINT_EXT also clears it; a disjoint event makes every result in flight meaningless.
  GLint disjoint = 0;
  glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
  for (int age = 1; age <= kFramesInFlight; ++age) {
    Frame& frame = frames_[static_cast<size_t>((current_ + age) % kFramesInFlight)];  // oldest first
    if (!frame.pending) continue;
    if (disjoint) frame.pending = false;
    else if (!collect(frame)) break;  // later frames cannot be ready before this one
  }
}

void GpuPassTimer::beginFrame(double tag, bool measure) {
  recording_ = false;
  if (!available_) return;
  collectResults();
  if (++unmeasured_ < kMeasureEvery && !measure) return;
  const int next = (current_ + 1) % kFramesInFlight;
  if (frames_[static_cast<size_t>(next)].pending) return;  // its results have not come back: the next frame tries
  current_ = next;
  unmeasured_ = 0;
  Frame& frame = frames_[static_cast<size_t>(current_)];
  frame.used.assign(frame.used.size(), false);
  frame.tag = tag;
  recording_ = true;
}

void GpuPassTimer::endFrame() {
  // A frame that measured no pass (the renderer failed before its first) has no times to report.
  Frame& frame = frames_[static_cast<size_t>(current_)];
  if (recording_) frame.pending = std::find(frame.used.begin(), frame.used.end(), true) != frame.used.end();
  recording_ = false;
}

void GpuPassTimer::begin(const std::string& pass) {
  if (!recording_) return;
  Frame& frame = frames_[static_cast<size_t>(current_)];
  const int index = passIndex(pass);
  if (index < 0 || frame.used[static_cast<size_t>(index)]) return;
  functions_->beginQuery(GL_TIME_ELAPSED_EXT, frame.queries[static_cast<size_t>(index)]);
  frame.used[static_cast<size_t>(index)] = true;
  measuring_ = index;
}

void GpuPassTimer::end(const std::string& pass) {
  if (!recording_ || measuring_ < 0 || measuring_ != passIndex(pass)) return;
  functions_->endQuery(GL_TIME_ELAPSED_EXT);
  measuring_ = -1;
}

}  // namespace obscura
