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
    const OutputTarget::Region& region = output_.region;
    if (region.width > 0 && region.height > 0)
      scissor(target, {region.x, region.y, region.width, region.height});
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

namespace {

glm::ivec4 intersection(const glm::ivec4& a, const glm::ivec4& b) {
  const glm::ivec2 from = glm::max(glm::ivec2(a.x, a.y), glm::ivec2(b.x, b.y));
  const glm::ivec2 to = glm::min(glm::ivec2(a.x + a.z, a.y + a.w), glm::ivec2(b.x + b.z, b.y + b.w));
  return {from, glm::max(to - from, glm::ivec2(0))};
}

}  // namespace

glm::ivec4 PassContext::withinOutputRegion(const std::string& target, const glm::ivec4& rect) const {
  const OutputTarget::Region& region = output_.region;
  if (writesOutput(target) && region.width > 0 && region.height > 0)
    return intersection(rect, {region.x, region.y, region.width, region.height});
  return rect;
}

glm::ivec4 PassContext::sceneRect(const std::string& target) const {
  const glm::ivec2 frameSize(frame_.camera.width, frame_.camera.height);
  const glm::ivec4& rect = frame_.sceneBounds;
  const glm::ivec2 targetSize = size(target);
  // Target pixel p stands for frame pixels from p * frame / target on (a half-size AO pixel p for frame pixel 2p).
  const glm::vec2 scale = glm::vec2(targetSize) / glm::vec2(frameSize);
  const glm::ivec2 from = glm::max(glm::ivec2(glm::floor(glm::vec2(rect.x, rect.y) * scale)) - 1, glm::ivec2(0));
  const glm::ivec2 to =
      glm::min(glm::ivec2(glm::ceil(glm::vec2(rect.x + rect.z, rect.y + rect.w) * scale)) + 1, targetSize);
  return withinOutputRegion(target, glm::ivec4(from, glm::max(to - from, glm::ivec2(0))));
}

bool PassContext::coversTarget(const std::string& target, const glm::ivec4& rect) const {
  const glm::ivec2 whole = size(target);
  return rect.x <= 0 && rect.y <= 0 && rect.x + rect.z >= whole.x && rect.y + rect.w >= whole.y;
}

void PassContext::scissor(const std::string& target, const glm::ivec4& rect) const {
  const glm::ivec4 r = withinOutputRegion(target, rect);
  if (coversTarget(target, r)) {
    // All of the target (the scene fills the frame; the output's region is all of it): no test to set, and three
    // calls a pass saved (a WebGL call costs the page host time whatever it does).
    if (scissored_) glDisable(GL_SCISSOR_TEST);
    scissored_ = false;
    return;
  }
  glEnable(GL_SCISSOR_TEST);
  glScissor(r.x, r.y, r.z, r.w);
  scissored_ = true;
}

void PassContext::drawAroundScene(const std::string& target, const std::function<void()>& drawBand) const {
  const glm::ivec4 covered = sceneRect(target);
  const glm::ivec2 whole = size(target);
  const int top = covered.y + covered.w, right = covered.x + covered.z;
  // Below and above the bounds, then to their left and right; the empty ones left out.
  const glm::ivec4 bands[] = {{0, 0, whole.x, covered.y},
                              {0, top, whole.x, whole.y - top},
                              {0, covered.y, covered.x, covered.w},
                              {right, covered.y, whole.x - right, covered.w}};
  for (const glm::ivec4& band : bands) {
    if (band.z <= 0 || band.w <= 0) continue;
    scissor(target, band);
    drawBand();
  }
  scissor(target, covered);
}

void PassContext::drawDepthTested(GLenum depthFunc, bool writeDepth, const std::function<void()>& draw) const {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(depthFunc);
  if (!writeDepth) glDepthMask(GL_FALSE);
  draw();
  glDisable(GL_DEPTH_TEST);
  if (!writeDepth) glDepthMask(GL_TRUE);
  glUseProgram(0);
}

void PassContext::limitToScene(const std::string& target, const glm::vec4& outside) const {
  if (writesOutput(target)) throw PipelineError("limitToScene: '" + target + "' is the output framebuffer");
  const glm::ivec4 scene = sceneRect(target);
  if (coversTarget(target, scene)) return;  // no pixel outside: nothing to clear, nothing to scissor
  glClearColor(outside.r, outside.g, outside.b, outside.a);
  glClear(GL_COLOR_BUFFER_BIT);
  scissor(target, scene);
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
