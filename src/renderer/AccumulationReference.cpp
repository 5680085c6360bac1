#include "renderer/AccumulationReference.h"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "base/Error.h"
#include "effects/dof/DepthOfFieldEffect.h"
#include "effects/tonemap/TonemapEffect.h"
#include "encoding/HdrEncoding.h"
#include "encoding/LinearDepthPacking.h"
#include "gl/RenderTarget.h"
#include "renderer/EffectTable.h"

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

namespace {

// One sub-frame of a reference: its camera (the image's size), time and projection shift (pixels of the image), and
// the shift's growth with depth (pixels per metre: the orthographic aperture's tilted rays).
struct SubFrame {
  Camera camera;
  double time = 0.0;
  glm::vec2 shift{0.0f};
  glm::vec2 shear{0.0f};
};

// The mean of the sub-frames' final images, each rendered at `k` times its size and box-downsampled. `linearLight`:
// the mean of their HDR colour (scene-color, decoded), tone-mapped afterwards with the settings' tone mapping.
LinearImage meanOfRenders(Renderer& renderer, const std::vector<SubFrame>& subFrames, const RenderSettings& settings,
                          int k, const AnimationChoice& animation, bool loop, bool linearLight = false) {
  if (k < 1) throw InputError("supersample: expected at least 1");
  const Camera& first = subFrames.front().camera;
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
  frame.animation = animation;
  frame.loop = loop;
  frame.allowCheapFrame = false;  // every sub-frame the frame asked for (resolution.quick-start's cheap one is not)
  if (linearLight) frame.retain = {"scene-color"};
  for (const SubFrame& sub : subFrames) {
    Camera camera = sub.camera;
    if (camera.width != first.width || camera.height != first.height)
      throw InputError("accumulation: every sub-frame's camera must have the same size");
    camera.width = width;
    camera.height = height;
    frame.time = sub.time;
    frame.previousTime = sub.time;  // nothing reads motion: the temporal effects are off
    frame.projectionShift = sub.shift * static_cast<float>(k);
    frame.projectionShear = sub.shear * static_cast<float>(k);
    renderer.render(camera, settings, View::Final, OutputTarget{output.framebuffer(), width, height, {}}, frame);
    if (!linearLight) {
      const LinearImage image = downsampleBox(output.readRgba(), width, height, k);
      for (size_t i = 0; i < sum.rgba.size(); ++i) sum.rgba[i] += image.rgba[i];
      continue;
    }
    const std::vector<std::uint8_t> hdr = renderer.retained("scene-color").readRgba();  // rows top to bottom
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::uint8_t* t = &hdr[(static_cast<size_t>(y) * width + x) * 4];
        const glm::vec3 c = decodeHdr(HdrTexel{t[0], t[1], t[2], t[3]}) / static_cast<float>(k * k);
        float* s = &sum.rgba[(static_cast<size_t>(y / k) * sum.width + x / k) * 4];
        s[0] += c.r;
        s[1] += c.g;
        s[2] += c.b;
      }
  }
  for (float& v : sum.rgba) v /= static_cast<float>(subFrames.size());
  if (linearLight) {
    const ToneMapInUse tone = ToneMapInUse::of(settings.of<TonemapSettings>());
    for (size_t i = 0; i < sum.rgba.size(); i += 4) {
      const glm::vec4 display = tone.displayColor(glm::vec3(sum.rgba[i], sum.rgba[i + 1], sum.rgba[i + 2]), false);
      for (int c = 0; c < 4; ++c) sum.rgba[i + static_cast<size_t>(c)] = display[c];
    }
  }
  return sum;
}

}  // namespace

LinearImage accumulateShutter(Renderer& renderer, const std::function<Camera(double)>& cameraAt,
                              const RenderSettings& settings, const AccumulationOptions& options) {
  std::vector<SubFrame> subFrames;
  for (double t : shutterSampleTimes(options.time, options.fps, options.shutter, options.samples))
    subFrames.push_back({cameraAt(t), t, glm::vec2(0.0f)});
  return meanOfRenders(renderer, subFrames, withoutTemporalEffects(settings), options.supersample, options.animation,
                       options.loop);
}

glm::vec2 lensPoint(int i, int n) {
  constexpr double kGoldenAngle = 2.39996322972865332;  // 2 pi (1 - 1 / phi)
  const double r = std::sqrt((i + 0.5) / n), a = kGoldenAngle * i;
  return {static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a))};
}

float autofocusDistance(Renderer& renderer, const Camera& camera, const RenderSettings& settings, double time,
                        const AnimationChoice& animation) {
  RenderSettings pinhole = withoutTemporalEffects(settings);
  pinhole.set("dof", "off");
  const gl::RenderTarget output("autofocus frame", camera.width, camera.height, GL_NEAREST,
                                gl::RenderTarget::Depth::Renderbuffer, renderer.caps().depth24,
                                renderer.caps().packedDepthStencil);
  FrameOptions frame;
  frame.time = frame.previousTime.emplace(time);
  frame.animation = animation;
  frame.allowCheapFrame = false;
  frame.retain = {"gbuffer"};
  renderer.render(camera, pinhole, View::Final, OutputTarget{output.framebuffer(), camera.width, camera.height, {}},
                  frame);
  const std::vector<std::uint8_t> gbuffer = renderer.retained("gbuffer").readRgba();
  const glm::ivec2 pixel = settings.of<DofSettings>().focusPixel(camera.width, camera.height);
  const std::uint8_t* texel = &gbuffer[(static_cast<size_t>(pixel.y) * camera.width + pixel.x) * 4];
  const float depth = LinearDepthPacking::depthFromCode(LinearDepthPacking::codeFromBytes(texel[2], texel[3]));
  return camera.near + depth * (camera.far - camera.near);
}

LinearImage accumulateAperture(Renderer& renderer, const Camera& camera, const RenderSettings& settings,
                               const ApertureOptions& options) {
  if (options.samples < 1) throw InputError("aperture samples: expected at least 1, got " +
                                            std::to_string(options.samples));
  const DofSettings& dof = settings.of<DofSettings>();
  const ThinLens lens = ThinLens::of(dof, camera.height, camera.orthographic);
  const float focus = lens.usableFocus(
      dof.focus ? *dof.focus : autofocusDistance(renderer, camera, settings, options.time, options.animation));
  std::vector<SubFrame> subFrames;
  RenderSettings pinhole = withoutTemporalEffects(settings);
  pinhole.set("dof", "off");
  // What the tone mapping adds is not part of the mean (it tone-maps the HDR mean itself).
  for (const char* added : {"auto-exposure", "lens-flare", "glare"})
    if (RenderSettings::find(added)) pinhole.set(added, "off");
  if (camera.orthographic) {
    // Parallel rays tilted over a disc of slopes about the plane in focus: a point at depth D moves by the slope
    // times D - P metres, pixelsPerMetre pixels each, so the plane P stays and the rest spreads over the
    // orthographic CoC (effects/dof/DepthOfFieldEffect.h).
    const float pixelsPerMetre = FrameCamera::from(camera, camera.width, camera.height).pixelsPerMetre(camera.height,
                                                                                                        focus);
    const float slopeRadius = 0.5f * lens.parallelAperture(focus, pixelsPerMetre);
    for (int i = 0; i < options.samples; ++i) {
      const glm::vec2 shear = lensPoint(i, options.samples) * slopeRadius * pixelsPerMetre;
      subFrames.push_back({camera, options.time, -shear * focus, shear});
    }
    return meanOfRenders(renderer, subFrames, pinhole, options.supersample, options.animation, true, true);
  }
  const float projScale = FrameCamera::from(camera, camera.width, camera.height).projScale(camera.height).x;
  const float lensRadius = 0.5f * lens.pinholeAperture(focus, projScale);
  // The camera's own axes: a lens point (x, y) moves the eye along them, the view direction unchanged.
  const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::vec3 up = glm::cross(right, forward);
  for (int i = 0; i < options.samples; ++i) {
    const glm::vec2 a = lensPoint(i, options.samples) * lensRadius;  // metres on the lens
    SubFrame sub{camera, options.time, glm::vec2(0.0f)};
    sub.camera.eye += right * a.x + up * a.y;
    sub.camera.target += right * a.x + up * a.y;
    // A point on the plane in focus moves by -a projScale / P pixels in the moved camera's image: shear it back.
    sub.shift = a * (projScale / focus);
    subFrames.push_back(sub);
  }
  return meanOfRenders(renderer, subFrames, pinhole, options.supersample, options.animation, true, true);
}

}  // namespace obscura
