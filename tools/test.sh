#!/usr/bin/env bash
# Runs every test on a fresh Debian machine: installs what is missing, builds, then runs the whole suite.
set -euo pipefail
cd "$(dirname "$0")/.."

tools/install-deps.sh
tools/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc 2>/dev/null || echo 2)"
tools/test-sanitizers.sh
tools/fuzz-gltf.sh 60
