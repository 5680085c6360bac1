#include "core/AccumulationReference.h"

#include <cmath>
#include <string>

#include "base/Error.h"
#include "core/EffectTable.h"
#include "gl/RenderTarget.h"

namespace obscura {

RenderSettings withoutTemporalEffects(const RenderSettings& settings) {
  RenderSettings out = settings;
  for (const EffectEntry& row : effectTable())
    if (row.info.temporal && row.info.hasSwitch) out.set(row.info.name, "off");
  // The AO's own accumulation over frames: a parameter of the AO, not an effect's switch.
  out.set("ao.temporal", "off");
  return out;
}

std::vector<double> shutterSampleTimes(double time, double fps, double shutter, int samples) {
  if (samples < 1) throw InputError("shutter samples: expected at least 1, got " + std::to_string(samples));
  if (!(fps > 0.0) || !std::isfinite(fps)) throw InputError("fps: expected a positive number");
  if (!(shutter >= 0.0 && shutter <= 1.0)) throw InputError("shutter: expected a fraction in [0, 1]");
  const double open = shutter / fps;  // the exposure's length, centred on `time`
  std::vector<double> times(static_cast<size_t>(samples));
  for (int i = 0; i < samples; ++i) times[static_cast<size_t>(i)] = time + open * ((i + 0.5) / samples - 0.5);
  return times;
}

Image LinearImage::toImage() const {
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.resize(rgba.size());
  for (size_t i = 0; i < rgba.size(); ++i)
    image.rgba[i] = static_cast<std::uint8_t>(std::lround(std::fmin(std::fmax(rgba[i], 0.0f), 1.0f) * 255.0f));
  return image;
}

LinearImage LinearImage::from(const std::vector<std::uint8_t>& rgba, int width, int height) {
  return downsampleBox(rgba, width, height, 1);
}

LinearImage downsampleBox(const std::vector<std::uint8_t>& rgba, int width, int height, int factor) {
  if (factor < 1 || width % factor != 0 || height % factor != 0 ||
      rgba.size() != static_cast<size_t>(width) * static_cast<size_t>(height) * 4)
    throw InputError("downsampleBox: a " + std::to_string(width) + "x" + std::to_string(height) +
                     " image does not divide into blocks of " + std::to_string(factor));
  LinearImage out;
  out.width = width / factor;
  out.height = height / factor;
  out.rgba.assign(static_cast<size_t>(out.width) * out.height * 4, 0.0f);
  const float scale = 1.0f / (255.0f * static_cast<float>(factor * factor));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 4; ++c)
        out.rgba[(static_cast<size_t>(y / factor) * out.width + x / factor) * 4 + c] +=
            rgba[(static_cast<size_t>(y) * width + x) * 4 + c] * scale;
  return out;
}

LinearImage accumulateShutter(Renderer& renderer, const std::function<Camera(double)>& cameraAt,
                              const RenderSettings& settings, const AccumulationOptions& options) {
  if (options.supersample < 1) throw InputError("supersample: expected at least 1");
  const std::vector<double> times =
      shutterSampleTimes(options.time, options.fps, options.shutter, options.samples);
  const RenderSettings subFrame = withoutTemporalEffects(settings);
  const Camera first = cameraAt(times.front());
  const int k = options.supersample;
  const int width = first.width * k, height = first.height * k;
  const int limit = renderer.caps().maxRenderSize();
  if (width > limit || height > limit)
    throw InputError("supersampled size " + std::to_string(width) + "x" + std::to_string(height) +
                     " exceeds this context's limit of " + std::to_string(limit) + " per side");
  // Like obscura-render's output: a depth and stencil buffer, so FXAA (when on) runs the same two draws.
  const gl::RenderTarget output("accumulation sub-frame", width, height, GL_NEAREST,
                                gl::RenderTarget::Depth::Renderbuffer, renderer.caps().depth24,
                                renderer.caps().packedDepthStencil);
  LinearImage sum;
  sum.width = first.width;
  sum.height = first.height;
  sum.rgba.assign(static_cast<size_t>(sum.width) * sum.height * 4, 0.0f);
  FrameOptions frame;
  frame.animation = options.animation;
  frame.loop = options.loop;
  for (double t : times) {
    Camera camera = cameraAt(t);
    if (camera.width != first.width || camera.height != first.height)
      throw InputError("accumulateShutter: every sub-frame's camera must have the same size");
    camera.width = width;
    camera.height = height;
    frame.time = t;
    frame.previousTime = t;  // nothing reads motion: the temporal effects are off
    renderer.render(camera, subFrame, View::Final, OutputTarget{output.framebuffer(), width, height, {}}, frame);
    const LinearImage image = downsampleBox(output.readRgba(), width, height, k);
    for (size_t i = 0; i < sum.rgba.size(); ++i) sum.rgba[i] += image.rgba[i];
  }
  for (float& v : sum.rgba) v /= static_cast<float>(times.size());
  return sum;
}

}  // namespace obscura
