#include "effects/glare/GlareEffect.h"

#include <cmath>
#include <string>

#include <glm/trigonometric.hpp>

#include "frame/PassContext.h"
#include "frame/FullscreenPass.h"

namespace obscura {
namespace {

const char* const kTemporaries[3] = {"glare-a", "glare-b", "glare-c"};

ProgramSpec spec(bool last) {
  return ProgramSpec{std::string("glare[") + (last ? "last" : "pass") + "]",
                     "lib/fullscreen.vert",
                     "glare/glare.frag",
                     {{"GLARE_LAST", last ? "1" : "0"}, {"FAR_RAY", "0"}}};
}

}  // namespace

const std::vector<Parameter<GlareSettings>>& GlareSettings::parameters() {
  using S = GlareSettings;
  static const std::vector<Parameter<S>> table = {
      switchParameter<S>("glare", "glare streaks on or off (a star of streaks from the light above bloom.threshold; "
                         "fed from bloom's bright pass)",
                         &S::enabled)
          .primary(),
      integerParameter<S>("streaks", 4, 6, "", "4 or 6", "the star's streaks (rays from the light)",
                          &S::streaks,
                          [](S& s, const std::string& v) {
                            if (s.streaks != 4 && s.streaks != 6)
                              throw InputError("glare.streaks: expected 4 or 6, got '" + v + "'");
                          })
          .primary(),
      numberParameter<S>("length", 0.005, 0.2, "fraction of the width",
                         "the distance at which a streak falls to 1/e (it ends at 0.2 of the width)", &S::length)
          .primary(),
      numberParameter<S>("intensity", 0, 16, "", "each streak's light per unit of the bright light",
                         &S::intensity)
          .primary(),
      numberParameter<S>("angle", -360, 360, "degrees", "the first streak's angle from the frame's x axis",
                         &S::angle)};
  return table;
}

void GlareSettings::validate() const {
  validateParameters("glare");
  if (streaks != 4 && streaks != 6)
    throw InputError("invalid glare settings: streaks = " + std::to_string(streaks) + ", expected 4 or 6");
}

glm::vec4 glareWeights(int pass, float length) {
  const float steps = length * kGlareStepsPerWidth;
  const float spacing = std::pow(4.0f, static_cast<float>(pass));
  glm::vec4 w(1.0f);
  for (int s = 1; s <= 3; ++s) w[s] = std::exp(-static_cast<float>(s) * spacing / steps);
  return w / (w.x + w.y + w.z + w.w);
}

std::vector<glm::vec2> glareRays(const GlareSettings& settings) {
  std::vector<glm::vec2> out;
  for (int r = 0; r < settings.streaks; ++r) {
    // A streak drawn at angle theta from a light gathers, at each pixel, the light at -theta from it.
    const float a =
        glm::radians(settings.angle + 360.0f * static_cast<float>(r) / static_cast<float>(settings.streaks));
    out.emplace_back(-std::cos(a), -std::sin(a));
  }
  return out;
}

EffectInfo GlareEffect::info() {
  EffectInfo info{"glare",
                  "Glare",
                  true,
                  false,
                  {"glare"},
                  {{kTemporaries[0], "RGB9E5: a streak's passes (1/4 of the frame)", GL_NEAREST, {}},
                   {kTemporaries[1], "as glare-a", GL_NEAREST, {}},
                   {kTemporaries[2], "as glare-a", GL_NEAREST, {}}}};
  info.waitsForFullFrame = true;
  return info;
}

std::vector<ProgramSpec> GlareEffect::programSpecs() { return {spec(false), spec(true)}; }

void GlareEffect::plan(FramePlanner& planner) {
  const GlareSettings settings = planner.settings().of<GlareSettings>();
  if (!settings.enabled) return;
  using Write = PassDecl::Write;
  const bool flare = planner.declares("lens-light");
  PassDecl pass;
  pass.name = "glare";
  pass.reads = {"bloom-bright"};
  if (flare) pass.reads.push_back("lens-light");
  for (const char* temporary : kTemporaries) pass.writes.push_back({temporary, TargetSize::quarter(),
                                                                    Write::Depth::None, ""});
  pass.writes.push_back({"lens-light", TargetSize::quarter(), Write::Depth::None, ""});
  // This frame's settings (the plan is cached: they do not shape it).
  pass.run = [flare](PassContext& context) { render(context, context.settings().of<GlareSettings>(), flare); };
  planner.add(std::move(pass));
}

void GlareEffect::render(const PassContext& context, const GlareSettings& settings, bool flare) {
  const glm::vec2 frame(context.camera().width, context.camera().height);
  const std::vector<glm::vec2> rays = glareRays(settings);
  const gl::Texture2D* sum = flare ? &context.texture("lens-light") : nullptr;
  int sumTemporary = -1;
  for (size_t r = 0; r < rays.size(); ++r) {
    // Two temporaries not holding the sum: the ray's first pass into x, its second into y.
    int x = -1, y = -1;
    for (int t = 0; t < 3; ++t)
      if (t != sumTemporary) (x < 0 ? x : y) = t;
    const gl::Texture2D* source = &context.texture("bloom-bright");
    for (int n = 0; n < kGlarePasses; ++n) {
      const bool last = n == kGlarePasses - 1;
      const bool lastRay = r + 1 == rays.size();
      const std::string target = !last ? kTemporaries[n == 0 ? x : y] : lastRay ? "lens-light" : kTemporaries[x];
      FullscreenDraw draw = context.draw(spec(last), target);
      draw.texture("u_source", *source);
      // 4^n steps of 1/320 of the width along the ray, in uv.
      const float spacing = std::pow(4.0f, static_cast<float>(n)) / kGlareStepsPerWidth;
      draw.set("u_step", spacing * glm::vec2(rays[r].x, rays[r].y * frame.x / frame.y));
      draw.set("u_weights", glareWeights(n, settings.length));
      if (last) {
        draw.set("u_intensity", settings.intensity);
        draw.set("u_hasSum", sum ? 1.0f : 0.0f);
        if (sum) draw.texture("u_sum", *sum);
      }
      draw.draw();
      if (!last) source = &context.writtenTexture(target);
    }
    if (r + 1 < rays.size()) {
      sum = &context.writtenTexture(kTemporaries[x]);
      sumTemporary = x;
    }
  }
}

}  // namespace obscura
