#pragma once
// The environment the lighting reads, by the name lighting.environment gives it ("sky", "uniform" or a file path),
// prepared (its irradiance projected, its specular levels prefiltered: environment/Environment.h) and on the GPU.
//
// Preparing is the dear part (the sky: about a second of CPU at 512 x 256, most of it the 4 million GGX samples of
// the prefilter), so it happens only when the request changes, before the frame is planned: the lighting effect calls
// use() from Effect::prepare, and its plan() and passes read current(). The built-in environments (the sky for a sun
// direction, the uniform furnace) are prepared once per process and shared by every cache: each Renderer starts with
// the sky, and the tests make hundreds of Renderers.
#include <memory>
#include <string>

#include <glm/vec3.hpp>

#include "environment/Environment.h"

namespace obscura {

class EnvironmentCache {
 public:
  // `layout`: where the GPU copies keep their levels (GpuEnvironment::layoutFor); `filtering`: which levels the
  // hardware's filter reads (PrefilteredEnvironment::of); `desktopGl`: the context's half-float format
  // (GpuEnvironment). Prepares nothing yet.
  EnvironmentCache(EnvironmentLayout layout, EnvironmentFiltering filtering, bool desktopGl)
      : layout_(layout), filtering_(filtering), desktopGl_(desktopGl) {}

  // Makes `name` the environment in use: "sky" (ProceduralSky with its sun towards `skySunDirection`, world space,
  // unit), "uniform" (radiance 1 everywhere) or the path of an equirectangular .hdr or RGBE .png. Does nothing when
  // that is the one in use. A file that cannot be read throws InputError once: the environment in use stays (the
  // default sky when there was none), and the same name is not tried again until another one was asked for, so a
  // stale path (a page URL naming a file dropped in an earlier visit) does not fail every frame.
  void use(const std::string& name, const glm::vec3& skySunDirection);

  // The environment in use; use() must have been called once.
  const GpuEnvironment& current() const;
  EnvironmentLayout layout() const { return layout_; }

 private:
  EnvironmentLayout layout_;
  EnvironmentFiltering filtering_;
  bool desktopGl_;
  std::string name_;       // the name the environment in use was asked for by
  glm::vec3 skySun_{0.0f};  // the sky's sun direction, when name_ is "sky"
  std::unique_ptr<GpuEnvironment> current_;
};

}  // namespace obscura
