#include "frame/ProgramCache.h"

#include <algorithm>
#include <iterator>

#include "base/TimeSpent.h"

namespace obscura {

const gl::Program& ProgramCache::get(const ProgramSpec& spec) {
  const auto it = programs_.find(spec.name);
  if (it != programs_.end()) return finished(*it->second);
  if (rehearsing_) {
    if (std::none_of(rehearsed_.begin(), rehearsed_.end(), [&](const ProgramSpec& s) { return s.name == spec.name; }))
      rehearsed_.push_back(spec);
    return standIn();
  }
  return *programs_.emplace(spec.name, std::make_unique<gl::Program>(spec.build(strict_))).first->second;
}

const gl::Program& ProgramCache::get(const std::string& name, const std::function<ProgramSpec()>& spec) {
  const auto it = programs_.find(name);
  return it != programs_.end() ? finished(*it->second) : get(spec());
}

const gl::Program& ProgramCache::finished(gl::Program& program) {
  if (program.linked()) return program;
  if (rehearsing_) return standIn();
  const TimedScope timed("programs");
  program.finishLink();  // a failure throws, and again at each use, as a program built at once would
  --pending_;
  return program;
}

size_t ProgramCache::dropPending() {
  const size_t dropped = pending_;
  if (pending_ == 0) return 0;
  for (auto it = programs_.begin(); it != programs_.end();)
    it = it->second->linked() ? std::next(it) : programs_.erase(it);
  pending_ = 0;
  return dropped;
}

const gl::Program& ProgramCache::standIn() {
  // Every vertex outside the clip volume: a draw with it rasterises nothing. Lenient: the uniforms a pass sets on
  // the program it asked for go nowhere.
  if (!standIn_)
    standIn_ = std::make_unique<gl::Program>("rehearsal stand-in",
                                             "#version 100\nvoid main() { gl_Position = vec4(2.0, 2.0, 2.0, 1.0); }\n",
                                             "#version 100\nprecision mediump float;\n"
                                             "void main() { gl_FragColor = vec4(0.0); }\n",
                                             false);
  return *standIn_;
}

ProgramCache::Rehearsal::Rehearsal(ProgramCache& cache) : cache_(cache) { cache_.rehearsing_ = true; }

ProgramCache::Rehearsal::~Rehearsal() {
  cache_.rehearsing_ = false;
  // Begun only now, after everything the rehearsal asked GL (a framebuffer's completeness, the stand-in's link):
  // a question waits for every command before it, and these compiles are what the driver should be left with.
  for (const ProgramSpec& spec : cache_.rehearsed_)
    cache_.programs_.emplace(spec.name, std::make_unique<gl::Program>(spec.begin(cache_.strict_)));
  cache_.pending_ += cache_.rehearsed_.size();
  cache_.rehearsed_.clear();
  // The stand-in goes after them (so none of them takes its name): what is made later finds no trace of it.
  cache_.standIn_.reset();
}

}  // namespace obscura
