#include "environment/EnvironmentCache.h"

#include <list>
#include <memory>
#include <mutex>
#include <utility>

#include "base/Error.h"
#include "environment/BuiltinSky.h"

namespace obscura {
namespace {

// An environment ready for the GPU: what GpuEnvironment uploads.
struct Prepared {
  PrefilteredEnvironment specular;
  ShIrradiance sh;
  Prepared(const EnvironmentImage& image, EnvironmentFiltering filtering)
      : specular(PrefilteredEnvironment::of(image, 4096, filtering)), sh(ShIrradiance::project(image)) {}
  explicit Prepared(PreparedEnvironment made) : specular(std::move(made.specular)), sh(made.irradiance) {}
};

// The built-in environments prepared so far in this process, most recently used first. Eight of them (about 4 MB
// each) cover the default sky, the furnace and a few suns a page's slider moved to.
class BuiltinEnvironments {
 public:
  static BuiltinEnvironments& instance() {
    static BuiltinEnvironments builtins;
    return builtins;
  }

  std::shared_ptr<const Prepared> get(const std::string& name, const glm::vec3& skySun,
                                      EnvironmentFiltering filtering) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto it = entries_.begin(); it != entries_.end(); ++it)
        if (it->name == name && (name != "sky" || it->skySun == skySun) && it->filtering == filtering) {
          entries_.splice(entries_.begin(), entries_, it);
          return entries_.front().prepared;
        }
    }
    // Prepared outside the lock: a second thread asking for the same one prepares it twice, which is only time. The
    // default sun's sky was prefiltered when the library was built (environment/BuiltinSky.h): milliseconds, where
    // another sun's takes about a second of CPU.
    std::shared_ptr<const Prepared> prepared;
    if (name == "sky" && skySun == builtinSkySun())
      prepared = std::make_shared<const Prepared>(builtinSky(filtering));
    else
      prepared = std::make_shared<const Prepared>(name == "sky" ? ProceduralSky{skySun}.image(kEnvironmentWidth,
                                                                                               kEnvironmentHeight)
                                                                : uniformEnvironment(glm::vec3(1.0f)),
                                                  filtering);
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.push_front({name, skySun, filtering, prepared});
    if (entries_.size() > kCapacity) entries_.pop_back();
    return prepared;
  }

 private:
  static constexpr size_t kCapacity = 8;
  struct Entry {
    std::string name;
    glm::vec3 skySun;
    EnvironmentFiltering filtering;
    std::shared_ptr<const Prepared> prepared;
  };
  std::mutex mutex_;
  std::list<Entry> entries_;
};

}  // namespace

void EnvironmentCache::use(const std::string& name, const glm::vec3& skySunDirection) {
  const bool sky = name == "sky";
  if (current_ && name_ == name && (!sky || skySun_ == skySunDirection)) return;
  name_ = name;
  skySun_ = skySunDirection;
  if (sky || name == "uniform") {
    const std::shared_ptr<const Prepared> prepared =
        BuiltinEnvironments::instance().get(name, skySunDirection, filtering_);
    current_ = std::make_unique<GpuEnvironment>(layout_, prepared->specular, prepared->sh, desktopGl_);
    return;
  }
  EnvironmentImage image;
  try {
    image = loadEnvironmentImage(name);
  } catch (const InputError&) {
    // name_ keeps the file's name, so the next frame asking for it again does not retry it.
    if (!current_) {
      const std::shared_ptr<const Prepared> fallback =
          BuiltinEnvironments::instance().get("sky", skySunDirection, filtering_);
      current_ = std::make_unique<GpuEnvironment>(layout_, fallback->specular, fallback->sh, desktopGl_);
    }
    throw;
  }
  const Prepared prepared(image, filtering_);
  current_ = std::make_unique<GpuEnvironment>(layout_, prepared.specular, prepared.sh, desktopGl_);
}

const GpuEnvironment& EnvironmentCache::current() const {
  if (!current_) throw PipelineError("EnvironmentCache::current() before any use()");
  return *current_;
}

}  // namespace obscura
