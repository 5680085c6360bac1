#include "frame/RenderTargetPool.h"

#include <algorithm>

namespace obscura {
namespace {

std::string slotName(const SlotKey& key) {
  return "pooled target (" + key.size.name() + (key.filter == GL_LINEAR ? ", linear" : "") +
         (key.ownDepth ? ", depth" : "") + " #" + std::to_string(key.index) + ")";
}

}  // namespace

void RenderTargetPool::beginFrame(glm::ivec2 size) {
  ++frame_;
  if (size == size_) return;
  size_ = size;
  sharedDepth_.clear();
  multipleTargets_.clear();
  slots_.clear();
  if (!history_.empty()) ++historyDrops_;
  history_.clear();
}

const gl::RenderTarget& RenderTargetPool::slot(const SlotKey& key) {
  auto it = slots_.find(key);
  if (it == slots_.end()) {
    const glm::ivec2 size = key.size.of(size_);
    it = slots_
             .emplace(key, Slot{gl::RenderTarget(slotName(key), size.x, size.y, key.filter,
                                                 key.ownDepth ? gl::RenderTarget::Depth::Renderbuffer
                                                              : gl::RenderTarget::Depth::None,
                                                 depth24_, key.ownDepth && stencil_),
                                0})
             .first;
  }
  it->second.lastUsed = frame_;
  return it->second.target;
}

GLuint RenderTargetPool::sharedDepthFramebuffer(const SlotKey& color, const SlotKey& depth) {
  const auto key = std::make_pair(color, depth);
  auto it = sharedDepth_.find(key);
  if (it == sharedDepth_.end())
    it = sharedDepth_
             .emplace(key, gl::RenderTarget::sharingDepth(slot(color), slot(depth),
                                                          slotName(color) + " with the depth of " + slotName(depth)))
             .first;
  return it->second.id();
}

GLuint RenderTargetPool::multipleTargetFramebuffer(const std::vector<SlotKey>& colors) {
  auto it = multipleTargets_.find(colors);
  if (it == multipleTargets_.end()) {
    std::vector<const gl::RenderTarget*> targets;
    for (const SlotKey& key : colors) targets.push_back(&slot(key));
    std::string name;
    for (const SlotKey& key : colors) name += (name.empty() ? "" : " + ") + slotName(key);
    it = multipleTargets_.emplace(colors, gl::RenderTarget::multipleTargets(targets, name)).first;
  }
  for (const SlotKey& key : colors) slot(key);  // marks them used
  return it->second.id();
}

void RenderTargetPool::endFrame() {
  for (auto it = slots_.begin(); it != slots_.end();) {
    if (frame_ - it->second.lastUsed < static_cast<std::uint64_t>(kKeepUnusedFrames)) {
      ++it;
      continue;
    }
    for (auto shared = sharedDepth_.begin(); shared != sharedDepth_.end();) {
      if (shared->first.first == it->first || shared->first.second == it->first) shared = sharedDepth_.erase(shared);
      else ++shared;
    }
    for (auto multiple = multipleTargets_.begin(); multiple != multipleTargets_.end();) {
      const std::vector<SlotKey>& keys = multiple->first;
      if (std::find(keys.begin(), keys.end(), it->first) != keys.end()) multiple = multipleTargets_.erase(multiple);
      else ++multiple;
    }
    it = slots_.erase(it);
  }
  for (auto& [name, history] : history_) {
    if (!history.written_) continue;
    history.written_ = false;
    history.valid_ = true;
    history.current_ = 1 - history.current_;
  }
}

RenderTargetPool::History& RenderTargetPool::history(const std::string& name, const TargetSize& size,
                                                     GLenum filter) {
  History& history = history_[name];
  if (!history.targets_[0]) {
    // Made on first use, perhaps while a pass draws into another framebuffer: that binding is kept.
    GLint bound = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &bound);
    const glm::ivec2 pixels = size.of(size_);
    for (int i = 0; i < 2; ++i)
      history.targets_[i] = gl::RenderTarget("history '" + name + "' " + std::to_string(i), pixels.x, pixels.y,
                                             filter, gl::RenderTarget::Depth::None, false);
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(bound));
  }
  history.written_ = true;
  return history;
}

const RenderTargetPool::History* RenderTargetPool::findHistory(const std::string& name) const {
  const auto it = history_.find(name);
  return it == history_.end() ? nullptr : &it->second;
}

void RenderTargetPool::dropHistory() {
  if (!history_.empty()) ++historyDrops_;
  history_.clear();
}

}  // namespace obscura
