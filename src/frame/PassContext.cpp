#include "frame/PassContext.h"

#include "base/Error.h"

namespace obscura {
namespace {

std::string passName(const FramePlan& plan, int pass) { return plan.passes()[static_cast<size_t>(pass)].decl.name; }

}  // namespace

const TargetVersion& PassContext::readVersion(const std::string& target) const {
  const PlannedPass& pass = plan_.passes()[static_cast<size_t>(pass_)];
  const auto it = pass.reads.find(target);
  if (it == pass.reads.end())
    throw PipelineError("pass '" + passName(plan_, pass_) + "' reads '" + target + "' without declaring it, or " +
                        "reads an optional target no running pass wrote");
  return plan_.versions()[static_cast<size_t>(it->second)];
}

const TargetVersion& PassContext::writeVersion(const std::string& target) const {
  const PlannedPass& pass = plan_.passes()[static_cast<size_t>(pass_)];
  const auto it = pass.writes.find(target);
  if (it == pass.writes.end())
    throw PipelineError("pass '" + passName(plan_, pass_) + "' writes '" + target + "' without declaring it");
  return plan_.versions()[static_cast<size_t>(it->second)];
}

const gl::Texture2D& PassContext::texture(const std::string& target) const {
  const TargetVersion& version = readVersion(target);
  if (version.history) {
    const RenderTargetPool::History* history = pool_.findHistory(version.target);
    if (!history) throw PipelineError("pass '" + passName(plan_, pass_) + "' reads history '" + target + "' unwritten");
    return history->current().color();
  }
  if (!version.slot)
    throw PipelineError("pass '" + passName(plan_, pass_) + "' reads '" + target + "', which has no pooled target");
  return pool_.slot(*version.slot).color();
}

const gl::Texture2D& PassContext::writtenTexture(const std::string& target) const {
  const TargetVersion& version = writeVersion(target);
  if (!version.slot)
    throw PipelineError("pass '" + passName(plan_, pass_) + "' writes '" + target + "', which has no pooled target");
  return pool_.slot(*version.slot).color();
}

bool PassContext::has(const std::string& target) const {
  return plan_.passes()[static_cast<size_t>(pass_)].reads.count(target) != 0;
}

void PassContext::bindForWriting(const std::string& target) const {
  const TargetVersion& version = writeVersion(target);
  if (version.output) {
    glBindFramebuffer(GL_FRAMEBUFFER, output_.framebuffer);
    glViewport(0, 0, output_.width, output_.height);
    if (output_.region.width > 0 && output_.region.height > 0) {
      glEnable(GL_SCISSOR_TEST);
      glScissor(output_.region.x, output_.region.y, output_.region.width, output_.region.height);
      scissored_ = true;
    }
    return;
  }
  if (version.history) {
    pool_.history(version.target, version.size, version.filter).current().bindForDrawing();
    return;
  }
  if (!version.slot)
    throw PipelineError("pass '" + passName(plan_, pass_) + "' binds '" + target + "', which has no pooled target");
  const gl::RenderTarget& slot = pool_.slot(*version.slot);
  if (version.depth == PassDecl::Write::Depth::Shared) {
    const TargetVersion& depth = plan_.versions()[static_cast<size_t>(version.depthVersion)];
    glBindFramebuffer(GL_FRAMEBUFFER, pool_.sharedDepthFramebuffer(*version.slot, *depth.slot));
    glViewport(0, 0, slot.width(), slot.height());
    return;
  }
  slot.bindForDrawing();
}

void PassContext::bindForWriting(const std::vector<std::string>& targets) const {
  std::vector<SlotKey> slots;
  for (const std::string& target : targets) {
    const TargetVersion& version = writeVersion(target);
    if (!version.slot || version.depth == PassDecl::Write::Depth::Shared)
      throw PipelineError("pass '" + passName(plan_, pass_) + "' writes '" + target +
                          "' among several targets, which needs pooled targets with no shared depth");
    slots.push_back(*version.slot);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, pool_.multipleTargetFramebuffer(slots));
  const glm::ivec2 size = writeVersion(targets.front()).size.of({frame_.camera.width, frame_.camera.height});
  glViewport(0, 0, size.x, size.y);
}

glm::ivec2 PassContext::size(const std::string& target) const {
  const PlannedPass& pass = plan_.passes()[static_cast<size_t>(pass_)];
  const TargetVersion& version = pass.writes.count(target) ? writeVersion(target) : readVersion(target);
  if (version.output) return {output_.width, output_.height};
  return version.size.of({frame_.camera.width, frame_.camera.height});
}

bool PassContext::writesOutput(const std::string& target) const { return writeVersion(target).output; }

bool PassContext::sharesDepth(const std::string& target) const {
  return writeVersion(target).depth == PassDecl::Write::Depth::Shared;
}

void PassContext::finish() const {
  if (scissored_) glDisable(GL_SCISSOR_TEST);
  scissored_ = false;
}

}  // namespace obscura
