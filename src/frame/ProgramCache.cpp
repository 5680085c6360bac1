#include "frame/ProgramCache.h"

namespace obscura {

const gl::Program& ProgramCache::get(const ProgramSpec& spec) {
  const auto it = programs_.find(spec.name);
  if (it != programs_.end()) return *it->second;
  auto program = std::make_unique<gl::Program>(spec.build(strict_));
  return *programs_.emplace(spec.name, std::move(program)).first->second;
}

const gl::Program& ProgramCache::get(const std::string& name, const std::function<ProgramSpec()>& spec) {
  const auto it = programs_.find(name);
  if (it != programs_.end()) return *it->second;
  return get(spec());
}

}  // namespace obscura
