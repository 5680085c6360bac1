// Renders a scene headlessly (EGL surfaceless, or OSMesa) into a PNG with Obscura's public API.
//   headless_png OUT.png [--scene FILE.glb] [--size WxH] [--backend egl|osmesa] [--set NAME=VALUE ...]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <obscura/headless.h>
#include <obscura/obscura.h>
#include <obscura/offscreen.h>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUT.png [--scene FILE] [--size WxH] [--backend egl|osmesa] [--set NAME=VALUE]\n",
                 argv[0]);
    return 2;
  }
  std::string out = argv[1], scene, backend = "egl";
  int width = 640, height = 360;
  std::vector<std::pair<std::string, std::string>> settings;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string option = argv[i], value = argv[i + 1];
    if (option == "--scene") scene = value;
    else if (option == "--backend") backend = value;
    else if (option == "--size") std::sscanf(value.c_str(), "%dx%d", &width, &height);
    else if (option == "--set" && value.find('=') != std::string::npos)
      settings.emplace_back(value.substr(0, value.find('=')), value.substr(value.find('=') + 1));
    else {
      std::fprintf(stderr, "unknown option %s\n", option.c_str());
      return 2;
    }
  }
  try {
    using namespace obscura::api;
    HeadlessContext context(HeadlessContext::parseBackend(backend));
    Renderer renderer({context.getProcAddress(), false});
    if (!scene.empty()) renderer.setSceneFile(scene);
    for (const auto& [name, value] : settings) renderer.set(name, value);
    OffscreenFramebuffer target(width, height);
    renderer.render(renderer.sceneCamera(width, height), target.framebuffer());
    writePng(out, width, height, target.readRgba());
    const Stats stats = renderer.stats();
    std::printf("obscura %s: %s, %zu triangles, %dx%d in %.1f ms (CPU), passes:", version(),
                renderer.scene().name.c_str(), renderer.scene().triangles, stats.width, stats.height, stats.cpuMs);
    for (const std::string& pass : stats.passesRun) std::printf(" %s", pass.c_str());
    std::printf("\nwrote %s\n", out.c_str());
  } catch (const obscura::api::Error& e) {
    std::fprintf(stderr, "headless_png: %s\n", e.what());
    return 1;
  }
  return 0;
}
