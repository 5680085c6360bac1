#pragma once
// Every program a Renderer's frame uses, by its spec's name (ProgramSpec::name identifies a program: its files,
// defines and extensions), built on first use and kept for the Renderer's life, strict where the Renderer checks GL
// errors (gl/Program.h). Effects reach it through EffectResources::program and PassContext::program; the fused
// programs of per-pixel stages (frame/Stage.h) are built here too, the first time a plan fuses that chain.
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "gl/Program.h"
#include "gl/ShaderLibrary.h"

namespace obscura {

class ProgramCache {
 public:
  explicit ProgramCache(bool strict) : strict_(strict) {}
  ProgramCache(const ProgramCache&) = delete;
  ProgramCache& operator=(const ProgramCache&) = delete;

  // The program of `spec`, built now if this is its first use, or finished if it was begun (GlError if it does not
  // compile or link).
  const gl::Program& get(const ProgramSpec& spec);
  // The program named `name`, its spec made by `spec` only if it is not built yet (a fused program's text is
  // generated once).
  const gl::Program& get(const std::string& name, const std::function<ProgramSpec()>& spec);
  // Whether `name`'s program has been built (linked, or begun: Rehearsal).
  bool built(const std::string& name) const { return programs_.count(name) != 0; }
  size_t size() const { return programs_.size(); }
  // Programs begun and not yet finished by a get().
  size_t pending() const { return pending_; }
  // Deletes the programs begun and never finished (a rehearsed frame that was not drawn: the state changed since);
  // returns how many.
  size_t dropPending();

  // While a Rehearsal lives, get() notes each program it is asked for that is not built and returns a stand-in, a
  // program that draws nothing, in its place; the Rehearsal's end begins them (gl::Program::begin: compiled and
  // linked without waiting). A frame run so begins every program it draws with and waits for none: the driver
  // compiles them while the caller goes on, and the next get() of each finishes it (Renderer::prepare). The stand-in
  // is deleted at the Rehearsal's end: nothing may keep it, or what it tells (ProgramVariants does not keep it,
  // GpuScene withholding its draws keeps no locations of it, the lines' pass looks its attributes up each frame).
  class Rehearsal {
   public:
    explicit Rehearsal(ProgramCache& cache);
    ~Rehearsal();
    Rehearsal(const Rehearsal&) = delete;
    Rehearsal& operator=(const Rehearsal&) = delete;

   private:
    ProgramCache& cache_;
  };
  bool rehearsing() const { return rehearsing_; }

 private:
  // A program found: finished now if it was begun (the stand-in while rehearsing).
  const gl::Program& finished(gl::Program& program);
  const gl::Program& standIn();

  bool strict_;
  bool rehearsing_ = false;
  size_t pending_ = 0;  // begun, not finished
  std::vector<ProgramSpec> rehearsed_;  // asked for during the rehearsal, to begin at its end
  std::unordered_map<std::string, std::unique_ptr<gl::Program>> programs_;
  std::unique_ptr<gl::Program> standIn_;
};

// Programs a pass chooses per draw by a key of its own (a material and vertex kind): the key found in a small map
// to the cache's program, its spec made (by the caller's function) only the first time: a geometry pass switches
// programs many times a frame.
template <typename Key>
class ProgramVariants {
 public:
  explicit ProgramVariants(ProgramCache& cache) : cache_(cache) {}
  template <typename MakeSpec>
  const gl::Program& operator()(const Key& key, MakeSpec&& spec) const {
    auto it = programs_.find(key);
    if (it != programs_.end()) return *it->second;
    const gl::Program& program = cache_.get(spec());
    if (!cache_.rehearsing()) programs_.emplace(key, &program);  // not a rehearsal's stand-in
    return program;
  }

 private:
  ProgramCache& cache_;
  mutable std::map<Key, const gl::Program*> programs_;
};

}  // namespace obscura
