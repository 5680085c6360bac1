#include "effects/ao/AoTemporalPass.h"

#include <cmath>

#include <glm/matrix.hpp>

#include "effects/ao/AoTemporal.h"
#include "gl/PipelineState.h"

namespace obscura {

std::vector<ProgramSpec> AoTemporalPass::programSpecs() {
  return {ProgramSpec{"ao-temporal", "lib/fullscreen.vert", "ao/ao_temporal.frag", {}, {}}};
}

AoTemporalPass::AoTemporalPass(const EffectResources& resources)
    : resources_(resources),
      program_(resources.build(programSpecs().front())),
      reconstruction_(program_),
      aoRaw_(program_.uniform("u_aoRaw")),
      history_(program_.uniform("u_history")),
      velocity_(program_.uniform("u_velocity")),
      gbuffer_(program_.uniform("u_gbuffer")),
      gbufferSize_(program_.uniform("u_gbufferSize")),
      aoSize_(program_.uniform("u_aoSize")),
      aoScale_(program_.uniform("u_aoScale")),
      historyValid_(program_.uniform("u_historyValid")),
      maxFrames_(program_.uniform("u_maxFrames")),
      planeTolerance_(program_.uniform("u_planeTolerance")),
      ditherOffset_(program_.uniform("u_ditherOffset")),
      previousFarHalfExtent_(program_.uniform("u_previousFarHalfExtent")),
      previousDepthToRay_(program_.uniform("u_previousDepthToRay")),
      previousViewToView_(program_.uniform("u_previousViewToView")),
      diskScale_(program_.uniform("u_diskScale")),
      maxRadiusPixels_(program_.uniform("u_maxRadiusPixels")),
      objectsMove_(program_.uniform("u_objectsMove")),
      tapRotation_(program_.uniform("u_tapRotation")) {}

void AoTemporalPass::render(const gl::Texture2D& rawAo, const gl::Texture2D& velocity, const gl::Texture2D& gbuffer,
                            RenderTargetPool::History& history, const FrameContext& frame,
                            const AoSettings& settings, int aoScale, glm::ivec2 aoSize, bool objectsMove) {
  using gl::Program;
  const Written now{frame.index, settings.estimator, settings.samples, aoScale, settings.radius};
  Written expected = now;
  expected.frame = frame.index - 1;
  // A second run in the same frame (the split view draws both halves from one frame context) reads the same
  // previous history again, as validly as the first did.
  const bool again = written_ && *written_ == now;
  const bool historyValid =
      history.valid() && frame.hasPrevious && (again ? historyWasValid_ : written_ && *written_ == expected);

  program_.use();
  rawAo.bind(0);
  Program::set(aoRaw_, 0);
  history.previous().color().bind(1);
  Program::set(history_, 1);
  velocity.bind(2);
  Program::set(velocity_, 2);
  gbuffer.bind(3);
  Program::set(gbuffer_, 3);
  Program::set(gbufferSize_, glm::vec2(gbuffer.width(), gbuffer.height()));
  Program::set(aoSize_, glm::vec2(aoSize));
  Program::set(aoScale_, static_cast<float>(aoScale));
  Program::set(historyValid_, historyValid ? 1.0f : 0.0f);
  Program::set(maxFrames_, static_cast<float>(settings.temporalFrames));
  // The tolerance of the tangent-plane test is the bilateral blur's depth sigma: the distance from the plane at
  // which the blur, too, stops treating a neighbour as the same surface.
  Program::set(planeTolerance_, settings.blurDepthSigmaDistance());
  Program::set(ditherOffset_, AoTemporal::ditherOffset(frame.index));
  // The projected AO radius, as the estimators have it (ao/ao_estimator.glsl: aoCentre).
  Program::set(diskScale_, frame.camera.projScale(gbuffer.height()) * settings.radius);
  Program::set(maxRadiusPixels_, settings.maxScreenRadius * static_cast<float>(gbuffer.height()));
  Program::set(objectsMove_, objectsMove ? 1.0f : 0.0f);
  // The velocity taps turn by the frame's rotation offset, an eighth of a turn at most (their pattern repeats every
  // quarter turn; two rings 45 degrees apart).
  const float turn = AoTemporal::frameOffset(frame.index).x * 0.25f * 3.14159265f;
  Program::set(tapRotation_, glm::vec2(std::cos(turn), std::sin(turn)));
  reconstruction_.set(frame.camera.reconstruction);
  const ViewReconstruction& previous = frame.previousCamera.reconstruction;
  Program::set(previousFarHalfExtent_, previous.farHalfExtent);
  Program::set(previousDepthToRay_, previous.depthToRay);
  Program::set(previousViewToView_, frame.camera.view * glm::inverse(frame.previousCamera.view));
  resources_.triangle.draw();

  // The history the next frame reads: a copy of what was just drawn (the bound framebuffer).
  history.current().color().bind(0);
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, aoSize.x, aoSize.y);
  gl::restoreBaselineState();
  written_ = now;
  historyWasValid_ = historyValid;
}

}  // namespace obscura
