// obscura-gltf-check: loads glTF files with Obscura's loader alone (no GL) and prints, per file, one JSON line:
// {"file": PATH, "loaded": true|false, "refusal": the one-line refusal or "", "warnings": [...], "triangles": N}.
// tools/gltf-validator/conformance.mjs sets it beside the Khronos glTF-Validator's report (docs/robustness.md).
//
// Usage: obscura-gltf-check FILE...   (exit status 0 whatever the files hold and however they are named; 2 for a
// usage error)
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "base/Error.h"
#include "scene/GltfLoader.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: obscura-gltf-check FILE...\n";
    return 2;
  }
  for (int i = 1; i < argc; ++i) {
    nlohmann::json line = {
        {"file", argv[i]}, {"loaded", false}, {"refusal", ""}, {"warnings", nlohmann::json::array()}};
    try {
      obscura::GltfLoadReport report;
      const obscura::Scene scene = obscura::loadGltfFile(argv[i], &report);
      line["loaded"] = true;
      line["warnings"] = report.warnings;
      line["triangles"] = scene.triangleCount();
    } catch (const obscura::InputError& e) {
      line["refusal"] = e.what();
    }
    // A path or a refusal may hold bytes that are not UTF-8 (a file name, a file's own text quoted in the
    // refusal): they print as U+FFFD rather than end the run with nlohmann's type_error.
    std::cout << line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  }
  return 0;
}
