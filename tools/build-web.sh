#!/usr/bin/env bash
# Builds the browser version (build-web/, Emscripten): the demo page lands in build-web/site.
# Usage: tools/build-web.sh [extra cmake arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/lib/ccache.sh
# Debian's emscripten runs its JavaScript optimiser on node and needs Debian's node modules (acorn) on the path.
export NODE_PATH="${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs"
jobs=$(nproc 2>/dev/null || echo 2)
# The npm glTF geometry decoders the page runs (web/package.json, pinned by web/package-lock.json).
if [ ! -d web/node_modules/draco3d ] || [ ! -d web/node_modules/meshoptimizer ] ||
   [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then
  (cd web && npm ci --no-audit --no-fund)
fi
emcmake cmake -S . -B build-web -DCMAKE_BUILD_TYPE=Release "${ccache_cmake_args[@]}" "$@" >/dev/null
cmake --build build-web -j"$jobs"
