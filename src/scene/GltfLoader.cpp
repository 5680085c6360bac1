#include "scene/GltfLoader.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <string_view>

#include <nlohmann/json.hpp>
#include <stb_image.h>
#include <tiny_gltf.h>

#include "base/Error.h"
#include "scene/GltfCompression.h"
#include "scene/GltfReading.h"
#include "scene/GltfSchema.h"
#include "scene/MeshDetail.h"

namespace obscura {
namespace {

// What the loader does with each extension a file may use (docs/robustness.md, "Extensions", lists them):
// implemented; or not implemented but the file is still drawn without it (a material's extra lobe, a choice of
// variants), with a one-line warning naming it; anything else a file requires is refused in one line. The compression
// extensions are implemented where the build has their decoders (GltfCompression.h).
enum class Support { Implemented, DrawnWithout };
struct ExtensionSupport {
  Support support;
  const char* without;  // DrawnWithout: what the drawing lacks
};
const std::map<std::string, ExtensionSupport>& knownExtensions() {
  static const std::map<std::string, ExtensionSupport> table = {
      {"KHR_materials_unlit", {Support::Implemented, ""}},
      {"KHR_materials_emissive_strength", {Support::Implemented, ""}},
      {"KHR_materials_ior", {Support::Implemented, ""}},
      {"KHR_materials_specular", {Support::Implemented, ""}},
      {"KHR_materials_clearcoat", {Support::Implemented, ""}},
      {"KHR_materials_transmission", {Support::Implemented, ""}},
      {"KHR_texture_transform", {Support::Implemented, ""}},
      {"KHR_lights_punctual", {Support::Implemented, ""}},
      {"KHR_materials_volume", {Support::DrawnWithout, "transmission is thin-walled (no thickness, no attenuation)"}},
      {"KHR_materials_sheen", {Support::DrawnWithout, "no sheen lobe"}},
      {"KHR_materials_iridescence", {Support::DrawnWithout, "no thin-film iridescence"}},
      {"KHR_materials_anisotropy", {Support::DrawnWithout, "isotropic highlights"}},
      {"KHR_materials_dispersion", {Support::DrawnWithout, "no dispersion"}},
      {"KHR_materials_diffuse_transmission", {Support::DrawnWithout, "no diffuse transmission"}},
      {"KHR_materials_variants", {Support::DrawnWithout, "the default materials only"}},
      {"KHR_animation_pointer", {Support::DrawnWithout, "only node channels animate"}},
      {"KHR_xmp_json_ld", {Support::DrawnWithout, "metadata not read"}},
      {"KHR_materials_pbrSpecularGlossiness",
       {Support::DrawnWithout, "the metallic-roughness fallback material is drawn"}},
  };
  return table;
}

struct ImageLoadContext {
  const GltfLimits* limits;
  const tinygltf::Model* model;  // being filled by tinygltf: its buffers and buffer views are loaded before images
};

// tinygltf image callback: decodes to RGBA8 after checking the size, so a huge image header cannot exhaust memory.
bool loadImageRgba8(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                    const unsigned char* bytes, int size, void* userData) {
  const auto* context = static_cast<const ImageLoadContext*>(userData);
  const GltfLimits* limits = context->limits;
  // tinygltf 2.7 hands over an image's buffer view without checking that it lies inside its buffer (found by
  // fuzzing: a heap overflow in the PNG decoder). Check it here, before any byte is read.
  if (image->bufferView >= 0) {
    const auto& views = context->model->bufferViews;
    const auto& buffers = context->model->buffers;
    const bool inside = static_cast<size_t>(image->bufferView) < views.size() &&
                        views[static_cast<size_t>(image->bufferView)].buffer >= 0 &&
                        static_cast<size_t>(views[static_cast<size_t>(image->bufferView)].buffer) < buffers.size() &&
                        std::uint64_t(views[static_cast<size_t>(image->bufferView)].byteOffset) +
                                views[static_cast<size_t>(image->bufferView)].byteLength <=
                            buffers[static_cast<size_t>(views[static_cast<size_t>(image->bufferView)].buffer)]
                                .data.size();
    if (!inside) {
      if (err) *err += "image " + std::to_string(index) + ": its bufferView lies outside its buffer\n";
      return false;
    }
  }
  if (size <= 0) {
    if (err) *err += "image " + std::to_string(index) + ": no image data\n";
    return false;
  }
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes, size, &width, &height, &channels)) {
    if (err) *err += "image " + std::to_string(index) + ": unknown or corrupt image format\n";
    return false;
  }
  if (width < 1 || height < 1 || width > limits->maxImageDimension || height > limits->maxImageDimension) {
    if (err)
      *err += "image " + std::to_string(index) + " is " + std::to_string(width) + "x" + std::to_string(height) +
              ", over the limit of " + std::to_string(limits->maxImageDimension) + " per side\n";
    return false;
  }
  unsigned char* pixels = stbi_load_from_memory(bytes, size, &width, &height, &channels, 4);
  if (!pixels) {
    if (err) *err += "image " + std::to_string(index) + ": " + stbi_failure_reason() + "\n";
    return false;
  }
  image->width = width;
  image->height = height;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image.assign(pixels, pixels + size_t(width) * height * 4);
  stbi_image_free(pixels);
  return true;
}

// File access for tinygltf: on disk relative to the .gltf, or from the in-memory side files (web drops).
struct FileResolver {
  std::string baseDir;
  const std::map<std::string, std::vector<std::uint8_t>>* sideFiles = nullptr;
  std::uint64_t maxBytes = 0;
};

std::string relativeTo(const FileResolver& r, const std::string& path) {
  if (!r.baseDir.empty() && path.rfind(r.baseDir, 0) == 0) return path.substr(r.baseDir.size());
  return path;
}

bool fileExists(const std::string& path, void* user) {
  const auto* r = static_cast<const FileResolver*>(user);
  if (r->sideFiles) return r->sideFiles->count(relativeTo(*r, path)) != 0;
  return std::ifstream(path, std::ios::binary).good();
}

std::string expandPath(const std::string& path, void*) { return path; }

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const auto* r = static_cast<const FileResolver*>(user);
  if (r->sideFiles) {
    auto it = r->sideFiles->find(relativeTo(*r, path));
    if (it == r->sideFiles->end()) {
      if (err) *err += "file not provided: " + path + "\n";
      return false;
    }
    out->assign(it->second.begin(), it->second.end());
    return true;
  }
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) {
    if (err) *err += "cannot open " + path + "\n";
    return false;
  }
  const std::streamoff size = file.tellg();
  if (size < 0 || static_cast<std::uint64_t>(size) > r->maxBytes) {
    if (err) *err += path + " is larger than the limit\n";
    return false;
  }
  out->resize(static_cast<size_t>(size));
  file.seekg(0);
  file.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size));
  return file.good() || file.eof();
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not supported\n";
  return false;
}

// First line of a multi-line tinygltf message, trimmed.
std::string firstLine(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line.empty() ? "unknown error" : line;
}

// A required extension is implemented (compression and quantization where the build decodes them), can be drawn
// without, or the file is refused.
void refuseUnlessSupported(const gltf::Refusal& refuse, const std::string& extension) {
  if (knownExtensions().count(extension)) return;
  std::string why;
  if (compressionExtensionSupported(extension, &why)) return;
  refuse(why.empty() ? "requires unsupported extension " + extension : why);
}

// One warning per extension the file uses that is not implemented, naming it (once per file, whatever uses it).
void warnUnimplementedExtensions(const tinygltf::Model& model, GltfLoadReport& report) {
  std::set<std::string> used(model.extensionsUsed.begin(), model.extensionsUsed.end());
  used.insert(model.extensionsRequired.begin(), model.extensionsRequired.end());
  for (const std::string& extension : used) {
    const auto known = knownExtensions().find(extension);
    if (known != knownExtensions().end()) {
      if (known->second.support == Support::DrawnWithout)
        report.warnings.push_back("extension " + extension + " is not implemented: " + known->second.without);
      continue;
    }
    std::string why;
    if (compressionExtensionSupported(extension, &why)) continue;
    // A compression extension without its decoder in this build, used but not required: the fallback is drawn.
    report.warnings.push_back("extension " + extension +
                              (why.empty() ? " is not implemented: ignored"
                                           : " cannot be decoded by this build: its uncompressed fallback is drawn"));
  }
}

// What the loader reads from the JSON apart from tinygltf: the asset's extensionsRequired (a file that needs, say,
// Draco has accessors without buffer views, and the user should hear about the extension rather than about
// accessor 0), per animation the channels whose target has no node (KHR_animation_pointer's), which tinygltf 2.7 drops
// with only an error line, and the properties of the wrong type (GltfSchema.h), which it skips without a word.
struct DocumentFacts {
  std::vector<std::string> requiredExtensions;
  std::vector<int> channelsWithoutNode;  // per animation
  std::vector<std::string> schemaMismatches;  // GltfSchema.h: what tinygltf would skip without a word
};

DocumentFacts scanDocument(const nlohmann::json& document) {
  DocumentFacts out;
  if (!document.is_object()) return out;
  out.schemaMismatches = gltf::schemaMismatches(document);
  if (document.contains("extensionsRequired") && document["extensionsRequired"].is_array())
    for (const auto& name : document["extensionsRequired"])
      if (name.is_string()) out.requiredExtensions.push_back(name.get<std::string>());
  if (document.contains("animations") && document["animations"].is_array()) {
    for (const auto& animation : document["animations"]) {
      int count = 0;
      if (animation.is_object() && animation.contains("channels") && animation["channels"].is_array())
        for (const auto& channel : animation["channels"])
          if (channel.is_object() && channel.contains("target") && channel["target"].is_object() &&
              !channel["target"].contains("node"))
            ++count;
      out.channelsWithoutNode.push_back(count);
    }
  }
  return out;
}

// tinygltf 2.7 checks a .glb's BIN chunk against the file's length without the chunk's own 8-byte header, and then
// copies a buffer from up to 8 bytes past the end of the file (found by the fuzzer: a heap-buffer-overflow in
// tinygltf::ParseBuffer). The chunk is checked here first, where tinygltf would accept it.
void checkGlbBinChunk(const gltf::Refusal& refuse, const std::vector<std::uint8_t>& glb) {
  if (glb.size() < 20 || std::memcmp(glb.data(), "glTF", 4) != 0) return;
  std::uint32_t length = 0, jsonLength = 0;
  std::memcpy(&length, glb.data() + 8, 4);
  std::memcpy(&jsonLength, glb.data() + 12, 4);
  const std::uint64_t binChunk = 20ull + jsonLength;
  if (length > glb.size() || binChunk + 12 > length) return;  // tinygltf refuses these, or there is no BIN chunk
  std::uint32_t binLength = 0;
  std::memcpy(&binLength, glb.data() + binChunk, 4);
  if (binChunk + 8 + binLength > length)
    refuse("the BIN chunk's " + std::to_string(binLength) + " bytes run past the end of the file (" +
           std::to_string(length) + " bytes)");
}

Scene loadWithResolver(const std::vector<std::uint8_t>& bytes, const std::string& name, FileResolver resolver,
                       GltfLoadReport* report, const GltfLimits& limits) {
  const gltf::Refusal refuse(name);
  if (bytes.empty()) refuse("file is empty");
  if (bytes.size() > limits.maxFileBytes)
    refuse("file is larger than " + std::to_string(limits.maxFileBytes) + " bytes");
  if (bytes.size() > 0xFFFFFFFFull) refuse("file is larger than 4 GiB");

  // The JSON is parsed twice, here and by tinygltf (the facts above, and the compressed file's mending, share this
  // parse: the fuzzer's executions per minute follow the parses, docs/robustness.md).
  const std::string_view json = gltfJsonText(bytes);
  nlohmann::json parsed = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  const DocumentFacts facts = scanDocument(parsed);
  for (const std::string& ext : facts.requiredExtensions) refuseUnlessSupported(refuse, ext);
  // What tinygltf 2.7 refuses in compressed files, mended (GltfCompression.h); `parsed` is changed.
  const std::vector<std::uint8_t> prepared = prepareCompressedDocument(bytes, parsed);
  const std::vector<std::uint8_t>& document = prepared.empty() ? bytes : prepared;
  checkGlbBinChunk(refuse, document);

  tinygltf::TinyGLTF gltf;
  resolver.maxBytes = limits.maxFileBytes;
  gltf.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &writeWholeFile, &resolver});
  tinygltf::Model model;
  ImageLoadContext imageContext{&limits, &model};
  gltf.SetImageLoader(&loadImageRgba8, &imageContext);

  std::string err, warn;
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  bool ok = false;
  try {
    ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn, document.data(),
                                            static_cast<unsigned>(document.size()), resolver.baseDir)
                : gltf.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(document.data()),
                                           static_cast<unsigned>(document.size()), resolver.baseDir);
  } catch (const std::exception& e) {
    refuse(std::string("malformed glTF: ") + e.what());
  }
  if (!ok) refuse(firstLine(err.empty() ? warn : err));

  GltfLoadReport localReport;
  GltfLoadReport& out = report ? *report : localReport;
  if (!warn.empty()) out.warnings.push_back(firstLine(warn));
  for (size_t a = 0; a < facts.channelsWithoutNode.size(); ++a)
    if (facts.channelsWithoutNode[a] > 0)
      out.warnings.push_back("animation " + std::to_string(a) + ": " + std::to_string(facts.channelsWithoutNode[a]) +
                             " channels have no target node (KHR_animation_pointer?); skipped");
  if (!facts.schemaMismatches.empty())
    out.warnings.push_back("does not follow the glTF schema: " + facts.schemaMismatches.front() +
                           (facts.schemaMismatches.size() > 1
                                ? " (and " + std::to_string(facts.schemaMismatches.size() - 1) + " more)"
                                : std::string()) +
                           "; ignored");
  for (const std::string& ext : model.extensionsRequired) refuseUnlessSupported(refuse, ext);
  warnUnimplementedExtensions(model, out);
  decompressGltfModel(model, name, limits, out);

  gltf::LoadBudget budget;
  const gltf::LoaderContext ctx{model, limits, refuse, out, budget};
  Scene scene;
  scene.name = name;
  gltf::loadMaterials(ctx, scene);
  const std::vector<std::vector<int>> copies = gltf::loadNodes(ctx, scene);
  gltf::loadAnimations(ctx, copies, scene);
  // A valid file may have nothing to draw (an empty scene): it loads, and says so.
  if (scene.instances.empty() && scene.lineInstances.empty())
    out.warnings.push_back("its default scene has no triangle, line or point geometry: nothing is drawn");
  const Bounds bounds = scene.worldBounds();
  const glm::vec3 extent = bounds.max - bounds.min;
  if (!std::isfinite(extent.x + extent.y + extent.z)) refuse("scene bounds are not finite after node transforms");
  addDetailLevels(scene);
  return scene;
}

}  // namespace

Scene loadGltfFile(const std::string& path, GltfLoadReport* report, const GltfLimits& limits) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) throw InputError(path + ": cannot open file");
  const std::streamoff size = file.tellg();
  if (size < 0) throw InputError(path + ": cannot read file");
  if (static_cast<std::uint64_t>(size) > limits.maxFileBytes)
    throw InputError(path + ": file is larger than " + std::to_string(limits.maxFileBytes) + " bytes");
  std::vector<std::uint8_t> bytes(static_cast<size_t>(size));
  file.seekg(0);
  file.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (!file) throw InputError(path + ": cannot read file");
  FileResolver resolver;
  const size_t slash = path.find_last_of('/');
  resolver.baseDir = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
  return loadWithResolver(bytes, path, resolver, report, limits);
}

Scene loadGltfMemory(const std::vector<std::uint8_t>& bytes, const std::string& name,
                     const std::map<std::string, std::vector<std::uint8_t>>& sideFiles, GltfLoadReport* report,
                     const GltfLimits& limits) {
  FileResolver resolver;
  resolver.sideFiles = &sideFiles;
  return loadWithResolver(bytes, name, resolver, report, limits);
}

}  // namespace obscura