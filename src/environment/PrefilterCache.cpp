#include "environment/PrefilterCache.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#ifndef __EMSCRIPTEN__
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace obscura::prefilter_cache {
namespace {

constexpr char kMagic[8] = {'O', 'B', 'S', 'P', 'F', 'C', '0', '1'};

// FNV-1a, 64 bits: a key, not a checksum against tampering.
struct Hash {
  std::uint64_t value = 14695981039346656037ull;
  void add(const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) value = (value ^ bytes[i]) * 1099511628211ull;
  }
  template <typename T>
  void add(const T& plain) {
    add(&plain, sizeof(plain));
  }
};

// The entry's path, or "" where the cache is off.
std::string entryPath(const EnvironmentImage& image, int samples) {
#ifdef __EMSCRIPTEN__
  (void)image;
  (void)samples;
  return {};
#else
  const char* folder = std::getenv("OBSCURA_PREFILTER_CACHE");
  if (!folder || !*folder) return {};
  char executable[4096];
  const ssize_t length = readlink("/proc/self/exe", executable, sizeof(executable) - 1);
  struct stat info {};
  if (length <= 0 || stat("/proc/self/exe", &info) != 0) return {};
  Hash hash;
  hash.add(executable, static_cast<size_t>(length));
  hash.add(static_cast<std::int64_t>(info.st_size));
  hash.add(static_cast<std::int64_t>(info.st_mtim.tv_sec));
  hash.add(static_cast<std::int64_t>(info.st_mtim.tv_nsec));
  hash.add(image.width);
  hash.add(image.height);
  hash.add(image.texels.data(), image.texels.size() * sizeof(glm::vec3));
  hash.add(samples);
  mkdir(folder, 0777);  // exists already but for the first process: harmless
  char name[32];
  std::snprintf(name, sizeof(name), "/%016llx.prefiltered", static_cast<unsigned long long>(hash.value));
  return std::string(folder) + name;
#endif
}

}  // namespace

bool load(const EnvironmentImage& image, int samples, std::array<EnvironmentImage, kEnvironmentLevels>* levels) {
  const std::string path = entryPath(image, samples);
  if (path.empty()) return false;
  std::ifstream in(path, std::ios::binary);
  char magic[sizeof(kMagic)] = {};
  if (!in.read(magic, sizeof(magic)) || std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) return false;
  std::array<EnvironmentImage, kEnvironmentLevels> read;
  for (int level = 0; level < kEnvironmentLevels; ++level) {
    std::int32_t size[2] = {};
    if (!in.read(reinterpret_cast<char*>(size), sizeof(size))) return false;
    if (size[0] != (kEnvironmentWidth >> level) || size[1] != (kEnvironmentHeight >> level)) return false;
    read[level] = EnvironmentImage(size[0], size[1]);
    const auto bytes = static_cast<std::streamsize>(read[level].texels.size() * sizeof(glm::vec3));
    if (!in.read(reinterpret_cast<char*>(read[level].texels.data()), bytes)) return false;
  }
  *levels = std::move(read);
  return true;
}

void store(const EnvironmentImage& image, int samples, const std::array<EnvironmentImage, kEnvironmentLevels>& levels) {
#ifndef __EMSCRIPTEN__
  const std::string path = entryPath(image, samples);
  if (path.empty()) return;
  const std::string temporary = path + "." + std::to_string(getpid());
  {
    std::ofstream out(temporary, std::ios::binary);
    out.write(kMagic, sizeof(kMagic));
    for (const EnvironmentImage& level : levels) {
      const std::int32_t size[2] = {level.width, level.height};
      out.write(reinterpret_cast<const char*>(size), sizeof(size));
      out.write(reinterpret_cast<const char*>(level.texels.data()),
                static_cast<std::streamsize>(level.texels.size() * sizeof(glm::vec3)));
    }
    if (!out) {
      std::remove(temporary.c_str());
      return;
    }
  }
  std::rename(temporary.c_str(), path.c_str());
#else
  (void)image;
  (void)samples;
  (void)levels;
#endif
}

}  // namespace obscura::prefilter_cache
