#!/usr/bin/env bash
# Runs every test on a fresh Debian machine: installs what is missing, builds the native and the web versions,
# installs the browser tests', the npm package tests', the browser benchmark's and the glTF-Validator's npm packages
# (tests/browser, tests/npm-package, tools/browser-bench and tools/gltf-validator, from their package-lock.json
# files), then runs the whole suite: the glTF corpus against the Khronos glTF-Validator, CPU and
# GPU unit tests, the command line, the desktop viewer under Xvfb, the installed C++ package and its examples, the web
# page and the npm package in headless Chromium and the browser benchmark's smoke run.
set -euo pipefail
cd "$(dirname "$0")/.."

tools/install-deps.sh
# Warnings are errors here, so the tree that passes CI builds clean with g++ and with Emscripten's clang.
tools/build.sh -DOBSCURA_WERROR=ON
tools/build-web.sh -DOBSCURA_WERROR=ON
(cd tests/browser && npm ci --no-audit --no-fund --loglevel=error)
(cd tools/browser-bench && npm ci --no-audit --no-fund --loglevel=error)
(cd tests/npm-package && npm ci --no-audit --no-fund --loglevel=error)
(cd tools/gltf-validator && npm ci --no-audit --no-fund --loglevel=error)
ctest --test-dir build --output-on-failure -j"$(nproc 2>/dev/null || echo 2)"
tools/test-sanitizers.sh
tools/fuzz-gltf.sh 60
