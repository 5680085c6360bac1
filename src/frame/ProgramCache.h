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

#include "gl/Program.h"
#include "gl/ShaderLibrary.h"

namespace obscura {

class ProgramCache {
 public:
  explicit ProgramCache(bool strict) : strict_(strict) {}
  ProgramCache(const ProgramCache&) = delete;
  ProgramCache& operator=(const ProgramCache&) = delete;

  // The program of `spec`, built now if this is its first use (GlError if it does not compile or link).
  const gl::Program& get(const ProgramSpec& spec);
  // The program named `name`, its spec made by `spec` only if it is not built yet (a fused program's text is
  // generated once).
  const gl::Program& get(const std::string& name, const std::function<ProgramSpec()>& spec);
  // Whether `name`'s program has been built.
  bool built(const std::string& name) const { return programs_.count(name) != 0; }
  size_t size() const { return programs_.size(); }

 private:
  bool strict_;
  std::unordered_map<std::string, std::unique_ptr<gl::Program>> programs_;
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
    if (it == programs_.end()) it = programs_.emplace(key, &cache_.get(spec())).first;
    return *it->second;
  }

 private:
  ProgramCache& cache_;
  mutable std::map<Key, const gl::Program*> programs_;
};

}  // namespace obscura
