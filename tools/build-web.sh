#!/usr/bin/env bash
# Builds the browser version (build-web/, Emscripten): the demo page lands in build-web/site.
# Usage: tools/build-web.sh [extra cmake arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
# Debian's emscripten runs its JavaScript optimiser on node and needs Debian's node modules (acorn) on the path.
export NODE_PATH="${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs"
jobs=$(nproc 2>/dev/null || echo 2)
emcmake cmake -S . -B build-web -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build-web -j"$jobs"
