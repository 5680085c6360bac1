#pragma once
// Prefiltered environments kept on disk between processes of one build, for the test runs: every test process that
// makes a Renderer prefilters the sky (PrefilteredEnvironment::of, about half a second of CPU each, two seconds
// sanitized), and ctest runs a process per suite, the command-line tests one per tool run. Off unless the
// OBSCURA_PREFILTER_CACHE environment variable names a folder (ctest sets it to the build tree's test-cache/); an
// entry is keyed by the source image, the sample count and the running executable (its path, size and time), so a
// rebuilt binary never reads what another build computed. Native only: the web build has no cache.
#include <array>

#include "environment/Environment.h"

namespace obscura::prefilter_cache {

// The levels a process of this executable stored for this image and sample count, if any (false otherwise, and
// where the cache is off or an entry is unreadable).
bool load(const EnvironmentImage& image, int samples, std::array<EnvironmentImage, kEnvironmentLevels>* levels);
// Stores them (written to a temporary file and renamed, so a process reading at the same time sees all or nothing).
void store(const EnvironmentImage& image, int samples, const std::array<EnvironmentImage, kEnvironmentLevels>& levels);

}  // namespace obscura::prefilter_cache
