// libFuzzer target for scene loading: any bytes, as .glb or .gltf, with a side file, must either load into a
// drawable (and poseable) scene or be refused with an InputError. Anything else (a crash, a sanitizer report,
// another exception, a hang) is a bug. Seeded with Debian's assimp-testmodels glTF files and tests/fuzz/seeds
// (tools/fuzz-gltf.sh; tests/fuzz/seeds/README.md lists the input forms).
#include <cstddef>
#include <cstdint>
#include <map>
#include <string_view>
#include <vector>

#include "base/Error.h"
#include "scene/Animation.h"
#include "scene/GltfLoader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::uint8_t> bytes(data, data + size);
  // A dropped .gltf may name a buffer file: where the input names "buffer.bin", its second half is offered as that
  // file, so external buffers get exercised too (tests/fuzz/seeds/external-buffer.glb is laid out for it). Only
  // there: a copy of half of every input is work the others need not do.
  std::map<std::string, std::vector<std::uint8_t>> sideFiles;
  if (std::string_view(reinterpret_cast<const char*>(data), size).find("buffer.bin") != std::string_view::npos)
    sideFiles.emplace("buffer.bin", std::vector<std::uint8_t>(data + size / 2, data + size));
  obscura::GltfLimits limits;
  limits.maxAccessorElements = 1u << 20;  // keep each run small; the limit logic itself is what is exercised
  limits.maxSceneTriangles = 1u << 20;
  limits.maxImageDimension = 1024;
  try {
    const obscura::Scene scene = obscura::loadGltfMemory(bytes, "fuzz-input", sideFiles, nullptr, limits);
    // Touch what the renderer will touch: the rest bounds, and a pose of every animation at once, looping and not,
    // baked on the CPU (skinning and morphing read joint indices, weights and targets the loader vouched for).
    volatile float sink = scene.worldBounds().radius();
    if (scene.animated()) {
      obscura::PoseOptions options;
      options.animation = obscura::AnimationChoice::all();
      for (const double time : {0.37, 1e6}) {
        options.loop = time < 1.0;
        sink = obscura::posedScene(scene, obscura::evaluatePose(scene, time, options)).worldBounds().radius();
      }
    }
    (void)sink;
  } catch (const obscura::InputError&) {
    // Refused with a message: the expected outcome for most inputs.
  }
  return 0;
}
