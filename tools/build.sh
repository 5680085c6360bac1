#!/usr/bin/env bash
# Builds the native tree (build/). Usage: tools/build.sh [extra cmake arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/lib/ccache.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${ccache_cmake_args[@]}" "$@" >/dev/null
cmake --build build -j"$jobs"
