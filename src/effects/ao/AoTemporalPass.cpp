#include "effects/ao/AoTemporalPass.h"

#include <cmath>

#include <glm/matrix.hpp>

#include "effects/ao/AoTemporal.h"
#include "frame/FullscreenPass.h"

namespace obscura {

std::vector<ProgramSpec> AoTemporalPass::programSpecs() {
  return {ProgramSpec{"ao-temporal", "lib/fullscreen.vert", "ao/ao_temporal.frag", {}, {}}};
}

void AoTemporalPass::render(const gl::Texture2D& rawAo, const gl::Texture2D& velocity, const gl::Texture2D& gbuffer,
                            RenderTargetPool::History& history, const FrameContext& frame,
                            const AoSettings& settings, int aoScale, glm::ivec2 aoSize, bool objectsMove) {
  const Written now{frame.index, settings.estimator, settings.samples, aoScale, settings.radius};
  Written expected = now;
  expected.frame = frame.index - 1;
  // A second run in the same frame (the split view draws both halves from one frame context) reads the same
  // previous history again, as validly as the first did.
  const bool again = written_ && *written_ == now;
  const bool historyValid =
      history.valid() && frame.hasPrevious && (again ? historyWasValid_ : written_ && *written_ == expected);

  {
    FullscreenDraw draw(resources_.program(programSpecs().front()), resources_.triangle);
    draw.texture("u_aoRaw", rawAo);
    draw.texture("u_history", history.previous().color());
    draw.texture("u_velocity", velocity);
    draw.texture("u_gbuffer", gbuffer);
    draw.set("u_gbufferSize", glm::vec2(gbuffer.width(), gbuffer.height()));
    draw.set("u_aoSize", glm::vec2(aoSize));
    draw.set("u_aoScale", static_cast<float>(aoScale));
    draw.set("u_historyValid", historyValid ? 1.0f : 0.0f);
    draw.set("u_maxFrames", static_cast<float>(settings.temporalFrames));
    // The tolerance of the tangent-plane test is the bilateral blur's depth sigma: the distance from the plane at
    // which the blur, too, stops treating a neighbour as the same surface.
    draw.set("u_planeTolerance", settings.blurDepthSigmaDistance());
    draw.set("u_ditherOffset", AoTemporal::ditherOffset(frame.index));
    // The projected AO radius, as the estimators have it (ao/ao_estimator.glsl: aoCentre).
    draw.set("u_diskScale", frame.camera.projScale(gbuffer.height()) * settings.radius);
    draw.set("u_maxRadiusPixels", settings.maxScreenRadius * static_cast<float>(gbuffer.height()));
    draw.set("u_objectsMove", objectsMove ? 1.0f : 0.0f);
    // The velocity taps turn by the frame's rotation offset, an eighth of a turn at most (their pattern repeats
    // every quarter turn; two rings 45 degrees apart).
    const float turn = AoTemporal::frameOffset(frame.index).x * 0.25f * 3.14159265f;
    draw.set("u_tapRotation", glm::vec2(std::cos(turn), std::sin(turn)));
    setReconstruction(draw.program(), frame.camera.reconstruction);
    const ViewReconstruction& previous = frame.previousCamera.reconstruction;
    draw.set("u_previousFarHalfExtent", previous.farHalfExtent);
    draw.set("u_previousDepthToRay", previous.depthToRay);
    draw.set("u_previousViewToView", frame.camera.view * glm::inverse(frame.previousCamera.view));
    draw.draw();
  }

  // The history the next frame reads: a copy of what was just drawn (the bound framebuffer).
  glBindTexture(GL_TEXTURE_2D, history.current().color().id());
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, aoSize.x, aoSize.y);
  glBindTexture(GL_TEXTURE_2D, 0);
  written_ = now;
  historyWasValid_ = historyValid;
}

}  // namespace obscura
