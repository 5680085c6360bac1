#include "apps/RenderCommandLine.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "base/Error.h"
#include "base/Text.h"
#include "gl/RenderTarget.h"
#include "platform/FinishPassTimer.h"
#include "renderer/AccumulationReference.h"
#include "scene/ImageIo.h"

namespace obscura {

std::string renderUsage() {
  std::string usage =
      "usage: obscura-render [--scene FILE [--scene-scale S]] [--time T] [--animation A] [--fps F] [--frames N]\n"
      "                      [--camera CAM.json | --fit | --camera-node C] [--orthographic] [--size WxH]\n"
      "                      [--view V [--compare SWITCH]] [--out FILE.png]\n"
      "                      [--NAME VALUE | --EFFECT | --no-EFFECT ...] [--preset P] [--bench N]\n"
      "                      [--backend osmesa|egl]\n"
      "                      [--accumulate N [--shutter S] [--supersample K]] [--aperture N [--supersample K]]\n"
      "\n"
      "Renders a glTF 2.0 scene (default: the built-in scene) headless: the G-buffer, Scalable Ambient Obscurance,\n"
      "lighting, fog, bloom, tone mapping and FXAA, or one of the frame's targets.\n"
      + sceneInputUsage() +
      "  --view V          " + parse::joinChoices(frameViewNames(), " | ") + "\n"
      "                    (default final; a target's view shows its values as they are: no tone curve, no FXAA)\n"
      "  --compare SWITCH  what --view split compares, off left | on right (default ao): " +
      parse::joinChoices(splitSwitches(), ", ") + "\n"
      "  --fps F           frames per second (default 60): the frame before --time is 1/F earlier, which motion\n"
      "                    vectors measure from\n"
      "  --frames N        draw N frames, at T, T + 1/F, ... (the history carrying over), and write the last\n"
      "  --at K NAME=V     from frame K of --frames on (0: the first), parameter NAME is V (a change within the\n"
      "                    sequence: --auto-exposure --frames 70 --at 10 lighting.sun-intensity=50); repeatable\n"
      "  --accumulate N    write the brute-force reference instead of the frame: the mean of N renders with the\n"
      "                    temporal effects off, at times spread over [T - S/(2F), T + S/(2F)]\n"
      "  --shutter S       the reference's shutter, a fraction of the frame interval (default 0.5; 0: one instant)\n"
      "  --supersample K   the reference's sub-frames rendered at K times the size, box-downsampled (default 1)\n"
      "  --aperture N      write depth of field's reference instead of the frame: the mean of N pinhole renders\n"
      "                    from points on the lens of the --dof.* parameters, each sheared to keep the focus plane\n"
      "                    (the tone-mapped light, without the display stages after the curve: compare it with\n"
      "                    frames rendered --no-dither)\n"
      "  --out FILE        output PNG (default obscura.png)\n"
      "  --bench N         render N frames and print per-pass milliseconds (glFinish-bounded)\n"
      "  --backend B       osmesa (default) or egl (Mesa EGL surfaceless, a true GLES 2 context)\n"
      "  --no-EFFECT       shorthand for --EFFECT off (--no-ao, --no-tonemap, --no-fxaa; --no-blur: --ao.blur off)\n"
      "  --EFFECT          with no value (last, or before another option): --EFFECT on (--bloom --fog)\n"
      "\n" + defaultAoRadiusUsage("--ao.radius") +
      "\nParameters (--NAME VALUE; in brackets, older names still accepted):\n";
  std::string effect = "-";
  for (const ParameterInfo& p : RenderSettings::parameters()) {
    if (p.effect != effect) {
      effect = p.effect;
      usage += effect.empty() ? std::string("  frame:\n") : "  " + effectEntry(effect).info.title + ":\n";
    }
    const std::string name = p.name + (p.alias.empty() ? "" : " (--" + p.alias + ")");
    char line[300];
    std::snprintf(line, sizeof line, "    --%-44s %-30s %s\n", name.c_str(), p.range.c_str(), p.help.c_str());
    usage += line;
  }
  return usage;
}

RenderOptions parseRenderCommandLine(const std::vector<std::string>& args) {
  RenderOptions options;
  bool compareGiven = false;
  auto isParameter = [](const std::string& name) { return RenderSettings::find(name) != nullptr; };
  auto isSwitch = [](const std::string& name) {
    const ParameterInfo* p = RenderSettings::find(name);
    return p && p->kind == ParameterKind::Switch;
  };
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw InputError(arg + ": missing value");
      return args[++i];
    };
    if (arg == "--help" || arg == "-h") options.help = true;
    else if (options.input.parseOption(args, i)) continue;
    else if (arg == "--view") {
      try {
        options.view.name = parseView(value()).name;
      } catch (const InputError& e) {
        throw InputError(std::string("--") + e.what());
      }
    } else if (arg == "--compare") {
      try {
        options.view.compare = parseCompare(value());
        compareGiven = true;
      } catch (const InputError& e) {
        throw InputError(std::string("--") + e.what());
      }
    } else if (arg == "--out") {
      options.outPath = value();
      if (options.outPath.empty()) throw InputError("--out: empty file name");
    } else if (arg == "--fps") options.fps = parseNumber(arg, value(), 0.01, 10000.0);
    else if (arg == "--frames") options.frames = parseCount(arg, value(), 100000);
    else if (arg == "--at") {
      RenderOptions::Change change;
      change.frame = static_cast<int>(parseNumber(arg, value(), 0.0, 100000.0));
      const std::string assignment = value();
      const size_t equals = assignment.find('=');
      if (equals == std::string::npos) throw InputError("--at: expected NAME=VALUE, got '" + assignment + "'");
      change.name = assignment.substr(0, equals);
      change.value = assignment.substr(equals + 1);
      try {
        RenderSettings(options.settings).set(change.name, change.value);  // refused now, not at frame K
      } catch (const InputError& e) {
        throw InputError(std::string("--at: ") + e.what());
      }
      options.changes.push_back(change);
    }
    else if (arg == "--accumulate") options.accumulate = parseCount(arg, value(), 4096);
    else if (arg == "--shutter") options.shutter = parseNumber(arg, value(), 0.0, 1.0);
    else if (arg == "--supersample") options.supersample = parseCount(arg, value(), 16);
    else if (arg == "--aperture") options.aperture = parseCount(arg, value(), 4096);
    else if (arg == "--bench") options.benchFrames = parseCount(arg, value(), 100000);
    else if (arg == "--backend") {
      try {
        options.backend = parseBackend(value());
      } catch (const InputError& e) {
        throw InputError(std::string("--") + e.what());
      }
    } else if (arg.rfind("--no-", 0) == 0 && isSwitch(arg.substr(5))) {
      options.settings.set(arg.substr(5), "off");  // --no-ao, --no-tonemap, --no-fxaa, --no-blur
    } else if (arg.rfind("--", 0) == 0 && isSwitch(arg.substr(2)) &&
               (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0)) {
      options.settings.set(arg.substr(2), "on");  // a bare switch: --bloom --fog
    } else if (arg.rfind("--", 0) == 0 && isParameter(arg.substr(2))) {
      const std::string name = arg.substr(2);
      try {
        options.settings.set(name, value());
      } catch (const InputError& e) {
        throw InputError(std::string("--") + e.what());
      }
      if (RenderSettings::canonicalName(name) == "ao.radius") options.radiusGiven = true;
    } else {
      throw InputError("unknown option '" + arg + "' (see --help)");
    }
  }
  options.input.check();
  if (compareGiven && options.view != View::Split) throw InputError("--compare: only --view split compares");
  for (const RenderOptions::Change& change : options.changes)
    if (change.frame >= options.frames)
      throw InputError("--at " + std::to_string(change.frame) + ": the sequence has only " +
                       std::to_string(options.frames) + " frame(s) (--frames N)");
  if (options.accumulate > 0 && (options.view != View::Final || options.benchFrames > 0 || options.frames != 1))
    throw InputError("--accumulate: writes the final image's reference; it takes no --view, --frames or --bench");
  if (options.aperture > 0 && (options.accumulate > 0 || options.shutter != 0.5))
    throw InputError("--aperture: the lens's reference is of one instant; it takes no --accumulate or --shutter");
  if (options.aperture > 0 && (options.view != View::Final || options.benchFrames > 0 || options.frames != 1))
    throw InputError("--aperture: writes the final image's reference; it takes no --view, --frames or --bench");
  if (options.accumulate == 0 && options.aperture == 0 && (options.shutter != 0.5 || options.supersample != 1))
    throw InputError("--shutter and --supersample shape the reference: they need --accumulate N (or --aperture N)");
  return options;
}

int runRender(const RenderOptions& options) {
  if (options.help) {
    std::cout << renderUsage();
    return 0;
  }
  try {
    // Input first, so a bad file is reported before any GL work.
    const SceneInput::Loaded input = options.input.load();
    const Scene& scene = input.scene;
    const Camera& camera = input.camera;

    HeadlessContext context(options.backend);
    if (std::max(camera.width, camera.height) > context.caps().maxRenderSize())
      throw InputError("--size: " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                       " exceeds this context's limit of " + std::to_string(context.caps().maxRenderSize()) +
                       " per side");
    options.input.printWarnings("obscura-render", input.warnings);  // every input checked: a refusal stays one line
    RenderSettings settings = options.settings;
    if (!options.radiusGiven) settings.ao().radius = chooseDefaultAoRadius("obscura-render", "--ao.radius", scene);
    RendererOptions rendererOptions;
    rendererOptions.checkGlErrors = true;
    Renderer renderer(context.caps(), rendererOptions);
    renderer.setScene(scene);
    const gl::RenderTarget output("output", camera.width, camera.height, GL_NEAREST,
                                  gl::RenderTarget::Depth::Renderbuffer, context.caps().depth24,
                                  context.caps().packedDepthStencil);  // the stencil: FxaaEffect.h
    OutputTarget target;
    target.framebuffer = output.framebuffer();
    target.width = camera.width;
    target.height = camera.height;

    if (options.accumulate > 0) {
      AccumulationOptions accumulation;
      accumulation.time = options.input.time;
      accumulation.fps = options.fps;
      accumulation.shutter = options.shutter;
      accumulation.samples = options.accumulate;
      accumulation.supersample = options.supersample;
      accumulation.animation = input.animation;
      // A scene camera moves over the shutter interval as the animation moves it.
      writePng(options.outPath,
               accumulateShutter(renderer, [&](double t) { return input.cameraAt(t); }, settings, accumulation)
                   .toImage());
      return 0;
    }

    if (options.aperture > 0) {
      ApertureOptions aperture;
      aperture.samples = options.aperture;
      aperture.supersample = options.supersample;
      aperture.time = options.input.time;
      aperture.animation = input.animation;
      writePng(options.outPath, accumulateAperture(renderer, camera, settings, aperture).toImage());
      return 0;
    }

    // The frames of the sequence: frame k at T + k / F, its previous frame 1 / F earlier (for the first, a frame
    // that is not drawn). The first also warms up shader compilation.
    const double interval = 1.0 / options.fps;
    FrameOptions frame;
    frame.animation = input.animation;
    frame.sceneCamera = input.sceneCamera;
    frame.allowCheapFrame = false;  // the file is the frame asked for, even with resolution.quick-start on
    for (int k = 0; k < options.frames; ++k) {
      frame.time = options.input.time + k * interval;
      frame.previousTime = frame.time - interval;
      for (const RenderOptions::Change& change : options.changes)
        if (change.frame == k) settings.set(change.name, change.value);
      renderer.render(camera, settings, options.view, target, frame);
    }
    if (options.benchFrames > 0) {
      // Each measured frame is the last frame again (the same time and motion).
      FinishPassTimer timer;
      frame.timer = &timer;
      const auto start = std::chrono::steady_clock::now();
      for (int k = 0; k < options.benchFrames; ++k) renderer.render(camera, settings, options.view, target, frame);
      glFinish();
      const double total = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      std::printf("obscura-render --bench: %dx%d, %d frames, view %s, %d AO samples, backend %s (%s)\n", camera.width,
                  camera.height, options.benchFrames, options.view.name.c_str(), settings.ao().samples,
                  backendName(options.backend), context.caps().renderer.c_str());
      std::printf("%-10s %10s %10s %10s\n", "pass", "mean ms", "min ms", "max ms");
      double sumOfMeans = 0.0;
      for (const std::string& pass : framePassNames()) {
        const std::vector<double>& s = timer.samples(pass);
        if (s.empty()) {
          // A pass whose work another one did this frame (the tone curve applied by the lighting) is named, so a
          // reader looking for it finds where its time went.
          for (const PlannedPass& planned : renderer.lastPlan().passes())
            if (planned.live && std::count(planned.absorbed.begin(), planned.absorbed.end(), pass))
              std::printf("%-10s %10s   (done by %s)\n", pass.c_str(), "-", planned.decl.name.c_str());
          continue;
        }
        double sum = 0.0;
        for (double v : s) sum += v;
        const double mean = sum / static_cast<double>(s.size());
        sumOfMeans += mean;
        std::printf("%-10s %10.3f %10.3f %10.3f\n", pass.c_str(), mean, *std::min_element(s.begin(), s.end()),
                    *std::max_element(s.begin(), s.end()));
      }
      std::printf("%-10s %10.3f   (sum of pass means; wall clock per frame %.3f ms)\n", "total", sumOfMeans,
                  total / options.benchFrames);
      const GpuScene::Counts counts = renderer.gpuScene().lastDrawCounts();
      std::printf("triangles  %ld   (drawn by the last geometry pass; gbuffer.lod draws coarser levels)\n",
                  counts.triangles);
      std::printf("draws      %d   (its draw calls; %d instances in static batches)\n", counts.drawCalls,
                  counts.batchedInstances);
    }

    Image image;
    image.width = camera.width;
    image.height = camera.height;
    image.rgba = output.readRgba();
    writePng(options.outPath, image);
    return 0;
  } catch (const InputError& e) {
    std::cerr << "obscura-render: " << e.what() << "\n";
    return 2;
  } catch (const GlError& e) {
    std::cerr << "obscura-render: GL error: " << e.what() << "\n";
    return 1;
  } catch (const PipelineError& e) {
    std::cerr << "obscura-render: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace obscura
